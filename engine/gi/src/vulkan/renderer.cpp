// The Vulkan GI renderer: creation, the textures the plan needs, uploads of walls and
// lights, and recording the planned rows (renderer.hpp). Timestamps: renderer_timings.cpp;
// read back and the copy baseline: renderer_read_back.cpp.
#include "lantern/gi/vulkan/renderer.hpp"

#include "lantern/gi/vulkan/pass_recorder.hpp"
#include "vulkan/renderer_internal.hpp"

#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace lantern::gi::vk {
namespace {

VkFormat view_format(TexFormat f, bool rgba8) {
    if (rgba8) return VK_FORMAT_R8G8B8A8_UNORM; // also the 32-bit heat tap masks (read as R32_UINT)
    switch (f) {
    case TexFormat::r8: return VK_FORMAT_R8_UNORM;
    case TexFormat::rg8: return VK_FORMAT_R8G8_UNORM;
    case TexFormat::rgba16f: return VK_FORMAT_R16G16B16A16_SFLOAT;
    }
    return VK_FORMAT_UNDEFINED;
}

// Whether the driver's fma rounds once (gi_probe_fma.comp against the host's std::fma), so
// that gi_exact.glsl's residuals may use it (EXACT_ROUNDING 2) rather than Dekker's product.
// Vulkan lets fma round twice, as lavapipe's does. Cases whose product needs 47 bits: an
// unfused fma gives 0 for each.
bool driver_fuses_fma(gpu::Device& device) {
    std::vector<glm::vec4> entries;
    for (int k = 1; k <= 64; ++k) {
        const float a = 1.0f + std::ldexp(float(k), -23), b = 1.0f - std::ldexp(float(2 * k + 1), -23);
        entries.emplace_back(a, b, -(a * b), 0.0f);
    }
    gpu::ComputePipelineDesc desc;
    desc.spirv = lantern_gi_shaders_spirv("gi_probe_fma.comp");
    desc.bindings = {gpu::BindingType::storage_buffer};
    desc.name = "gi_probe_fma";
    gpu::ComputePipeline pipeline = device.create_compute_pipeline(desc);
    gpu::BufferDesc bd;
    bd.size = entries.size() * sizeof(glm::vec4);
    bd.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    bd.name = "gi fma probe";
    gpu::Buffer buffer = device.create_buffer(bd);
    device.upload(buffer, std::as_bytes(std::span<const glm::vec4>(entries)));
    gpu::CommandList cmd = device.begin("gi fma probe");
    cmd.bind(pipeline);
    cmd.push_descriptors(gpu::DescriptorWrites().storage_buffer(0, buffer));
    cmd.dispatch(1);
    device.wait(device.submit(std::move(cmd)));
    const std::vector<std::byte> bytes = device.read_back(buffer);
    if (bytes.size() < entries.size() * sizeof(glm::vec4)) return false;
    std::vector<glm::vec4> got(entries.size());
    std::memcpy(got.data(), bytes.data(), got.size() * sizeof(glm::vec4));
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const glm::vec4 e = entries[i];
        if (got[i].w != std::fma(e.x, e.y, e.z)) return false;
    }
    return true;
}

} // namespace

void check_params_layout(const char* shader, std::span<const std::uint32_t> spirv,
                         std::span<const gpu::ScalarKind> kinds) {
    auto layout = gpu::reflect_spirv(spirv);
    LANTERN_VERIFY(layout.ok(), layout.ok() ? "" : layout.error().message.c_str());
    using gpu::PushMember;
    using gpu::ScalarKind;
    std::vector<PushMember> expected = {{0, 16, ScalarKind::other}, {16, 16, ScalarKind::other},
                                        {32, 16, ScalarKind::other}, {48, 16, ScalarKind::other}};
    for (std::uint32_t i = 0; i < kinds.size(); ++i) expected.push_back({pass_params_offset + 4 * i, 4, kinds[i]});
    expected.push_back({96, 16, ScalarKind::other});
    LANTERN_VERIFY(layout->push_constant_members == expected && layout->push_constant_size == sizeof(GiPassParams),
                   (std::string(shader) +
                    ": its push-constant block does not match its C++ GiPush<Params> (vulkan/pass_params.hpp and the "
                    "pass's row): size, order or scalar types of the parameters differ")
                       .c_str());
}

