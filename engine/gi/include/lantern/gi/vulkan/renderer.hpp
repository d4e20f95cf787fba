// The Vulkan GI backend: persistent GI textures on a gpu::Device, recorded by the rows of
// the pass table (pass_table.hpp; each row's recorder sees a vk::PassRecorder). The frame
// systems (and lantern-render) decide which passes to record; the renderer records them
// with timestamps and keeps the results for the next frame.
//
// Storage (docs/gi.md, "Memory layout"): every GI texture is a buffer of pitch x height
// texels (pitch = width rounded up to 4) written by the shaders as 32/64-bit words and read
// back through uniform texel buffer views. Each invocation computes a block of 4 x block_h
// texels. Chosen by measurement on lavapipe: see docs/gi.md and lantern-bench-gi.
//
// Threads: a Renderer belongs to the submission thread of its Device.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/passes.hpp"
#include "lantern/gi/texture.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/gpu/reflect.hpp"

#include <array>
#include <map>
#include <typeindex>
#include <utility>
#include <memory>
#include <cstdint>
#include <optional>
#include <span>
#include <tuple>
#include <string>
#include <vector>

namespace lantern::gi::vk {

template <typename P>
struct GiPush;         // lantern/gi/vulkan/pass_params.hpp
struct NoParams;
using GiPassParams = GiPush<NoParams>;
struct PassState;      // lantern/gi/vulkan/pass_recorder.hpp
struct PipelineSpec;

// The textures are the pass table's (pass_table.hpp); these names keep vk:: code short.
using gi::Tex;
using gi::tex_count;
using gi::tex_name;

struct RendererOptions {
    std::uint32_t block_h = 0;      // texel rows per invocation; 0 = by device type
    std::uint32_t group_x = 0;      // workgroup size in blocks; 0 = by device type
    std::uint32_t group_y = 0;
    // The direct pass records only the workgroups whose lights changed since it last ran,
    // and runs the ones no light reaches without its light loops (docs/gi.md, "Dirty light
    // bins"). The results are the same bit for bit; false records every workgroup the one
    // way (benchmarks compare the two).
    // With it the heat pass also keeps its tap masks while the window, the walls and its
    // settings stay (a torch's flicker reruns the heat, not the masks).
    bool dirty_bins = true;
    // Memory for the direct pass's proxy lists per (workgroup, point light, sub-block): the
    // finest sub-blocks whose lists fit (docs/gi.md, "Proxy lists per light and sub-bin");
    // beyond it, one list per workgroup. The results are the same; only the time differs.
    std::uint64_t proxy_list_bytes = std::uint64_t(16) << 20;
};

struct PassTiming {
    Pass pass;
    double gpu_ms = 0.0;
    gpu::TimestampRegion region; // raw and CPU-clock times (for the profiler's GPU lane)
    // A timed part of the pass (PassRecorder::begin_part: "light bins"), measured inside the
    // pass's own region; nullptr for the whole pass. Sum only the wholes.
    const char* part = nullptr;
};

struct FrameTimings {
    std::uint64_t frame = 0;
    std::vector<PassTiming> passes;
};

class Renderer {
  public:
    static Result<std::unique_ptr<Renderer>> create(gpu::Device& device, const RendererOptions& options = {});
    ~Renderer();

    gpu::Device& device() { return device_; }

    // (Re)allocates the textures a frame with this window and plan needs (same size: kept).
    // An error when the window does not fit the device's buffer limits.
    Result<void> prepare(const FrameInputs& in, const PassPlan& plan);
    // Uploads the whole wall buffer (first frame, or when the grid's size changed).
    void upload_walls(gpu::CommandList& cmd, const WallView& walls);
    // Uploads only the changed byte ranges of the wall buffer (streaming, edits).
    void update_walls(gpu::CommandList& cmd, const WallView& walls, std::span<const WallRange> ranges);
    std::uint64_t wall_bytes_uploaded() const { return wall_bytes_uploaded_; }
    // Blocking copy of the GPU wall buffer (tests: it must equal the CPU mirror).
    std::vector<std::uint8_t> read_back_walls();
    // Records the light, proxy and sun data of `in` (small: copied into the command buffer).
    void upload_lights(gpu::CommandList& cmd, const FrameInputs& in);
    // RendererOptions::proxy_list_bytes from the next frame recorded on.
    void set_proxy_list_bytes(std::uint64_t bytes) { proxy_list_bytes_ = bytes; }

    // Records one pass (with its timestamps and the barriers it needs after it).
    void record(gpu::CommandList& cmd, Pass pass, const FrameInputs& in, const PassPlan& plan);
    // Records every pass of `plan` in pipeline order; passes left out clear what they own
    // when later passes read it.
    void record_plan(gpu::CommandList& cmd, const FrameInputs& in, const PassPlan& plan);
    // Records the passes of `plan` that are in `subset` (the others keep last frame's results:
    // the caller knows they are still valid).
    void record_plan(gpu::CommandList& cmd, const FrameInputs& in, const PassPlan& plan, PassSet subset);

    // Starts a query set for the passes recorded into `cmd` (`frame`: the caller's frame
    // number, returned with the timings). Three sets rotate; a set is read before reuse.
    void begin_frame(gpu::CommandList& cmd, std::uint64_t frame = 0);
    // Timings of recorded frames whose submissions completed, oldest first, each returned
    // once. Never blocks.
    std::vector<FrameTimings> completed_timings();
    // Blocks until the frame begun last completed, then returns its pass durations (tools).
    std::vector<PassTiming> wait_timings();

