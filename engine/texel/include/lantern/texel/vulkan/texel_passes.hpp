// The texel passes on Vulkan (texel.hpp; shaders texel_uv_to_world.comp and
// texel_light.comp): the scene's buffers on the GPU, and the two passes recorded into the
// caller's command list.
//
//   auto passes = TexelPasses::create(device);
//   gpu::CommandList cmd = device.begin("texels");
//   passes->record_plan(cmd, frame, plan_texel_frame(frame, history)); // the pass table's way
//
// or the passes one by one:
//   passes->upload_scene(cmd, scene);                    // triangles, placements, maps, walls
//   passes->record_uv_to_world(cmd);                     // surfaces(), once per layout/move
//   passes->record_light(cmd, static_lights, Mode::bake); // baked(), when static lights change
//   passes->record_light(cmd, lights, Mode::realtime);   // lit() = saturate(sum + baked())
//   device.submit(std::move(cmd));
//
// Buffers are storage buffers of the texel.hpp structs (surfaces(): TexelSurface per atlas
// texel; baked(), lit() and albedo(): vec4 per atlas texel), grown as scenes grow, the baked
// light cleared whenever the atlas is reallocated. Uploads of up to 1 MiB travel inside the
// command buffer (no staging memory per call). Every record_* call leaves a compute-to-compute
// barrier after its writes, so later dispatches (and the raster, after a
// barrier_compute_to_graphics) may read them.
//
// Threads: the Device's submission thread. Ownership: move-only GPU handles, destroyed
// (deferred) before the Device.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gpu/buffer.hpp"
#include "lantern/gpu/pipeline.hpp"
#include "lantern/texel/pass_table.hpp"
#include "lantern/texel/texel.hpp"

#include <memory>
#include <span>

namespace lantern::gpu {
class CommandList;
class Device;
} // namespace lantern::gpu

namespace lantern::texel::vk {

// How much TexelPasses' buffers hold from the start (they grow past it, doubling, and never
// shrink): a game that reserves its largest view allocates nothing while it plays.
struct TexelCapacity {
    std::uint32_t texels = 0, triangles = 0, placements = 0, lights = 0, wall_cells = 0;
};

// Where record_plan marks each row it records (a GPU timer's regions, named by the row).
class TexelRowTimer {
  public:
    virtual ~TexelRowTimer() = default;
    virtual std::uint32_t begin(gpu::CommandList& cmd, const char* row) = 0;
    virtual void end(gpu::CommandList& cmd, std::uint32_t region) = 0;
};

class TexelPasses {
  public:
    enum class Mode { bake, realtime };

    using Capacity = TexelCapacity;

    static Result<std::unique_ptr<TexelPasses>> create(gpu::Device& device, const Capacity& reserve = {});
    ~TexelPasses();
    TexelPasses(const TexelPasses&) = delete;
    TexelPasses& operator=(const TexelPasses&) = delete;

    // The plan's uploads and rows (pass_table.hpp), each row between `timer`'s marks.
    void record_plan(gpu::CommandList& cmd, const TexelFrame& frame, const TexelPlan& plan,
                     TexelRowTimer* timer = nullptr);

    // Writes the scene's triangles, placements, normal maps and wall patch (when this list
    // runs). A scene with more texels than the atlas holds reallocates it (doubling), which
    // clears the bake; a new layout needs a new bake anyway.
    void upload_scene(gpu::CommandList& cmd, const TexelScene& scene);
    // Only the triangles and placements (a moved placement: move_placement), then
    // record_uv_to_world again.
    void upload_triangles(gpu::CommandList& cmd, const TexelScene& scene);
    // Only the wall patch (walls mined or built; the same placements).
    void upload_walls(gpu::CommandList& cmd, const TexelScene& scene);
    // The colour of every atlas texel (texel_count() of them), for the raster: albedo().
    // The passes do not read it; it lives here so the atlas is one owner's.
    void upload_albedo(gpu::CommandList& cmd, std::span<const glm::vec4> albedo);
    // UV to world for every texel of the uploaded scene: surfaces(); with `placements`
    // (ascending), for their texels only.
    void record_uv_to_world(gpu::CommandList& cmd);
    void record_uv_to_world(gpu::CommandList& cmd, std::span<const std::uint32_t> placements);
    // The light pass over every texel: bake writes baked() (raw sums of `lights`), realtime
    // writes lit() = saturate(sums + baked()). At most 65536 lights. Each texel loops over its
    // placement's light list (light_lists: the lights that reach it).
    void record_light(gpu::CommandList& cmd, std::span<const TexelLight> lights, Mode mode);

    const gpu::Buffer& surfaces() const;
    const gpu::Buffer& baked() const;
    const gpu::Buffer& lit() const;
    const gpu::Buffer& albedo() const;
    std::uint32_t texel_count() const;

  private:
    struct Impl;
    explicit TexelPasses(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace lantern::texel::vk
