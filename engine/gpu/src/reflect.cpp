// SPIR-V reflection (reflect.hpp). One pass over the instructions collects the decorations,
// types and variables; a second step turns the variables of set 0 into binding types and
// sizes the push-constant block. Opcodes and enumerants: the SPIR-V specification, 1.6.
#include "lantern/gpu/reflect.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <string>

namespace lantern::gpu {
namespace {

// Opcodes.
constexpr std::uint32_t op_type_int = 21, op_type_float = 22, op_type_vector = 23, op_type_matrix = 24,
                        op_type_image = 25, op_type_sampler = 26, op_type_sampled_image = 27, op_type_array = 28,
                        op_type_runtime_array = 29, op_type_struct = 30, op_type_pointer = 32, op_constant = 43,
                        op_variable = 59, op_decorate = 71, op_member_decorate = 72, op_type_bool = 20;
// Decorations.
constexpr std::uint32_t dec_block = 2, dec_buffer_block = 3, dec_array_stride = 6, dec_matrix_stride = 7,
                        dec_binding = 33, dec_descriptor_set = 34, dec_offset = 35;
// Storage classes.
constexpr std::uint32_t sc_uniform_constant = 0, sc_uniform = 2, sc_push_constant = 9, sc_storage_buffer = 12;
constexpr std::uint32_t dim_buffer = 5;

struct Type {
    std::uint32_t opcode = 0;
    std::vector<std::uint32_t> operands; // the words after the result id
};

struct Module {
    std::map<std::uint32_t, Type> types;
    std::map<std::uint32_t, std::uint32_t> constants; // id -> first value word (32-bit integers)
    std::map<std::uint32_t, std::map<std::uint32_t, std::uint32_t>> decorations; // id -> decoration -> value
    std::map<std::uint32_t, std::map<std::uint32_t, std::uint32_t>> member_offsets; // struct -> member -> offset
    std::map<std::uint32_t, std::map<std::uint32_t, std::uint32_t>> member_matrix_strides;
    struct Variable {
        std::uint32_t id, pointer_type, storage_class;
    };
    std::vector<Variable> variables;