Renderer::Renderer(gpu::Device& device) : device_(device), pipelines_(new Pipelines) { pipelines_->device = &device; }
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::create(gpu::Device& device, const RendererOptions& options) {
    if (!device.supports_buffer_format(VK_FORMAT_R8_UINT, VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT))
        return make_error("GI backend: " + device.name() + " cannot read R8_UINT uniform texel buffers", 1);
    std::unique_ptr<Renderer> r(new Renderer(device));
    // Defaults measured on lavapipe (docs/gi.md): CPU drivers like a block of 4x4 texels
    // per invocation; GPUs get one row of 4 and wider groups.
    const bool cpu = device.type() == gpu::DeviceType::cpu;
    r->block_h_ = options.block_h ? options.block_h : (cpu ? 4u : 1u);
    r->group_x_ = options.group_x ? options.group_x : (cpu ? 8u : 16u);
    r->group_y_ = options.group_y ? options.group_y : (cpu ? 8u : 8u);
    r->dirty_bins_ = options.dirty_bins;
    r->proxy_list_bytes_ = options.proxy_list_bytes;
    // The direct pass repacks its workgroup's shadow texels through shared memory (4 bytes a
    // texel): keep it within the 16 KiB every Vulkan device offers.
    const std::uint64_t shared_bytes = std::uint64_t(r->group_x_) * r->group_y_ * 4u * r->block_h_ * 4u;
    if (shared_bytes > 16384)
        return make_error("GI backend: a workgroup of " + std::to_string(r->group_x_) + " x " +
                              std::to_string(r->group_y_) + " blocks of 4 x " + std::to_string(r->block_h_) +
                              " texels is too large (the direct pass needs " + std::to_string(shared_bytes) +
                              " bytes of shared memory; at most 16384, 4096 texels)",
                          1);
    // gi_exact.glsl: CPU drivers divide and take roots with the processor's IEEE
    // instructions; GPUs' may err by ULPs, corrected with fma residuals where it is fused.
    r->pipelines_->exact_rounding = cpu ? 0u : (driver_fuses_fma(device) ? 2u : 1u);
    if (device.capabilities().timestamps) {
        for (int i = 0; i < num_query_sets; ++i) {
            auto q = device.create_timestamp_queries(2 * pass_count + 8, "gi passes"); // passes and parts
            if (!q) return q.error();
            r->queries_.push_back(QuerySet{std::move(q.value()), {}, false, 0});
        }
    }
    gpu::BufferDesc ubo;
    ubo.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    ubo.size = sizeof(GpuPointLight) * max_gpu_lights;
    ubo.name = "gi lights";
    r->lights_ = device.create_buffer(ubo);
    ubo.size = sizeof(GpuShadowProxy) * max_gpu_proxies;
    ubo.name = "gi proxies";
    r->proxies_ = device.create_buffer(ubo);
    ubo.size = sizeof(GpuDirectionalLight) * max_gpu_suns;
    ubo.name = "gi suns";
    r->suns_ = device.create_buffer(ubo);
    return r;
}

void Renderer::ensure_texture(Tex t, TexFormat format, int width, int height, bool rgba8) {
    GpuTexture& g = textures_[int(t)];
    if (g.buffer && g.width == width && g.height == height && g.format == format) return;
    g = GpuTexture{};
    g.format = format;
    g.rgba8 = rgba8;
    g.width = width;
    g.height = height;
    g.pitch = pitch_of(width);
    g.serial = ++texture_serial_;
    const VkDeviceSize texel_bytes = rgba8 ? 4 : VkDeviceSize(bytes_per_texel(format));
    gpu::BufferDesc desc;
    desc.size = std::max<VkDeviceSize>(16, (VkDeviceSize(g.pitch) * VkDeviceSize(height) * texel_bytes + 15) & ~VkDeviceSize(15));
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    desc.name = tex_name(t);
    g.buffer = device_.create_buffer(desc);
    g.view = device_.create_buffer_view(g.buffer, view_format(format, rgba8), 0, VK_WHOLE_SIZE, tex_name(t));
    if (rgba8) g.view_u32 = device_.create_buffer_view(g.buffer, VK_FORMAT_R32_UINT, 0, VK_WHOLE_SIZE, tex_name(t));
}

void Renderer::drop_texture(Tex t) {
    if (textures_[int(t)].buffer) textures_[int(t)] = GpuTexture{};
}

