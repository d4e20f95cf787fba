// The texel passes on Vulkan (texel_passes.hpp).
#include "lantern/texel/vulkan/texel_passes.hpp"

#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern_texel_shaders.hpp"

#include <glm/vec4.hpp>

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

namespace lantern::texel::vk {
namespace {

// texel.glsl's TexelPush.
struct TexelPush {
    glm::ivec4 walls{0};
    glm::vec4 params{0.0f};
    glm::uvec4 counts{0u};
    glm::uvec4 span{0u}; // uv_to_world: x first texel, y texels
};
static_assert(sizeof(TexelPush) == 64);

constexpr std::uint32_t group_size = 64; // local_size_x of both shaders
constexpr std::uint32_t spec_exact_rounding = 10; // gi_exact.glsl's EXACT_ROUNDING

template <typename T>
std::span<const std::byte> bytes_of(std::span<const T> values) {
    return std::as_bytes(values);
}

} // namespace

struct TexelPasses::Impl {
    gpu::Device* device = nullptr;
    gpu::ComputePipeline uv_to_world, light;
    // Scene buffers (grown, never shrunk).
    gpu::Buffer triangles, placements, normal_maps, walls, lights_bake, lights_live, lists_bake, lists_live;
    // The uploaded placements and which of them move (the light lists' input).
    std::vector<GpuPlacement> placed;
    std::vector<std::uint8_t> moving;
    // Atlas buffers.
    gpu::Buffer surfaces, baked, lit, albedo;
    std::uint32_t atlas_capacity = 0; // texels the atlas buffers hold
    TexelPush push;

    // `buffer` holds at least `bytes` (a new one, contents undefined, when it did not).
    bool ensure(gpu::Buffer& buffer, VkDeviceSize bytes, const char* name) {
        bytes = std::max<VkDeviceSize>((bytes + 15) & ~VkDeviceSize(15), 16);
        if (buffer && buffer.size() >= bytes) return false;
        gpu::BufferDesc desc;
        desc.size = std::max<VkDeviceSize>(bytes, buffer ? buffer.size() * 2 : 0);
        desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        desc.name = name;
        buffer = device->create_buffer(desc);
        return true;
    }

    template <typename T>
    void write(gpu::CommandList& cmd, gpu::Buffer& buffer, const std::vector<T>& values, const char* name) {
        ensure(buffer, values.size() * sizeof(T), name);
        upload(cmd, buffer, bytes_of(std::span<const T>(values)));
    }
    static void upload(gpu::CommandList& cmd, const gpu::Buffer& buffer, std::span<const std::byte> bytes) {
        // Up to 1 MiB inside the command buffer (64 KiB update commands): no staging memory
        // allocated per frame (a game re-uploads its scene as props come into view).
        if (bytes.size() > (std::size_t(1) << 20) || bytes.size() % 4 != 0) {
            cmd.upload(buffer, 0, bytes);
            return;
        }
        for (std::size_t at = 0; at < bytes.size(); at += 65536)
            cmd.update_buffer(buffer, at, bytes.subspan(at, std::min<std::size_t>(65536, bytes.size() - at)));
    }

    std::uint32_t groups() const { return groups_for(push.counts.x); }
    static std::uint32_t groups_for(std::uint32_t texels) { return (texels + group_size - 1) / group_size; }
    // UV to world's pipeline and buffers, after earlier passes' use of its outputs.
    void bind_uv_to_world(gpu::CommandList& cmd) const {
        before_writes(cmd);
        cmd.bind(uv_to_world);
        cmd.push_descriptors(gpu::DescriptorWrites()
                                 .storage_buffer(0, triangles)
                                 .storage_buffer(1, placements)
                                 .storage_buffer(2, normal_maps)
                                 .storage_buffer(3, surfaces));
    }
    void dispatch_uv_to_world(gpu::CommandList& cmd, std::uint32_t first, std::uint32_t texels) {
        TexelPush p = push;
        p.span = glm::uvec4(first, texels, 0u, 0u);
        cmd.push_constants(p);
        cmd.dispatch(groups_for(texels));
    }

