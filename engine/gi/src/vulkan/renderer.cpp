#include "lantern/gi/vulkan/renderer.hpp"

#include "lantern/gi/reference_indirect.hpp"
#include "lantern_gi_shaders.hpp"
#include "vulkan/pass_params.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <span>
#include <tuple>

namespace lantern::gi::vk {
namespace {

using gpu::BindingType;

constexpr int num_query_sets = 3; // frames in flight + one being recorded

int pitch_of(int width) { return (width + 3) & ~3; }

VkFormat view_format(TexFormat f, bool rgba8) {
    if (rgba8) return VK_FORMAT_R8G8B8A8_UNORM; // also the 32-bit heat tap masks (read as R32_UINT)
    switch (f) {
    case TexFormat::r8: return VK_FORMAT_R8_UNORM;
    case TexFormat::rg8: return VK_FORMAT_R8G8_UNORM;
    case TexFormat::rgba16f: return VK_FORMAT_R16G16B16A16_SFLOAT;
    }
    return VK_FORMAT_UNDEFINED;
}

// Binding lists of the shaders (set 0, dense).
const std::vector<BindingType>& bindings_of(const char* shader) {
    using B = BindingType;
    static const std::map<std::string, std::vector<BindingType>> table = {
        {"gi_conduction.comp", {B::uniform_texel_buffer, B::uniform_buffer, B::storage_buffer}},
        {"gi_ao.comp", {B::uniform_texel_buffer, B::uniform_buffer, B::uniform_texel_buffer, B::storage_buffer}},
        {"gi_light_bins.comp", {B::uniform_buffer, B::storage_buffer}},
        {"gi_direct.comp",
         {B::uniform_texel_buffer, B::uniform_buffer, B::uniform_buffer, B::storage_buffer, B::storage_buffer,
          B::storage_buffer, B::storage_buffer, B::storage_buffer, B::storage_buffer, B::storage_buffer}},
        {"gi_directional.comp",
         {B::uniform_texel_buffer, B::uniform_buffer, B::uniform_buffer, B::uniform_texel_buffer,
          B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer,
          B::uniform_texel_buffer, B::storage_buffer, B::storage_buffer, B::storage_buffer, B::storage_buffer,
          B::storage_buffer, B::storage_buffer}},
        {"gi_emission.comp", {B::uniform_texel_buffer, B::storage_buffer}},
        {"gi_heat_seed.comp", {B::uniform_texel_buffer, B::uniform_texel_buffer, B::storage_buffer}},
        {"gi_heat_mask.comp", {B::uniform_texel_buffer, B::uniform_buffer, B::storage_buffer}},
        {"gi_heat.comp", {B::uniform_texel_buffer, B::uniform_texel_buffer, B::storage_buffer}},
        {"gi_upsample.comp", {B::uniform_texel_buffer, B::uniform_buffer, B::uniform_texel_buffer, B::storage_buffer}},
        {"gi_blur.comp", {B::uniform_texel_buffer, B::uniform_buffer, B::uniform_texel_buffer, B::storage_buffer}},
        {"gi_wall_indirect.comp",
         {B::uniform_texel_buffer, B::uniform_buffer, B::uniform_texel_buffer, B::storage_buffer, B::storage_buffer,
          B::storage_buffer, B::storage_buffer}},
        {"gi_lit.comp",
         {B::uniform_texel_buffer, B::uniform_buffer, B::uniform_buffer, B::uniform_texel_buffer,
          B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer,
          B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer,
          B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer, B::storage_buffer}},
        {"gi_copy.comp", {B::uniform_texel_buffer, B::storage_buffer}},
    };
    return table.at(shader);
}

std::span<const std::byte> bytes_of(const void* data, std::size_t size) {
    return {static_cast<const std::byte*>(data), size};
}

} // namespace

const char* tex_name(Tex t) {
    static constexpr const char* names[tex_count] = {
        "conduction",       "ao",           "direct",           "shadow",           "wall_direct_px",
        "wall_direct_nx",   "wall_direct_pz", "wall_direct_nz", "emission",         "heat_a",
        "heat_b",           "heat_mask",    "indirect",     "blur_temp",        "wall_indirect_px", "wall_indirect_nx",
        "wall_indirect_pz", "wall_indirect_nz", "lit",           "direct_point",     "shadow_point",
        "wall_direct_point_px", "wall_direct_point_nx", "wall_direct_point_pz", "wall_direct_point_nz"};
    return names[int(t)];
}

// Pipelines by (shader, specialisation), created on first use and kept.
struct Renderer::Pipelines {
    gpu::Device* device = nullptr;
    std::map<std::tuple<std::string, bool, bool, bool, bool>, gpu::ComputePipeline> cache;