Result<void> Renderer::prepare(const FrameInputs& in, const PassPlan& plan) {
    if (auto ok = check_texture_budget(in, plan, TextureStorage::gpu); !ok) return ok;
    const GiWindow& w = in.window;
    const auto& caps = device_.capabilities();
    const std::uint64_t texels = std::uint64_t(pitch_of(w.width)) * std::uint64_t(w.height);
    if (texels > caps.max_texel_buffer_elements || texels * 8 > caps.max_storage_buffer_range)
        return make_error("GI window of " + std::to_string(w.width) + " x " + std::to_string(w.height) +
                              " texels does not fit the device (" + device_.name() + ": at most " +
                              std::to_string(std::min<std::uint64_t>(caps.max_texel_buffer_elements,
                                                                     caps.max_storage_buffer_range / 8)) +
                              " texels per texture); lower gi.resolution or gi.padding",
                          1);
    const std::uint64_t groups_x = (std::uint64_t(pitch_of(w.width)) / 4 + group_x_ - 1) / group_x_;
    const std::uint64_t groups_y = (std::uint64_t(w.height) + block_h_ * group_y_ - 1) / (block_h_ * group_y_);
    if (groups_x > caps.max_compute_workgroup_count[0] || groups_y > caps.max_compute_workgroup_count[1])
        return make_error("GI window of " + std::to_string(w.width) + " x " + std::to_string(w.height) +
                              " texels needs more workgroups than the device allows", 1);
    if (in.point_lights.size() + in.emissive_lights.size() > std::size_t(max_gpu_lights))
        return make_error("GI backend: " + std::to_string(in.point_lights.size() + in.emissive_lights.size()) +
                              " point and emissive lights in the window; one pass takes at most " +
                              std::to_string(max_gpu_lights), 2);
    if (in.directional_lights.size() > std::size_t(max_gpu_suns))
        return make_error("GI backend: at most " + std::to_string(max_gpu_suns) + " directional lights", 2);
    if (in.proxies.size() > std::size_t(max_gpu_proxies))
        return make_error("GI backend: at most " + std::to_string(max_gpu_proxies) + " shadow proxies", 2);

    // Exactly the textures the planned rows write (pass table); the others are released.
    const TexSet written = textures_written(in, plan);
    for (int t = 0; t < registered_texture_count(); ++t) {
        const TextureRow& row = texture_row(Tex(t));
        if (!written.has(row.id)) {
            drop_texture(row.id);
            continue;
        }
        const glm::ivec2 size = texture_size(row.id, in);
        ensure_texture(row.id, row.format, size.x, size.y, row.words32);
    }
    return {};
}

void Renderer::upload_walls(gpu::CommandList& cmd, const WallView& walls) {
    const std::size_t cells = std::size_t(walls.width) * std::size_t(walls.height);
    const VkDeviceSize size = std::max<VkDeviceSize>(16, (VkDeviceSize(cells) + 15) & ~VkDeviceSize(15));
    if (!walls_ || walls_.size() != size) {
        gpu::BufferDesc desc;
        desc.size = size;
        desc.usage = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
        desc.name = "gi walls";
        walls_ = device_.create_buffer(desc);
        walls_view_ = device_.create_buffer_view(walls_, VK_FORMAT_R8_UINT, 0, VK_WHOLE_SIZE, "gi walls");
    }
    if (cells) {
        cmd.upload(walls_, 0, bytes_of(walls.cells, cells));
        wall_bytes_uploaded_ += cells;
    }
    cmd.barrier_transfer_to_compute();
}

void Renderer::update_walls(gpu::CommandList& cmd, const WallView& walls, std::span<const WallRange> ranges) {
    LANTERN_ASSERT(walls_ && walls_.size() >= VkDeviceSize(walls.width) * VkDeviceSize(walls.height),
                   "update_walls before upload_walls, or after the grid size changed");
    for (const WallRange& r : ranges) {
        LANTERN_ASSERT(r.end <= std::size_t(walls.width) * std::size_t(walls.height) && r.begin < r.end,
                       "wall range outside the grid");
        cmd.upload(walls_, r.begin, bytes_of(walls.cells + r.begin, r.end - r.begin));
        wall_bytes_uploaded_ += r.end - r.begin;
    }
    if (!ranges.empty()) cmd.barrier_transfer_to_compute();
}

void Renderer::upload_lights(gpu::CommandList& cmd, const FrameInputs& in) {
    std::vector<GpuPointLight> lights(in.point_lights);
    lights.insert(lights.end(), in.emissive_lights.begin(), in.emissive_lights.end());
    if (!lights.empty()) cmd.update_buffer(lights_, 0, bytes_of(lights.data(), lights.size() * sizeof(GpuPointLight)));
    if (!in.proxies.empty())
        cmd.update_buffer(proxies_, 0, bytes_of(in.proxies.data(), in.proxies.size() * sizeof(GpuShadowProxy)));
    if (!in.directional_lights.empty())
        cmd.update_buffer(suns_, 0,
                          bytes_of(in.directional_lights.data(), in.directional_lights.size() * sizeof(GpuDirectionalLight)));
    cmd.barrier_transfer_to_compute();
}