    // Before anything here is overwritten: earlier passes' writes and reads, and on a raster
    // device earlier frames' vertex and fragment shaders reading the results, come first.
    void before_writes(gpu::CommandList& cmd) const {
        VkPipelineStageFlags readers = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
        if (device->capabilities().graphics)
            readers |= VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
        cmd.memory_barrier(readers, VK_ACCESS_SHADER_WRITE_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                           VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT |
                               VK_ACCESS_SHADER_WRITE_BIT);
    }
};

TexelPasses::TexelPasses(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
TexelPasses::~TexelPasses() = default;

Result<std::unique_ptr<TexelPasses>> TexelPasses::create(gpu::Device& device, const Capacity& reserve) {
    auto impl = std::make_unique<Impl>();
    impl->device = &device;
    // gi_exact.glsl: CPU drivers divide and take roots with the processor's IEEE
    // instructions; elsewhere residuals by Dekker's product (correct on every driver).
    const std::uint32_t exact = device.type() == gpu::DeviceType::cpu ? 0u : 1u;
    using gpu::BindingType;
    const auto make = [&](const char* name, std::vector<BindingType> bindings) {
        gpu::ComputePipelineDesc desc;
        desc.spirv = lantern_texel_shaders_spirv(name);
        desc.bindings = std::move(bindings);
        desc.specialization = {{spec_exact_rounding, exact}};
        desc.push_constant_size = sizeof(TexelPush);
        desc.name = name;
        return device.create_compute_pipeline(desc);
    };
    const BindingType sb = BindingType::storage_buffer;
    impl->uv_to_world = make("texel_uv_to_world.comp", {sb, sb, sb, sb});
    impl->light = make("texel_light.comp", {sb, sb, sb, sb, sb, sb, sb, sb});
    if (!impl->uv_to_world || !impl->light) return make_error("texel passes: a compute pipeline could not be created");
    Impl& m = *impl;
    m.ensure(m.triangles, VkDeviceSize(reserve.triangles) * sizeof(GpuTriangle), "texel triangles");
    m.ensure(m.placements, VkDeviceSize(reserve.placements) * sizeof(GpuPlacement), "texel placements");
    m.ensure(m.lights_bake, VkDeviceSize(reserve.lights) * sizeof(TexelLight), "texel static lights");
    m.ensure(m.lights_live, VkDeviceSize(reserve.lights) * sizeof(TexelLight), "texel lights");
    const VkDeviceSize list_words = 2 * VkDeviceSize(reserve.placements) + VkDeviceSize(reserve.placements) * reserve.lights;
    m.ensure(m.lists_bake, list_words * 4, "texel static light lists");
    m.ensure(m.lists_live, list_words * 4, "texel light lists");
    m.ensure(m.walls, (VkDeviceSize(reserve.wall_cells) + 3) / 4 * 4, "texel walls");
    m.ensure(m.normal_maps, VkDeviceSize(reserve.texels) * sizeof(glm::vec4), "texel normal maps");
    if (reserve.texels > 0) {
        const VkDeviceSize n = reserve.texels;
        m.ensure(m.surfaces, n * sizeof(TexelSurface), "texel surfaces");
        m.ensure(m.baked, n * sizeof(glm::vec4), "texel baked light");
        m.ensure(m.lit, n * sizeof(glm::vec4), "texel light");
        m.ensure(m.albedo, n * sizeof(glm::vec4), "texel albedo");
        m.atlas_capacity = reserve.texels;
        gpu::CommandList cmd = device.begin("texel passes: clear the bake");
        cmd.fill_buffer(m.baked, 0u); // nothing baked yet
        device.submit(std::move(cmd));
    }
    return std::unique_ptr<TexelPasses>(new TexelPasses(std::move(impl)));
}

void TexelPasses::upload_triangles(gpu::CommandList& cmd, const TexelScene& scene) {
    Impl& m = *impl_;
    m.before_writes(cmd); // earlier passes' reads of the buffers come first
    m.write(cmd, m.triangles, scene.triangles, "texel triangles");
    m.write(cmd, m.placements, scene.placements, "texel placements");
    m.push.counts.y = std::uint32_t(scene.placements.size());
    m.placed = scene.placements;
    m.moving.clear();
    for (const GpuPlacement& p : scene.placements) m.moving.push_back(placement_moves(scene, p) ? 1 : 0);
    cmd.barrier_transfer_to_compute();
}

void TexelPasses::upload_walls(gpu::CommandList& cmd, const TexelScene& scene) {
    Impl& m = *impl_;
    m.before_writes(cmd);
    m.write(cmd, m.walls, scene.walls.words, "texel walls");
    m.push.walls = glm::ivec4(scene.walls.origin, scene.walls.width, scene.walls.height);
    m.push.params.x = scene.wall_height;
    cmd.barrier_transfer_to_compute();
}

void TexelPasses::upload_albedo(gpu::CommandList& cmd, std::span<const glm::vec4> albedo) {
    Impl& m = *impl_;
    if (!m.albedo) return; // no scene yet
    const std::size_t count = std::min<std::size_t>(albedo.size(), m.atlas_capacity);
    m.before_writes(cmd);
    Impl::upload(cmd, m.albedo, bytes_of(albedo.first(count)));
    cmd.barrier_transfer_to_compute(); // the raster's readers: its own barrier (WorldRenderer::record)
}

void TexelPasses::upload_scene(gpu::CommandList& cmd, const TexelScene& scene) {
    Impl& m = *impl_;
    m.before_writes(cmd);
    m.write(cmd, m.normal_maps, scene.normal_maps, "texel normal maps");
    m.write(cmd, m.walls, scene.walls.words, "texel walls");
    const std::uint32_t texels = scene.texel_count;
    if (texels > m.atlas_capacity) {
        const std::uint32_t grown = std::max(texels, 2 * m.atlas_capacity); // doubling: few reallocations
        const VkDeviceSize n = std::max<VkDeviceSize>(grown, 1);
        m.surfaces.reset();
        m.baked.reset();
        m.lit.reset();
        m.albedo.reset();
        m.ensure(m.surfaces, n * sizeof(TexelSurface), "texel surfaces");
        m.ensure(m.baked, n * sizeof(glm::vec4), "texel baked light");
        m.ensure(m.lit, n * sizeof(glm::vec4), "texel light");
        m.ensure(m.albedo, n * sizeof(glm::vec4), "texel albedo");
        m.atlas_capacity = grown;
        cmd.fill_buffer(m.baked, 0u); // no bake yet: nothing baked
    }
    m.push.counts.x = texels;
    m.push.walls = glm::ivec4(scene.walls.origin, scene.walls.width, scene.walls.height);
    m.push.params.x = scene.wall_height;
    upload_triangles(cmd, scene);
}

void TexelPasses::record_uv_to_world(gpu::CommandList& cmd) {
    Impl& m = *impl_;
    if (m.push.counts.x == 0) return;
    m.bind_uv_to_world(cmd);
    m.dispatch_uv_to_world(cmd, 0u, m.push.counts.x);
    cmd.barrier_compute_to_compute();
}

void TexelPasses::record_uv_to_world(gpu::CommandList& cmd, std::span<const std::uint32_t> placements) {
    Impl& m = *impl_;
    if (m.push.counts.x == 0 || placements.empty()) return;
    m.bind_uv_to_world(cmd);
    // One dispatch per run of neighbouring placements (the player's parts are one).
    for (std::size_t i = 0; i < placements.size();) {
        std::size_t j = i + 1;
        while (j < placements.size() && placements[j] == placements[j - 1] + 1) ++j;
        if (placements[j - 1] >= m.placed.size()) break; // not uploaded
        const glm::uvec4 first = m.placed[placements[i]].ranges, last = m.placed[placements[j - 1]].ranges;
        const std::uint32_t begin = first.z, end = last.z + last.w * last.w;
        m.dispatch_uv_to_world(cmd, begin, std::min(end, m.push.counts.x) - std::min(begin, m.push.counts.x));
        i = j;
    }
    cmd.barrier_compute_to_compute();
}

void TexelPasses::record_plan(gpu::CommandList& cmd, const TexelFrame& frame, const TexelPlan& plan,
                              TexelRowTimer* timer) {
    if (plan.upload_layout) upload_scene(cmd, frame.scene);
    else {
        if (plan.upload_walls) upload_walls(cmd, frame.scene);
        if (plan.upload_triangles) upload_triangles(cmd, frame.scene);
    }
    const auto row = [&](TexelPass pass, auto&& record) {
        if (!plan.runs(pass)) return;
        const std::uint32_t region = timer ? timer->begin(cmd, texel_row(pass).name.data()) : 0u;
        record();
        if (timer) timer->end(cmd, region);
    };
    row(TexelPass::uv_to_world, [&] {
        if (plan.moved.empty()) record_uv_to_world(cmd);
        else record_uv_to_world(cmd, plan.moved);
    });
    row(TexelPass::bake, [&] {
        std::vector<TexelLight> fixed;
        for (const TexelLight& l : frame.lights)
            if (is_baked(l)) fixed.push_back(l);
        record_light(cmd, fixed, Mode::bake);
    });
    row(TexelPass::light, [&] { record_light(cmd, frame.lights, Mode::realtime); });
}

void TexelPasses::record_light(gpu::CommandList& cmd, std::span<const TexelLight> lights, Mode mode) {
    Impl& m = *impl_;
    if (m.push.counts.x == 0) return;
    const std::size_t count = std::min<std::size_t>(lights.size(), 65536);
    gpu::Buffer& buffer = mode == Mode::bake ? m.lights_bake : m.lights_live;
    gpu::Buffer& lists = mode == Mode::bake ? m.lists_bake : m.lists_live;
    const std::vector<std::uint32_t> list =
        light_lists(m.placed, m.moving, lights.first(count), mode == Mode::bake ? LightPass::bake : LightPass::realtime);
    m.before_writes(cmd);
    m.ensure(buffer, count * sizeof(TexelLight), mode == Mode::bake ? "texel static lights" : "texel lights");
    m.write(cmd, lists, list, mode == Mode::bake ? "texel static light lists" : "texel light lists");
    Impl::upload(cmd, buffer, bytes_of(lights.first(count)));
    cmd.barrier_transfer_to_compute();
    TexelPush push = m.push;
    push.counts.z = std::uint32_t(count);
    push.counts.w = mode == Mode::bake ? 0u : 1u;
    cmd.bind(m.light);
    // Bake reads no baked light: binding 5 is then the (unread) realtime output, so no
    // buffer is both read and written.
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .storage_buffer(0, m.triangles)
                             .storage_buffer(1, m.placements)
                             .storage_buffer(2, m.surfaces)
                             .storage_buffer(3, buffer)
                             .storage_buffer(4, m.walls)
                             .storage_buffer(5, mode == Mode::bake ? m.lit : m.baked)
                             .storage_buffer(6, mode == Mode::bake ? m.baked : m.lit)
                             .storage_buffer(7, lists));
    cmd.push_constants(push);
    cmd.dispatch(m.groups());
    cmd.barrier_compute_to_compute();
}

const gpu::Buffer& TexelPasses::surfaces() const { return impl_->surfaces; }
const gpu::Buffer& TexelPasses::baked() const { return impl_->baked; }
const gpu::Buffer& TexelPasses::lit() const { return impl_->lit; }
const gpu::Buffer& TexelPasses::albedo() const { return impl_->albedo; }
std::uint32_t TexelPasses::texel_count() const { return impl_->push.counts.x; }

} // namespace lantern::texel::vk