    const gpu::ComputePipeline& get(const char* shader, std::uint32_t block_h, std::uint32_t gx, std::uint32_t gy,
                                    bool proxies = true, bool walls = true, bool per_channel = true,
                                    bool segment_check = true) {
        auto key = std::make_tuple(std::string(shader), proxies, walls, per_channel, segment_check);
        auto it = cache.find(key);
        if (it != cache.end()) return it->second;
        gpu::ComputePipelineDesc desc;
        desc.spirv = lantern_gi_shaders_spirv(shader);
        LANTERN_VERIFY(!desc.spirv.empty(), "GI shader missing from lantern_gi_shaders");
        desc.bindings = bindings_of(shader);
        desc.specialization = {{spec_block_h, block_h},       {spec_group_x, gx},
                               {spec_group_y, gy},            {spec_has_proxies, proxies ? 1u : 0u},
                               {spec_has_walls, walls ? 1u : 0u}, {spec_per_channel, per_channel ? 1u : 0u},
                               {spec_segment_check, segment_check ? 1u : 0u}};
        if (std::string(shader) == "gi_direct.comp" || std::string(shader) == "gi_light_bins.comp")
            desc.specialization.push_back({spec_max_lights, max_gpu_lights});
        desc.push_constant_size = sizeof(GiPassParams);
        desc.name = shader;
        return cache.emplace(key, device->create_compute_pipeline(desc)).first->second;
    }
};

struct Renderer::QuerySet {
    gpu::TimestampQueries queries;
    std::vector<Pass> passes; // region i measured passes[i]
    bool pending = false;     // recorded, not yet read
    std::uint64_t frame = 0;
};

struct Renderer::PassParams : GiPassParams {};

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
    if (device.capabilities().timestamps) {
        for (int i = 0; i < num_query_sets; ++i) {
            auto q = device.create_timestamp_queries(pass_count + 8, "gi passes");
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
    const VkDeviceSize texel_bytes = rgba8 ? 4 : VkDeviceSize(bytes_per_texel(format));
    gpu::BufferDesc desc;
    desc.size = std::max<VkDeviceSize>(16, (VkDeviceSize(g.pitch) * VkDeviceSize(height) * texel_bytes + 15) & ~VkDeviceSize(15));
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    desc.name = tex_name(t);
    g.buffer = device_.create_buffer(desc);
    g.view = device_.create_buffer_view(g.buffer, view_format(format, rgba8), 0, VK_WHOLE_SIZE, tex_name(t));
    if (rgba8) g.view_u32 = device_.create_buffer_view(g.buffer, VK_FORMAT_R32_UINT, 0, VK_WHOLE_SIZE, tex_name(t));
}

void Renderer::drop_texture(Tex t) { textures_[int(t)] = GpuTexture{}; }

Result<void> Renderer::prepare(const FrameInputs& in, const PassPlan& plan) {
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

    const int W = w.width, H = w.height;
    auto need = [&](Pass p) { return plan.run.has(p); };
    ensure_texture(Tex::conduction, TexFormat::r8, W, H);
    if (need(Pass::ao)) ensure_texture(Tex::ao, TexFormat::r8, W, H);
    else drop_texture(Tex::ao);
    ensure_texture(Tex::direct, TexFormat::rgba16f, W, H);
    ensure_texture(Tex::shadow, TexFormat::rg8, W, H);
    for (int f = 0; f < 4; ++f) ensure_texture(Tex(int(Tex::wall_direct_px) + f), TexFormat::rgba16f, W, H);
    if (!in.directional_lights.empty()) {
        ensure_texture(Tex::direct_point, TexFormat::rgba16f, W, H);
        ensure_texture(Tex::shadow_point, TexFormat::rg8, W, H);
        for (int f = 0; f < 4; ++f) ensure_texture(Tex(int(Tex::wall_direct_point_px) + f), TexFormat::rgba16f, W, H);
    } else {
        for (int t = int(Tex::direct_point); t <= int(Tex::wall_direct_point_nz); ++t) drop_texture(Tex(t));
    }
    const bool indirect = need(Pass::emission) || need(Pass::heat);
    if (indirect) {
        const HeatGrid g = heat_grid(w, in.settings.heat_scale);
        ensure_texture(Tex::emission, TexFormat::rgba16f, W, H);
        ensure_texture(Tex::heat_a, TexFormat::rgba16f, g.width, g.height);
        ensure_texture(Tex::heat_b, TexFormat::rgba16f, g.width, g.height);
        ensure_texture(Tex::heat_mask, TexFormat::r8, g.width, g.height, true);
        ensure_texture(Tex::indirect, TexFormat::rgba16f, W, H);
    } else {
        for (Tex t : {Tex::emission, Tex::heat_a, Tex::heat_b, Tex::heat_mask, Tex::indirect}) drop_texture(t);
    }
    if (need(Pass::blur)) ensure_texture(Tex::blur_temp, TexFormat::rgba16f, W, H);
    else drop_texture(Tex::blur_temp);
    for (int f = 0; f < 4; ++f) {
        Tex t = Tex(int(Tex::wall_indirect_px) + f);
        if (need(Pass::wall_indirect)) ensure_texture(t, TexFormat::rgba16f, W, H);
        else drop_texture(t);
    }
    if (need(Pass::lit)) ensure_texture(Tex::lit, TexFormat::r8, W, H, true);
    else drop_texture(Tex::lit);
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

std::vector<std::uint8_t> Renderer::read_back_walls() {
    if (!walls_) return {};
    const auto bytes = device_.read_back(walls_);
    std::vector<std::uint8_t> out(bytes.size());
    std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
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

Renderer::PassParams Renderer::params(const FrameInputs& in, int width, int height, int resolution) const {
    PassParams p{};
    const CameraView& v = in.window.view;
    p.camera_view = glm::vec4(v.min_x, v.min_z, v.width, v.height);
    p.size = glm::ivec4(width, height, pitch_of(width), resolution);
    p.grid = glm::ivec4(in.walls.width, in.walls.height, in.walls.origin.x, in.walls.origin.y);
    p.grid_phase = glm::ivec4(in.walls.phase, 0, 0);
    p.counts = glm::ivec4(int(in.point_lights.size()), int(in.emissive_lights.size()),
                          int(in.directional_lights.size()), int(in.proxies.size()));
    return p;
}

void Renderer::dispatch_blocks(gpu::CommandList& cmd, int width, int height) {
    const std::uint32_t blocks_x = std::uint32_t(pitch_of(width) / 4);
    const std::uint32_t blocks_y = (std::uint32_t(height) + block_h_ - 1) / block_h_;
    cmd.dispatch((blocks_x + group_x_ - 1) / group_x_, (blocks_y + group_y_ - 1) / group_y_);
}

void Renderer::clear(gpu::CommandList& cmd, Tex t) { cmd.fill_buffer(textures_[int(t)].buffer, 0); }

void Renderer::begin_frame(gpu::CommandList& cmd, std::uint64_t frame) {
    if (queries_.empty()) return;
    frame_slot_ = (frame_slot_ + 1) % int(queries_.size());
    QuerySet& set = queries_[std::size_t(frame_slot_)];
    if (set.pending) {
        // Three recordings old: its submission is normally done. Read it if so; a set whose
        // submission is still running is dropped rather than waited for.
        if (auto done = set.queries.try_resolve()) resolved_.push_back(collect_timings(set, *done));
        set.pending = false;
    }
    set.queries.reset(cmd);
    set.passes.clear();
    set.pending = true;
    set.frame = frame;
}

FrameTimings Renderer::collect_timings(const QuerySet& set, const gpu::TimestampResult& result) {
    FrameTimings out{set.frame, {}};
    for (std::size_t i = 0; i < result.regions.size() && i < set.passes.size(); ++i)
        out.passes.push_back({set.passes[i], double(result.regions[i].duration_ns) * 1e-6, result.regions[i]});
    return out;
}

std::vector<FrameTimings> Renderer::completed_timings() {
    std::vector<FrameTimings> out = std::move(resolved_);
    resolved_.clear();
    // Oldest first: walk the sets from the one after the newest.
    for (int k = 1; k <= int(queries_.size()); ++k) {
        QuerySet& set = queries_[std::size_t((frame_slot_ + k) % int(queries_.size()))];
        if (!set.pending) continue;
        if (auto done = set.queries.try_resolve()) {
            out.push_back(collect_timings(set, *done));
            set.pending = false;
        }
    }
    return out;
}

std::vector<PassTiming> Renderer::wait_timings() {
    if (queries_.empty() || frame_slot_ < 0) return {};
    QuerySet& set = queries_[std::size_t(frame_slot_)];
    if (!set.pending) return {};
    set.pending = false;
    return collect_timings(set, set.queries.resolve()).passes;
}

void Renderer::record(gpu::CommandList& cmd, Pass pass, const FrameInputs& in, const PassPlan& plan) {
    QuerySet* set = (!queries_.empty() && frame_slot_ >= 0) ? &queries_[std::size_t(frame_slot_)] : nullptr;
    std::uint32_t region = 0;
    if (set) {
        region = set->queries.begin(cmd, pass_name(pass));
        set->passes.push_back(pass);
    }
    switch (pass) {
    case Pass::conduction: record_conduction(cmd, in); break;
    case Pass::ao: record_ao(cmd, in); break;
    case Pass::direct: record_direct(cmd, in, plan); break;
    case Pass::directional: record_directional(cmd, in, plan); break;
    case Pass::emission: record_emission(cmd, in); break;
    case Pass::heat: record_heat(cmd, in); break;
    case Pass::blur: record_blur(cmd, in); break;
    case Pass::wall_indirect: record_wall_indirect(cmd, in); break;
    case Pass::lit: record_lit(cmd, in, plan); break;
    case Pass::count: break;
    }
    if (set) set->queries.end(cmd, region);
}

std::array<Tex, 6> Renderer::direct_outputs(const FrameInputs& in) const {
    if (in.directional_lights.empty())
        return {Tex::direct, Tex::shadow, Tex::wall_direct_px, Tex::wall_direct_nx, Tex::wall_direct_pz, Tex::wall_direct_nz};
    return {Tex::direct_point,         Tex::shadow_point,         Tex::wall_direct_point_px,
            Tex::wall_direct_point_nx, Tex::wall_direct_point_pz, Tex::wall_direct_point_nz};
}

void Renderer::record_plan(gpu::CommandList& cmd, const FrameInputs& in, const PassPlan& plan) {
    record_plan(cmd, in, plan, plan.run);
}

void Renderer::record_plan(gpu::CommandList& cmd, const FrameInputs& in, const PassPlan& plan, PassSet subset) {
    for (int p = 0; p < pass_count; ++p)
        if (plan.run.has(Pass(p)) && subset.has(Pass(p))) record(cmd, Pass(p), in, plan);
}

// ---- issue 3 passes

void Renderer::record_conduction(gpu::CommandList& cmd, const FrameInputs& in) {
    const GiWindow& w = in.window;
    cmd.bind(pipelines_->get("gi_conduction.comp", block_h_, group_x_, group_y_, false));
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .uniform_texel_buffer(0, walls_view_)
                             .uniform_buffer(1, proxies_)
                             .storage_buffer(2, textures_[int(Tex::conduction)].buffer));
    PassParams p = params(in, w.width, w.height, w.resolution);
    cmd.push_constants(static_cast<const GiPassParams&>(p));
    dispatch_blocks(cmd, w.width, w.height);
    cmd.barrier_compute_to_compute();
}

void Renderer::record_ao(gpu::CommandList& cmd, const FrameInputs& in) {
    const GiWindow& w = in.window;
    const scene::AoSettings& ao = in.settings.ao;
    const auto key = std::make_tuple(w.resolution, ao.radius, ao.power);
    if (!ao_kernel_ || ao_kernel_key_ != key) {
        // The weight table changes only with the resolution and the AO shape: upload it then.
        const AoKernel k = ao_kernel(w.resolution, ao);
        std::vector<float> table(k.weights);
        table.insert(table.end(), k.totals.begin(), k.totals.end());
        gpu::BufferDesc desc;
        desc.size = (table.size() * sizeof(float) + 15) & ~std::size_t(15);
        desc.usage = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
        desc.name = "ao kernel";
        ao_kernel_ = device_.create_buffer(desc);
        ao_kernel_view_ = device_.create_buffer_view(ao_kernel_, VK_FORMAT_R32_SFLOAT, 0, VK_WHOLE_SIZE, "ao kernel");
        cmd.upload(ao_kernel_, 0, bytes_of(table.data(), table.size() * sizeof(float)));
        cmd.barrier_transfer_to_compute();
        ao_kernel_key_ = key;
        ao_range_ = k.range;
    }
    cmd.bind(pipelines_->get("gi_ao.comp", block_h_, group_x_, group_y_, false));
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .uniform_texel_buffer(0, walls_view_)
                             .uniform_buffer(1, proxies_)
                             .uniform_texel_buffer(2, ao_kernel_view_)
                             .storage_buffer(3, textures_[int(Tex::ao)].buffer));
    PassParams p = params(in, w.width, w.height, w.resolution);
    p.params0 = glm::vec4(ao.radius, ao.power, ao.strength, ao.dither ? 1.0f : 0.0f);
    p.params1.x = float(ao_range_);
    cmd.push_constants(static_cast<const GiPassParams&>(p));
    dispatch_blocks(cmd, w.width, w.height);
    cmd.barrier_compute_to_compute();
}

void Renderer::record_direct(gpu::CommandList& cmd, const FrameInputs& in, const PassPlan& plan) {
    const GiWindow& w = in.window;
    auto tex = [&](Tex t) -> const gpu::Buffer& { return textures_[int(t)].buffer; };
    const auto out = direct_outputs(in);
    // No point or emissive lights: the outputs are zero. No wall in view: the shader skips
    // the faces, which stay zero.
    const bool no_lights = in.point_lights.empty() && in.emissive_lights.empty();
    if (no_lights || !plan.has_walls_in_window) {
        for (std::size_t i = no_lights ? 0 : 2; i < out.size(); ++i) clear(cmd, out[i]);
        cmd.barrier_transfer_to_compute();
        if (no_lights) return;
    }
    // Light bins: one per direct-pass workgroup, a bitmask of the lights reaching it.
    const std::uint32_t blocks_x = std::uint32_t(pitch_of(w.width) / 4);
    const std::uint32_t blocks_y = (std::uint32_t(w.height) + block_h_ - 1) / block_h_;
    const std::uint32_t bins_x = (blocks_x + group_x_ - 1) / group_x_, bins_y = (blocks_y + group_y_ - 1) / group_y_;
    const std::uint32_t words = std::uint32_t((in.point_lights.size() + in.emissive_lights.size() + 31) / 32);
    const VkDeviceSize bin_bytes = std::max<VkDeviceSize>(16, VkDeviceSize(bins_x) * bins_y * std::max(words, 1u) * 4);
    if (!light_bins_ || light_bins_.size() < bin_bytes) {
        gpu::BufferDesc desc;
        desc.size = bin_bytes;
        desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        desc.name = "gi light bins";
        light_bins_ = device_.create_buffer(desc);
    }
    cmd.bind(pipelines_->get("gi_light_bins.comp", 1, 8, 8, false));
    cmd.push_descriptors(gpu::DescriptorWrites().uniform_buffer(0, lights_).storage_buffer(1, light_bins_));
    PassParams b = params(in, w.width, w.height, w.resolution);
    b.params0 = glm::vec4(float(bins_x), float(bins_y), float(words), 0.0f);
    b.params1 = glm::vec4(float(4 * group_x_), float(block_h_ * group_y_), 0.0f, 0.0f);
    cmd.push_constants(static_cast<const GiPassParams&>(b));
    cmd.dispatch((bins_x + 7) / 8, (bins_y + 7) / 8);
    cmd.barrier_compute_to_compute();

    cmd.bind(pipelines_->get("gi_direct.comp", block_h_, group_x_, group_y_, !in.proxies.empty(),
                             plan.has_walls_in_window));
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .uniform_texel_buffer(0, walls_view_)
                             .uniform_buffer(1, proxies_)
                             .uniform_buffer(2, lights_)
                             .storage_buffer(3, tex(out[0]))
                             .storage_buffer(4, tex(out[1]))
                             .storage_buffer(5, tex(out[2]))
                             .storage_buffer(6, tex(out[3]))
                             .storage_buffer(7, tex(out[4]))
                             .storage_buffer(8, tex(out[5]))
                             .storage_buffer(9, light_bins_));
    PassParams p = params(in, w.width, w.height, w.resolution);
    p.params0.x = in.settings.light_softness;
    cmd.push_constants(static_cast<const GiPassParams&>(p));
    dispatch_blocks(cmd, w.width, w.height);
    cmd.barrier_compute_to_compute();
}

void Renderer::record_directional(gpu::CommandList& cmd, const FrameInputs& in, const PassPlan& plan) {
    const GiWindow& w = in.window;
    auto tex = [&](Tex t) -> const GpuTexture& { return textures_[int(t)]; };
    if (!plan.has_walls_in_window) { // the shader skips the faces: they stay zero
        for (Tex t : {Tex::wall_direct_px, Tex::wall_direct_nx, Tex::wall_direct_pz, Tex::wall_direct_nz}) clear(cmd, t);
        cmd.barrier_transfer_to_compute();
    }
    cmd.bind(pipelines_->get("gi_directional.comp", block_h_, group_x_, group_y_, !in.proxies.empty(),
                             plan.has_walls_in_window));
    gpu::DescriptorWrites writes;
    writes.uniform_texel_buffer(0, walls_view_).uniform_buffer(1, proxies_).uniform_buffer(2, suns_);
    // Reads the point-light results, writes the contract textures (never in place).
    const auto inputs = direct_outputs(in);
    const Tex outputs[6] = {Tex::direct, Tex::shadow, Tex::wall_direct_px, Tex::wall_direct_nx, Tex::wall_direct_pz,
                            Tex::wall_direct_nz};
    for (int i = 0; i < 6; ++i) writes.uniform_texel_buffer(std::uint32_t(3 + i), tex(inputs[std::size_t(i)]).view);
    for (int i = 0; i < 6; ++i) writes.storage_buffer(std::uint32_t(9 + i), tex(outputs[i]).buffer);
    cmd.push_descriptors(writes);
    PassParams p = params(in, w.width, w.height, w.resolution);
    p.params0 = glm::vec4(in.wall_height, in.settings.directional_angle_scale, 0.0f, 0.0f);
    cmd.push_constants(static_cast<const GiPassParams&>(p));
    dispatch_blocks(cmd, w.width, w.height);
    cmd.barrier_compute_to_compute();
}

// ---- issue 4 passes

void Renderer::record_emission(gpu::CommandList& cmd, const FrameInputs& in) {
    const GiWindow& w = in.window;
    cmd.bind(pipelines_->get("gi_emission.comp", block_h_, group_x_, group_y_, false));
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .uniform_texel_buffer(0, textures_[int(Tex::direct)].view)
                             .storage_buffer(1, textures_[int(Tex::emission)].buffer));
    PassParams p = params(in, w.width, w.height, w.resolution);
    p.params0.x = in.settings.emission_strength;
    cmd.push_constants(static_cast<const GiPassParams&>(p));
    dispatch_blocks(cmd, w.width, w.height);
    cmd.barrier_compute_to_compute();
}

