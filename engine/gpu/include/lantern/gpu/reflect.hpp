// A minimal SPIR-V reader: the descriptor bindings and the push-constant block a shader
// declares, so pipeline layouts come from the shaders themselves instead of hand-written
// tables that repeat every GLSL binding (docs/gpu.md, "Layouts from the shaders").
//
// Reads what Lantern's pipelines use: one descriptor set (set 0) with dense bindings of the
// BindingType kinds, and at most one push-constant block of scalars, vectors, matrices,
// arrays and structs. Anything else (another set, a descriptor array, an image kind Lantern
// has no BindingType for) is an error naming it. Safe on untrusted words: every length and
// id is checked, so malformed SPIR-V is an error, never a crash.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gpu/pipeline.hpp"

#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace lantern::gpu {

// One member of the push-constant block, nested structs flattened in declaration order.
enum class ScalarKind : std::uint8_t { f32, i32, u32, other }; // other: vectors, matrices, arrays, ...
struct PushMember {
    std::uint32_t offset = 0; // bytes from the block's start
    std::uint32_t size = 0;
    ScalarKind kind = ScalarKind::other;
    friend bool operator==(const PushMember&, const PushMember&) = default;
};

struct ShaderLayout {
    std::map<std::uint32_t, BindingType> bindings; // set 0, by binding number
    std::uint32_t push_constant_size = 0;           // bytes (the block's end, rounded up to 4); 0: none
    std::vector<PushMember> push_constant_members;  // flattened, in order

    // The bindings as the pipeline contract wants them: dense from 0 (an error names the
    // first missing binding).
    Result<std::vector<BindingType>> dense_bindings() const;
};

Result<ShaderLayout> reflect_spirv(std::span<const std::uint32_t> words);

// The layout two stages share (vertex + fragment): the union of their bindings (a binding
// both declare must have one type) and the larger push-constant block.
Result<ShaderLayout> merge_layouts(const ShaderLayout& a, const ShaderLayout& b);

} // namespace lantern::gpu