    bool has(Tex t) const { return bool(textures_[int(t)].buffer); }
    glm::ivec2 size(Tex t) const { return {textures_[int(t)].width, textures_[int(t)].height}; }
    // Read access for raster passes (the game's world renderer): the texture's uniform texel
    // buffer view (R8_UNORM, R8G8_UNORM or R16G16B16A16_SFLOAT as its format is; R8G8B8A8_UNORM
    // for the lit image and the heat tap masks), or nullptr when the texture is not allocated.
    // Texel (x, y) is element y * pitch(t) + x; every texture of one window has the same
    // pitch (its width rounded up to 4; heat textures at other scales have their own).
    // Valid until the next prepare() (which may reallocate); written by the passes recorded
    // before: put cmd.barrier_compute_to_graphics() between them and the reads.
    const gpu::BufferView* view(Tex t) const {
        const GpuTexture& g = textures_[int(t)];
        return g.buffer ? &g.view : nullptr;
    }
    int pitch(Tex t) const { return textures_[int(t)].pitch; } // 0 when not allocated
    // The wall grid (R8_UINT, 1 = wall) as uploaded by upload_walls/update_walls, laid out as
    // FrameInputs::walls (toroidal, see gi_walls.glsl). An empty view before upload_walls.
    const gpu::BufferView& walls_view() const { return walls_view_; }
    // Blocking read back into the C++ texture representation (tests and tools).
    Texture read_back(Tex t);
    Texture read_back(Tex t, const char* name);
    // The lit image as RGB8 (after Pass::lit ran).
    std::vector<std::uint8_t> read_back_lit_rgb();

    std::uint32_t block_h() const { return block_h_; }
    std::uint32_t group_x() const { return group_x_; }
    std::uint32_t group_y() const { return group_y_; }

    // Workgroups of a pass that can record only part of its work (the direct and mixed
    // passes keep the workgroups whose lights did not change: docs/gi.md, "Dirty light
    // bins"; the heat pass keeps its tap masks while the window and walls stay: its count
    // is the masks' workgroups), summed over every frame recorded: how many it had, and how
    // many it recorded.
    struct PartialWork {
        std::uint64_t workgroups = 0;
        std::uint64_t recorded = 0;
    };
    PartialWork partial_work(Pass pass) const { return partial_work_[std::size_t(pass)]; }

    // Benchmark baseline: GPU time (ms, median of `repeats`) of the copy kernel (texel-buffer
    // read, one 64-bit word written per texel: the GI passes' access pattern) run as one
    // dispatch per entry of `bytes_written`, each writing that many bytes. Blocking.
    double time_copy_dispatches(const std::vector<std::uint64_t>& bytes_written, int repeats = 5);
    // Bytes each dispatch of `pass` writes for this frame (same order as record()).
    static std::vector<std::uint64_t> pass_bytes_written(Pass pass, const FrameInputs& in);

  private:
    struct GpuTexture {
        gpu::Buffer buffer;
        gpu::BufferView view;
        gpu::BufferView view_u32; // 32-bit word textures (lit, heat_mask): R32_UINT view
        TexFormat format = TexFormat::rgba16f;
        int width = 0, height = 0, pitch = 0;
        bool rgba8 = false;
        std::uint64_t serial = 0; // which allocation this is (unique per renderer)
    };
    struct Pipelines;
    struct QuerySet;
    friend class PassRecorder;
    explicit Renderer(gpu::Device& device);

    void ensure_texture(Tex t, TexFormat format, int width, int height, bool rgba8 = false);
    void drop_texture(Tex t);
    void clear(gpu::CommandList& cmd, Tex t);
    GiPassParams params(const FrameInputs& in, int width, int height) const;
    void dispatch_blocks(gpu::CommandList& cmd, int width, int height);
    // The workgroups dispatch_blocks dispatches over a width x height texture.
    glm::uvec2 block_groups(int width, int height) const;
    const gpu::ComputePipeline& pipeline(ShaderLookup shaders, const char* shader, const PipelineSpec& spec,
                                         std::span<const gpu::ScalarKind> kinds);
    void prefetch_pipeline(ShaderLookup shaders, const char* shader, const PipelineSpec& spec,
                           std::span<const gpu::ScalarKind> kinds);
    static FrameTimings collect_timings(const QuerySet& set, const gpu::TimestampResult& result);
    static constexpr std::uint32_t no_part = ~0u;
    std::uint32_t begin_part(gpu::CommandList& cmd, Pass pass, const char* part);
    void end_part(gpu::CommandList& cmd, std::uint32_t region);

    gpu::Device& device_;
    std::unique_ptr<Pipelines> pipelines_;
    std::array<GpuTexture, tex_count> textures_;
    gpu::Buffer walls_;
    gpu::BufferView walls_view_;
    std::uint64_t wall_bytes_uploaded_ = 0;
    std::uint64_t texture_serial_ = 0;
    std::array<PartialWork, pass_count> partial_work_{};
    // record_plan's count of plans, and per pass the last plan it was not in (PassRecorder::planned_since).
    std::uint64_t plans_ = 0;
    std::array<std::uint64_t, pass_count> unplanned_{};
    bool dirty_bins_ = true;
    std::uint64_t proxy_list_bytes_ = std::uint64_t(16) << 20;
    gpu::Buffer lights_, proxies_, suns_; // uniform buffers, written with update_buffer
    // Each row's own GPU state, one object per row and state type (a row may keep several:
    // the mixed row keeps the direct pass's and the suns' pass's).
    std::map<std::pair<const PassRow*, std::type_index>, std::unique_ptr<PassState>> states_;
    std::vector<QuerySet> queries_;
    std::vector<FrameTimings> resolved_; // read from a set before its reuse, not yet returned
    int frame_slot_ = -1;
    std::uint32_t block_h_ = 4, group_x_ = 8, group_y_ = 8;
};

} // namespace lantern::gi::vk