void Renderer::record_heat(gpu::CommandList& cmd, const FrameInputs& in) {
    const GiWindow& w = in.window;
    const scene::GiSettings& s = in.settings;
    const HeatGrid g = heat_grid(w, s.heat_scale);
    // Seed.
    cmd.bind(pipelines_->get("gi_heat_seed.comp", block_h_, group_x_, group_y_, false));
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .uniform_texel_buffer(0, textures_[int(Tex::emission)].view)
                             .uniform_texel_buffer(1, textures_[int(Tex::shadow)].view)
                             .storage_buffer(2, textures_[int(Tex::heat_a)].buffer));
    PassParams seed = params(in, g.width, g.height, w.resolution);
    seed.params1 = glm::vec4(float(w.width), float(w.height), float(pitch_of(w.width)), float(g.scale));
    cmd.push_constants(static_cast<const GiPassParams&>(seed));
    dispatch_blocks(cmd, g.width, g.height);
    cmd.barrier_compute_to_compute();
    // Tap masks: which taps each heat texel may use (air, segment clear), once per frame.
    const float distance = s.diffusion_distance * g.texels_per_unit;
    cmd.bind(pipelines_->get("gi_heat_mask.comp", block_h_, group_x_, group_y_, false, true, true, s.segment_check));
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .uniform_texel_buffer(0, walls_view_)
                             .uniform_buffer(1, proxies_)
                             .storage_buffer(2, textures_[int(Tex::heat_mask)].buffer));
    PassParams mask = params(in, g.width, g.height, w.resolution);
    mask.params0 = glm::vec4(g.texels_per_unit, distance, s.diffusion_distance * 2.0f + 2.0f, 0.0f);
    cmd.push_constants(static_cast<const GiPassParams&>(mask));
    dispatch_blocks(cmd, g.width, g.height);
    cmd.barrier_compute_to_compute();
    // Rounds, ping-pong.
    const auto& round_pipeline =
        pipelines_->get("gi_heat.comp", block_h_, group_x_, group_y_, false, true, s.per_channel, true);
    PassParams round = params(in, g.width, g.height, w.resolution);
    round.params0 = glm::vec4(g.texels_per_unit, distance, s.diffusion_rate, s.range_boost);
    round.params1 = glm::vec4(s.intensity_multiplier, 0.0f, 0.0f, 0.0f);
    Tex src = Tex::heat_a, dst = Tex::heat_b;
    for (int r = 0; r < s.heat_rounds; ++r) {
        cmd.bind(round_pipeline);
        cmd.push_descriptors(gpu::DescriptorWrites()
                                 .uniform_texel_buffer(0, textures_[int(Tex::heat_mask)].view_u32)
                                 .uniform_texel_buffer(1, textures_[int(src)].view)
                                 .storage_buffer(2, textures_[int(dst)].buffer));
        cmd.push_constants(static_cast<const GiPassParams&>(round));
        dispatch_blocks(cmd, g.width, g.height);
        cmd.barrier_compute_to_compute();
        std::swap(src, dst);
    }
    // Upsample (or copy) into the indirect texture.
    cmd.bind(pipelines_->get("gi_upsample.comp", block_h_, group_x_, group_y_, false));
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .uniform_texel_buffer(0, walls_view_)
                             .uniform_buffer(1, proxies_)
                             .uniform_texel_buffer(2, textures_[int(src)].view)
                             .storage_buffer(3, textures_[int(Tex::indirect)].buffer));
    PassParams up = params(in, w.width, w.height, w.resolution);
    up.params0 = glm::vec4(float(g.width), float(g.height), float(pitch_of(g.width)), g.texels_per_unit);
    up.params1.x = float(g.scale);
    cmd.push_constants(static_cast<const GiPassParams&>(up));
    dispatch_blocks(cmd, w.width, w.height);
    cmd.barrier_compute_to_compute();
}