    bool decorated(std::uint32_t id, std::uint32_t decoration) const {
        auto it = decorations.find(id);
        return it != decorations.end() && it->second.count(decoration);
    }
    std::optional<std::uint32_t> decoration(std::uint32_t id, std::uint32_t decoration) const {
        auto it = decorations.find(id);
        if (it == decorations.end()) return std::nullopt;
        auto d = it->second.find(decoration);
        if (d == it->second.end()) return std::nullopt;
        return d->second;
    }
    const Type* type(std::uint32_t id) const {
        auto it = types.find(id);
        return it == types.end() ? nullptr : &it->second;
    }
};

Error bad(const std::string& what) { return make_error("SPIR-V reflection: " + what, 1); }

Result<Module> parse(std::span<const std::uint32_t> words) {
    if (words.size() < 5 || words[0] != 0x07230203u) return bad("not SPIR-V (no magic number)");
    Module m;
    for (std::size_t i = 5; i < words.size();) {
        const std::uint32_t count = words[i] >> 16, opcode = words[i] & 0xffffu;
        if (count == 0 || i + count > words.size()) return bad("truncated instruction at word " + std::to_string(i));
        const std::span<const std::uint32_t> ops = words.subspan(i + 1, count - 1);
        switch (opcode) {
        case op_type_bool:
        case op_type_int:
        case op_type_float:
        case op_type_vector:
        case op_type_matrix:
        case op_type_image:
        case op_type_sampler:
        case op_type_sampled_image:
        case op_type_array:
        case op_type_runtime_array:
        case op_type_struct:
        case op_type_pointer:
            if (ops.empty()) return bad("type without a result id");
            m.types[ops[0]] = Type{opcode, std::vector<std::uint32_t>(ops.begin() + 1, ops.end())};
            break;
        case op_constant:
            if (ops.size() >= 3) m.constants[ops[1]] = ops[2];
            break;
        case op_variable:
            if (ops.size() < 3) return bad("OpVariable with too few operands");
            m.variables.push_back({ops[1], ops[0], ops[2]});
            break;
        case op_decorate:
            if (ops.size() < 2) return bad("OpDecorate with too few operands");
            m.decorations[ops[0]][ops[1]] = ops.size() >= 3 ? ops[2] : 0;
            break;
        case op_member_decorate:
            if (ops.size() < 3) return bad("OpMemberDecorate with too few operands");
            if (ops[2] == dec_offset && ops.size() >= 4) m.member_offsets[ops[0]][ops[1]] = ops[3];
            if (ops[2] == dec_matrix_stride && ops.size() >= 4) m.member_matrix_strides[ops[0]][ops[1]] = ops[3];
            break;
        default: break;
        }
        i += count;
    }
    return m;
}

// A push-constant block is at most a few hundred bytes on any device; the reader refuses
// one over 64 KiB, so no size or offset it computes can wrap around.
constexpr std::uint64_t max_block_bytes = 65536;

Result<std::uint32_t> checked_size(std::uint64_t bytes) {
    if (bytes > max_block_bytes)
        return bad("a push-constant block over " + std::to_string(max_block_bytes) + " bytes");
    return std::uint32_t(bytes);
}

// Bytes a value of `type_id` occupies in an explicitly laid-out block (std140/std430 as
// decorated): scalars, vectors, matrices (columns x MatrixStride), arrays (length x
// ArrayStride) and structs (last member's offset + size). `matrix_stride` comes from the
// member decoration of the enclosing struct. Computed in 64 bits and refused over
// max_block_bytes, so every member's offset + size fits the block's size.
Result<std::uint32_t> size_of(const Module& m, std::uint32_t type_id, std::uint32_t matrix_stride, int depth = 0) {
    if (depth > 16) return bad("types nested too deeply");
    const Type* t = m.type(type_id);
    if (!t) return bad("unknown type id " + std::to_string(type_id));
    switch (t->opcode) {
    case op_type_bool: return 4u;
    case op_type_int:
    case op_type_float:
        if (t->operands.empty()) return bad("scalar type without a width");
        return checked_size(t->operands[0] / 8);
    case op_type_vector: {
        if (t->operands.size() < 2) return bad("vector type without a count");
        auto component = size_of(m, t->operands[0], 0, depth + 1);
        if (!component) return component.error();
        return checked_size(std::uint64_t(*component) * t->operands[1]);
    }
    case op_type_matrix: {
        if (t->operands.size() < 2) return bad("matrix type without a column count");
        if (matrix_stride == 0) {
            auto column = size_of(m, t->operands[0], 0, depth + 1);
            if (!column) return column.error();
            matrix_stride = *column;
        }
        return checked_size(std::uint64_t(matrix_stride) * t->operands[1]);
    }
    case op_type_array: {
        if (t->operands.size() < 2) return bad("array type without a length");
        auto length = m.constants.find(t->operands[1]);
        if (length == m.constants.end()) return bad("array length is not a constant");
        const auto stride = m.decoration(type_id, dec_array_stride);
        if (!stride) return bad("array without an ArrayStride in a push-constant block");
        return checked_size(std::uint64_t(*stride) * length->second);
    }
    case op_type_struct: {
        std::uint64_t end = 0;
        auto offsets = m.member_offsets.find(type_id);
        for (std::uint32_t k = 0; k < t->operands.size(); ++k) {
            if (offsets == m.member_offsets.end() || !offsets->second.count(k))
                return bad("struct member " + std::to_string(k) + " without an Offset");
            std::uint32_t stride = 0;
            if (auto s = m.member_matrix_strides.find(type_id); s != m.member_matrix_strides.end() && s->second.count(k))
                stride = s->second.at(k);
            auto member = size_of(m, t->operands[k], stride, depth + 1);
            if (!member) return member.error();
            end = std::max(end, std::uint64_t(offsets->second.at(k)) + *member);
        }
        return checked_size(end);
    }
    default: return bad("a type of opcode " + std::to_string(t->opcode) + " in a push-constant block");
    }
}

// Appends the members of struct `type_id` (at `base`), flattening nested structs.
Result<void> flatten(const Module& m, std::uint32_t type_id, std::uint32_t base, std::vector<PushMember>& out, int depth = 0) {
    if (depth > 16) return bad("types nested too deeply");
    const Type* t = m.type(type_id);
    if (!t || t->opcode != op_type_struct) return bad("not a struct");
    auto offsets = m.member_offsets.find(type_id);
    for (std::uint32_t k = 0; k < t->operands.size(); ++k) {
        if (offsets == m.member_offsets.end() || !offsets->second.count(k))
            return bad("struct member " + std::to_string(k) + " without an Offset");
        const std::uint32_t at = base + offsets->second.at(k);
        const Type* member = m.type(t->operands[k]);
        if (!member) return bad("unknown member type");
        if (member->opcode == op_type_struct) {
            if (auto ok = flatten(m, t->operands[k], at, out, depth + 1); !ok) return ok;
            continue;
        }
        std::uint32_t stride = 0;
        if (auto s = m.member_matrix_strides.find(type_id); s != m.member_matrix_strides.end() && s->second.count(k))
            stride = s->second.at(k);
        auto size = size_of(m, t->operands[k], stride, depth + 1);
        if (!size) return size.error();
        if (*size == 0) return bad("push-constant member " + std::to_string(k) + " has no size");
        ScalarKind kind = ScalarKind::other;
        if (member->opcode == op_type_float && *size == 4) kind = ScalarKind::f32;
        if (member->opcode == op_type_int && *size == 4 && member->operands.size() >= 2)
            kind = member->operands[1] ? ScalarKind::i32 : ScalarKind::u32;
        out.push_back({at, *size, kind});
    }
    return {};
}

Result<BindingType> binding_type(const Module& m, const Module::Variable& v, const Type& pointee, std::uint32_t pointee_id,
                                 std::uint32_t binding) {
    const std::string where = "binding " + std::to_string(binding) + ": ";
    if (pointee.opcode == op_type_array || pointee.opcode == op_type_runtime_array)
        return bad(where + "arrays of descriptors are not supported");
    switch (v.storage_class) {
    case sc_storage_buffer: return BindingType::storage_buffer;
    case sc_uniform:
        if (m.decorated(pointee_id, dec_buffer_block)) return BindingType::storage_buffer;
        if (m.decorated(pointee_id, dec_block)) return BindingType::uniform_buffer;
        return bad(where + "a Uniform variable that is neither Block nor BufferBlock");
    case sc_uniform_constant:
        if (pointee.opcode == op_type_sampled_image) {
            const Type* image = pointee.operands.empty() ? nullptr : m.type(pointee.operands[0]);
            if (image && image->opcode == op_type_image && image->operands.size() >= 6 && image->operands[1] == dim_buffer)
                return BindingType::uniform_texel_buffer; // samplerBuffer
            return BindingType::combined_image_sampler;
        }
        if (pointee.opcode == op_type_image) {
            if (pointee.operands.size() < 6) return bad(where + "malformed OpTypeImage");
            const bool buffer = pointee.operands[1] == dim_buffer;
            const std::uint32_t sampled = pointee.operands[5];
            if (buffer && sampled == 1) return BindingType::uniform_texel_buffer; // textureBuffer
            if (buffer && sampled == 2) return BindingType::storage_texel_buffer; // imageBuffer
            return bad(where + "an image kind Lantern has no binding type for (only texel buffers and sampler2D)");
        }
        return bad(where + "a UniformConstant of an unsupported type (opcode " + std::to_string(pointee.opcode) + ")");
    default: return bad(where + "unsupported storage class " + std::to_string(v.storage_class));
    }
}

} // namespace

Result<ShaderLayout> reflect_spirv(std::span<const std::uint32_t> words) {
    auto parsed = parse(words);
    if (!parsed) return parsed.error();
    const Module& m = *parsed;
    ShaderLayout out;
    std::map<std::uint32_t, BindingType>& bindings = out.bindings;
    bool push_block_seen = false;
    for (const Module::Variable& v : m.variables) {
        const Type* pointer = m.type(v.pointer_type);
        if (!pointer || pointer->opcode != op_type_pointer || pointer->operands.size() < 2)
            return bad("variable " + std::to_string(v.id) + " is not of a pointer type");
        const std::uint32_t pointee_id = pointer->operands[1];
        const Type* pointee = m.type(pointee_id);
        if (!pointee) return bad("variable " + std::to_string(v.id) + " points to an unknown type");
        if (v.storage_class == sc_push_constant) {
            if (push_block_seen) return bad("more than one push-constant block");
            push_block_seen = true;
            if (pointee->opcode != op_type_struct) return bad("a push-constant variable that is not a block");
            auto size = size_of(m, pointee_id, 0);
            if (!size) return size.error();
            out.push_constant_size = (*size + 3) & ~3u;
            if (auto ok = flatten(m, pointee_id, 0, out.push_constant_members); !ok) return ok.error();
            continue;
        }
        const auto binding = m.decoration(v.id, dec_binding);
        if (!binding) continue; // inputs, outputs, workgroup memory, ...
        if (const auto set = m.decoration(v.id, dec_descriptor_set); set.value_or(0) != 0)
            return bad("binding " + std::to_string(*binding) + " is in descriptor set " + std::to_string(*set) +
                       "; Lantern's pipelines use set 0 only");
        auto type = binding_type(m, v, *pointee, pointee_id, *binding);
        if (!type) return type.error();
        if (auto [it, added] = bindings.emplace(*binding, *type); !added && it->second != *type)
            return bad("binding " + std::to_string(*binding) + " declared twice with different types");
    }
    return out;
}

Result<std::vector<BindingType>> ShaderLayout::dense_bindings() const {
    std::vector<BindingType> out;
    for (const auto& [binding, type] : bindings) {
        if (binding != out.size())
            return bad("bindings must be dense from 0: binding " + std::to_string(out.size()) + " is missing");
        out.push_back(type);
    }
    return out;
}

Result<ShaderLayout> merge_layouts(const ShaderLayout& a, const ShaderLayout& b) {
    ShaderLayout out = a;
    for (const auto& [binding, type] : b.bindings) {
        if (auto [it, added] = out.bindings.emplace(binding, type); !added && it->second != type)
            return bad("binding " + std::to_string(binding) + " is " + to_string(it->second) + " in one stage and " +
                       to_string(type) + " in the other");
    }
    if (b.push_constant_size > out.push_constant_size) {
        out.push_constant_size = b.push_constant_size;
        out.push_constant_members = b.push_constant_members;
    }
    return out;
}

} // namespace lantern::gpu