GiPassParams Renderer::params(const FrameInputs& in, int width, int height) const {
    GiPassParams p{};
    const CameraView& v = in.window.view;
    p.camera_view = glm::vec4(v.min_x, v.min_z, v.width, v.height);
    p.size = glm::ivec4(width, height, pitch_of(width), in.window.resolution);
    p.grid = glm::ivec4(in.walls.width, in.walls.height, in.walls.origin.x, in.walls.origin.y);
    p.grid_phase = glm::ivec4(in.walls.phase, 0, 0);
    p.counts = glm::ivec4(int(in.point_lights.size()), int(in.emissive_lights.size()),
                          int(in.directional_lights.size()), int(in.proxies.size()));
    return p;
}

glm::uvec2 Renderer::block_groups(int width, int height) const {
    const std::uint32_t blocks_x = std::uint32_t(pitch_of(width) / 4);
    const std::uint32_t blocks_y = (std::uint32_t(height) + block_h_ - 1) / block_h_;
    return {(blocks_x + group_x_ - 1) / group_x_, (blocks_y + group_y_ - 1) / group_y_};
}

void Renderer::dispatch_blocks(gpu::CommandList& cmd, int width, int height) {
    const glm::uvec2 groups = block_groups(width, height);
    cmd.dispatch(groups.x, groups.y);
}

void Renderer::clear(gpu::CommandList& cmd, Tex t) { cmd.fill_buffer(textures_[int(t)].buffer, 0); }

void Renderer::record(gpu::CommandList& cmd, Pass pass, const FrameInputs& in, const PassPlan& plan) {
    QuerySet* set = (!queries_.empty() && frame_slot_ >= 0) ? &queries_[std::size_t(frame_slot_)] : nullptr;
    std::uint32_t region = 0;
    if (set) {
        region = set->queries.begin(cmd, pass_name(pass));
        set->passes.push_back({pass});
    }
    const PassRow* row = find_row(method(in.settings.method), pass);
    LANTERN_ASSERT(row && row->record, "record() of a pass that is not in the frame's gi.method");
    const int iterations = row->iteration_count(in);
    for (int i = 0; i < iterations; ++i) {
        PassRecorder recorder(*this, cmd, in, plan, *row, i);
        row->record(recorder);
    }
    if (set) set->queries.end(cmd, region);
}

void Renderer::record_plan(gpu::CommandList& cmd, const FrameInputs& in, const PassPlan& plan) {
    record_plan(cmd, in, plan, plan.run);
}

void Renderer::record_plan(gpu::CommandList& cmd, const FrameInputs& in, const PassPlan& plan, PassSet subset) {
    ++plans_;
    for (std::size_t p = 0; p < std::size_t(pass_count); ++p)
        if (!plan.run.has(Pass(p))) unplanned_[p] = plans_;
    for (const PassRow* row : method(in.settings.method).rows)
        if (plan.run.has(row->pass) && subset.has(row->pass)) record(cmd, row->pass, in, plan);
}

namespace {
// A spec with the renderer's block and workgroup sizes filled in.
ResolvedSpec resolve(const PipelineSpec& spec, std::uint32_t block_h, std::uint32_t gx, std::uint32_t gy) {
    return {spec.block_h ? spec.block_h : block_h, spec.group_x ? spec.group_x : gx, spec.group_y ? spec.group_y : gy,
            spec.proxies, spec.walls, spec.per_channel, spec.segment_check, spec.features, spec.faces, spec.linear_penumbra,
            spec.proxy_registers};
}
} // namespace

const gpu::ComputePipeline& Renderer::pipeline(ShaderLookup shaders, const char* shader, const PipelineSpec& spec,
                                               std::span<const gpu::ScalarKind> kinds) {
    return pipelines_->get(shaders, shader, kinds, resolve(spec, block_h_, group_x_, group_y_));
}

void Renderer::prefetch_pipeline(ShaderLookup shaders, const char* shader, const PipelineSpec& spec,
                                 std::span<const gpu::ScalarKind> kinds) {
    pipelines_->prefetch(shaders, shader, kinds, resolve(spec, block_h_, group_x_, group_y_));
}

} // namespace lantern::gi::vk