void Renderer::record_blur(gpu::CommandList& cmd, const FrameInputs& in) {
    const GiWindow& w = in.window;
    const auto& pipeline = pipelines_->get("gi_blur.comp", block_h_, group_x_, group_y_, false);
    auto blur_pass = [&](Tex src, Tex dst, glm::vec2 axis) {
        cmd.bind(pipeline);
        cmd.push_descriptors(gpu::DescriptorWrites()
                                 .uniform_texel_buffer(0, walls_view_)
                                 .uniform_buffer(1, proxies_)
                                 .uniform_texel_buffer(2, textures_[int(src)].view)
                                 .storage_buffer(3, textures_[int(dst)].buffer));
        PassParams p = params(in, w.width, w.height, w.resolution);
        p.params0 = glm::vec4(axis, 0.0f, 0.0f);
        cmd.push_constants(static_cast<const GiPassParams&>(p));
        dispatch_blocks(cmd, w.width, w.height);
        cmd.barrier_compute_to_compute();
    };
    blur_pass(Tex::indirect, Tex::blur_temp, {1.0f, 0.0f});
    blur_pass(Tex::blur_temp, Tex::indirect, {0.0f, 1.0f});
}

void Renderer::record_wall_indirect(gpu::CommandList& cmd, const FrameInputs& in) {
    const GiWindow& w = in.window;
    cmd.bind(pipelines_->get("gi_wall_indirect.comp", block_h_, group_x_, group_y_, false));
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .uniform_texel_buffer(0, walls_view_)
                             .uniform_buffer(1, proxies_)
                             .uniform_texel_buffer(2, textures_[int(Tex::indirect)].view)
                             .storage_buffer(3, textures_[int(Tex::wall_indirect_px)].buffer)
                             .storage_buffer(4, textures_[int(Tex::wall_indirect_nx)].buffer)
                             .storage_buffer(5, textures_[int(Tex::wall_indirect_pz)].buffer)
                             .storage_buffer(6, textures_[int(Tex::wall_indirect_nz)].buffer));
    PassParams p = params(in, w.width, w.height, w.resolution);
    cmd.push_constants(static_cast<const GiPassParams&>(p));
    dispatch_blocks(cmd, w.width, w.height);
    cmd.barrier_compute_to_compute();
}

void Renderer::record_lit(gpu::CommandList& cmd, const FrameInputs& in, const PassPlan& plan) {
    const GiWindow& w = in.window;
    // Absent textures are bound as the direct texture (any valid view) and flagged absent.
    auto view_or = [&](Tex t, std::uint32_t bit, std::uint32_t& present) -> const gpu::BufferView& {
        if (has(t)) {
            present |= 1u << bit;
            return textures_[int(t)].view;
        }
        return textures_[int(Tex::direct)].view;
    };
    std::uint32_t present = 0;
    gpu::DescriptorWrites writes;
    writes.uniform_texel_buffer(0, walls_view_).uniform_buffer(1, proxies_).uniform_buffer(2, suns_);
    writes.uniform_texel_buffer(3, view_or(Tex::direct, 0, present));
    writes.uniform_texel_buffer(4, view_or(Tex::indirect, 1, present));
    writes.uniform_texel_buffer(5, view_or(Tex::ao, 2, present));
    writes.uniform_texel_buffer(6, view_or(Tex::shadow, 3, present));
    for (int f = 0; f < 4; ++f) writes.uniform_texel_buffer(std::uint32_t(7 + f), view_or(Tex(int(Tex::wall_direct_px) + f), 4u + f, present));
    for (int f = 0; f < 4; ++f)
        writes.uniform_texel_buffer(std::uint32_t(11 + f), view_or(Tex(int(Tex::wall_indirect_px) + f), 8u + f, present));
    writes.storage_buffer(15, textures_[int(Tex::lit)].buffer);
    cmd.bind(pipelines_->get("gi_lit.comp", block_h_, group_x_, group_y_, false, plan.has_walls_in_window));
    cmd.push_descriptors(writes);
    PassParams p = params(in, w.width, w.height, w.resolution);
    p.params0 = glm::vec4(in.wall_height, float(present), 0.0f, 0.0f);
    p.params1 = glm::vec4(float(int(in.settings.tone_map)), in.settings.white_point, in.settings.directional_angle_scale, 0.0f);
    cmd.push_constants(static_cast<const GiPassParams&>(p));
    dispatch_blocks(cmd, w.width, w.height);
    cmd.barrier_compute_to_compute();
}

// ---- read back

Texture Renderer::read_back(Tex t) { return read_back(t, tex_name(t)); }

Texture Renderer::read_back(Tex t, const char* name) {
    const GpuTexture& g = textures_[int(t)];
    LANTERN_ASSERT(bool(g.buffer), "read_back of a texture this frame did not allocate");
    Texture out(name, g.format, g.width, g.height);
    const auto bytes = device_.read_back(g.buffer);
    const int bpt = bytes_per_texel(g.format);
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const std::byte* src = bytes.data() + (std::size_t(y) * std::size_t(g.pitch) + std::size_t(x)) * std::size_t(bpt);
            float* dst = out.at(x, y);
            if (g.format == TexFormat::rgba16f) {
                for (int c = 0; c < 4; ++c) {
                    std::uint16_t h;
                    std::memcpy(&h, src + 2 * c, 2);
                    dst[c] = half_to_float(h);
                }
            } else {
                for (int c = 0; c < bpt; ++c) dst[c] = unorm8_to_float(std::uint8_t(src[c]));
            }
        }
    return out;
}

std::vector<std::uint8_t> Renderer::read_back_lit_rgb() {
    const GpuTexture& g = textures_[int(Tex::lit)];
    LANTERN_ASSERT(bool(g.buffer), "read_back_lit_rgb without a lit pass");
    const auto bytes = device_.read_back(g.buffer);
    std::vector<std::uint8_t> rgb(std::size_t(g.width) * std::size_t(g.height) * 3);
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x)
            for (int c = 0; c < 3; ++c)
                rgb[(std::size_t(y) * std::size_t(g.width) + std::size_t(x)) * 3 + std::size_t(c)] =
                    std::uint8_t(bytes[(std::size_t(y) * std::size_t(g.pitch) + std::size_t(x)) * 4 + std::size_t(c)]);
    return rgb;
}

// ---- benchmark baseline

std::vector<std::uint64_t> Renderer::pass_bytes_written(Pass pass, const FrameInputs& in) {
    const std::uint64_t texels = std::uint64_t(pitch_of(in.window.width)) * std::uint64_t(in.window.height);
    const HeatGrid g = heat_grid(in.window, in.settings.heat_scale);
    const std::uint64_t heat_texels = std::uint64_t(pitch_of(g.width)) * std::uint64_t(g.height);
    switch (pass) {
    case Pass::conduction:
    case Pass::ao: return {texels};
    case Pass::direct:
    case Pass::directional: return {texels * (8 + 2 + 4 * 8)};
    case Pass::emission: return {texels * 8};
    case Pass::heat: {
        std::vector<std::uint64_t> out{heat_texels * 8, heat_texels * 4};
        for (int r = 0; r < in.settings.heat_rounds; ++r) out.push_back(heat_texels * 8);
        out.push_back(texels * 8);
        return out;
    }
    case Pass::blur: return {texels * 8, texels * 8};
    case Pass::wall_indirect: return {texels * 4 * 8};
    case Pass::lit: return {texels * 4};
    case Pass::count: break;
    }
    return {};
}

double Renderer::time_copy_dispatches(const std::vector<std::uint64_t>& bytes_written, int repeats) {
    if (bytes_written.empty() || queries_.empty()) return 0.0;
    const std::uint64_t max_bytes = *std::max_element(bytes_written.begin(), bytes_written.end());
    // Copy texels laid out as rows of 1024 (the kernel needs a 2D grid).
    constexpr int row = 1024;
    gpu::BufferDesc desc;
    desc.size = ((max_bytes + 8 * row - 1) / (8 * row)) * (8 * row);
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    desc.name = "copy src";
    gpu::Buffer src = device_.create_buffer(desc);
    desc.name = "copy dst";
    gpu::Buffer dst = device_.create_buffer(desc);
    gpu::BufferView src_view = device_.create_buffer_view(src, VK_FORMAT_R16G16B16A16_SFLOAT);
    auto queries = device_.create_timestamp_queries(1, "copy");
    if (!queries) return 0.0;
    const auto& pipeline = pipelines_->get("gi_copy.comp", block_h_, group_x_, group_y_, false);
    std::vector<double> samples;
    for (int rep = 0; rep < repeats + 1; ++rep) { // the first run warms up
        gpu::CommandList cmd = device_.begin("copy baseline");
        cmd.fill_buffer(src, 0x3C003C00u); // 1.0 halves
        cmd.barrier_transfer_to_compute();
        queries->reset(cmd);
        const std::uint32_t region = queries->begin(cmd, "copy");
        for (std::uint64_t bytes : bytes_written) {
            const int height = int((bytes / 8 + row - 1) / row);
            cmd.bind(pipeline);
            cmd.push_descriptors(gpu::DescriptorWrites().uniform_texel_buffer(0, src_view).storage_buffer(1, dst));
            GiPassParams p{};
            p.size = glm::ivec4(row, height, row, 1);
            cmd.push_constants(p);
            dispatch_blocks(cmd, row, height);
            cmd.barrier_compute_to_compute();
        }
        queries->end(cmd, region);
        device_.submit(std::move(cmd));
        const auto result = queries->resolve();
        if (rep > 0) samples.push_back(double(result.regions[0].duration_ns) * 1e-6);
    }
    std::sort(samples.begin(), samples.end());
    return samples[samples.size() / 2];
}

} // namespace lantern::gi::vk
