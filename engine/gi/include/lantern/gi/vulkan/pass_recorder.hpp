// What a pass row's Vulkan recorder sees (pass_table.hpp): the frame, the command list, the
// renderer's textures (by Tex), wall grid and light buffers, the GI pipelines (from the
// row's shader library), the dispatch and clear helpers, the iteration and history of the
// row, and a state object of its own that lives as long as the renderer.
//
// Threads: a PassRecorder lives for one call of a row's recorder, on the renderer's
// submission thread. Ownership: it borrows everything; what it returns (buffers, views,
// pipelines) belongs to the renderer and is valid until the next Renderer::prepare.
#pragma once

#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gi/vulkan/pass_params.hpp"

#include <memory>
#include <typeindex>
#include <typeinfo>

namespace lantern::gi::vk {

// Persistent GPU state a row keeps between frames (a weight table, light bins): one object
// per row, type and renderer, created on first use by PassRecorder::state<T>().
struct PassState {
    virtual ~PassState() = default;
};

// The specialisation constants of a GI pipeline (pass_params.hpp, SpecId).
struct PipelineSpec {
    bool proxies = true;
    bool walls = true;
    bool per_channel = true;
    bool segment_check = true;
    std::uint32_t block_h = 0, group_x = 0, group_y = 0; // 0: the renderer's
    // The pass's own compile-time switches (FEATURES): code a frame does not use is compiled
    // out rather than branched over. Lavapipe keeps a shader variant per value of every
    // push-constant word that decides a branch, so lean shaders also keep those variants small.
    std::uint32_t features = 0;
    std::uint32_t faces = 15; // computed_faces (FACES): constant for a configuration, so compiled in
    // Every proxy's penumbra power is 1 (LINEAR_PENUMBRA): the penumbras' pow compiled out.
    // PassRecorder sets it from the frame wherever `proxies` is set.
    bool linear_penumbra = false;
    // The frame's proxies fit two words of a proxy mask and its point lights are not too many
    // (PROXY_REGISTERS, pass_params.hpp): the proxy loops of the passes that visit a mask keep
    // its words in registers. Set by PassRecorder likewise.
    bool proxy_registers = false;
};

class PassRecorder {
  public:
    PassRecorder(Renderer& renderer, gpu::CommandList& command_list, const FrameInputs& inputs,
                 const PassPlan& frame_plan, const PassRow& row, int iteration_index = 0)
        : cmd(command_list), in(inputs), plan(frame_plan), iteration(iteration_index),
          history(frame_plan.history[int(row.pass)]), r_(renderer), row_(row) {}

    gpu::CommandList& cmd;
    const FrameInputs& in;
    const PassPlan& plan;
    const int iteration; // 0 .. iterations - 1 (PassRow::iterations)
    const int history;   // converging rows: frames accumulated before this one (0: afresh)

    gpu::Device& device() { return r_.device_; }
    bool has(Tex t) const { return r_.has(t); }
    const gpu::Buffer& buffer(Tex t) const { return texture(t).buffer; }
    const gpu::BufferView& view(Tex t) const { return texture(t).view; }
    const gpu::BufferView& view_u32(Tex t) const { return texture(t).view_u32; } // words32 textures
    int pitch(Tex t) const { return texture(t).pitch; }
    // Which allocation of `t` this is: a texture reallocated (a new size, or released and
    // allocated again) holds nothing of what was written before.
    std::uint64_t serial(Tex t) const { return texture(t).serial; }
    const PassRow& row() const { return row_; }
    // The plans record_plan has recorded, this frame's included (0 before the first), and
    // whether this row was in every one after plan `serial` (a row out of the plan leaves
    // its outputs to whatever else writes them then: another method's rows, the baked row).
    std::uint64_t plan_serial() const { return r_.plans_; }
    bool planned_since(std::uint64_t serial) const { return r_.unplanned_[std::size_t(row_.pass)] <= serial; }
    // RendererOptions::dirty_bins.
    bool dirty_bins() const { return r_.dirty_bins_; }
    std::uint64_t proxy_list_bytes() const { return r_.proxy_list_bytes_; }
    // This pass recorded `recorded` of its `workgroups` (Renderer::partial_work).
    void count_workgroups(std::uint64_t workgroups, std::uint64_t recorded) {
        Renderer::PartialWork& w = r_.partial_work_[std::size_t(row_.pass)];
        w.workgroups += workgroups;
        w.recorded += recorded;
    }
    const gpu::BufferView& walls() const { return r_.walls_view_; }
    const gpu::Buffer& lights() const { return r_.lights_; }
    const gpu::Buffer& proxies() const { return r_.proxies_; }
    const gpu::Buffer& suns() const { return r_.suns_; }
    std::uint32_t block_h() const { return r_.block_h_; }
    std::uint32_t group_x() const { return r_.group_x_; }
    std::uint32_t group_y() const { return r_.group_y_; }
    // Whether each block of this frame's window lies in one wall tile (window.hpp).
    bool blocks_in_one_tile() const { return gi::blocks_in_one_tile(in.window, r_.block_h_); }

    // The pipeline of a shader of the row's library (PassRow::shaders; the engine's
    // lantern_gi_shaders by default: "gi_ao.comp") whose parameters are P (GI_PASS_PARAMS in
    // the shader), created on first use; its push-constant block is then checked against
    // GiPush<P> and its bindings come from the shader itself.
    template <typename P = NoParams>
    const gpu::ComputePipeline& pipeline(const char* shader, const PipelineSpec& spec = {}) {
        const std::array<gpu::ScalarKind, 8> kinds = field_kinds<P>();
        return r_.pipeline(row_.shaders, shader, frame_spec(spec), kinds);
    }
    // Starts creating that pipeline on a background thread (a variant a later frame may need:
    // creating it then would stall that frame).
    template <typename P = NoParams>
    void prefetch_pipeline(const char* shader, const PipelineSpec& spec = {}) {
        const std::array<gpu::ScalarKind, 8> kinds = field_kinds<P>();
        r_.prefetch_pipeline(row_.shaders, shader, frame_spec(spec), kinds);
    }
    // `spec` with what the frame decides filled in (linear_penumbra, proxy_registers).
    PipelineSpec frame_spec(PipelineSpec spec) const {
        spec.linear_penumbra = spec.proxies && penumbras_linear(in);
        spec.proxy_registers = spec.proxies && in.proxies.size() <= proxy_register_count &&
                               in.point_lights.size() <= proxy_register_lights;
        return spec;
    }
    // The push constants of a width x height texture: the shared fields (window, grid,
    // counts) filled, `pass` for the caller.
    template <typename P = NoParams>
    GiPush<P> params(int width, int height) const {
        const GiPassParams common = r_.params(in, width, height);
        GiPush<P> p{};
        p.camera_view = common.camera_view;
        p.size = common.size;
        p.grid = common.grid;
        p.counts = common.counts;
        p.grid_phase = common.grid_phase;
        return p;
    }
    // One invocation per block of 4 x block_h texels of a width x height texture.
    void dispatch(int width, int height) { r_.dispatch_blocks(cmd, width, height); }
    // How many workgroups dispatch(width, height) records.
    std::uint64_t dispatch_groups(int width, int height) const {
        const glm::uvec2 g = r_.block_groups(width, height);
        return std::uint64_t(g.x) * g.y;
    }
    void clear(Tex t) { r_.clear(cmd, t); }
    // Times the commands recorded until end_part as a part of this pass (a row of its own
    // under the pass in the pass table: PassTiming::part, PassReport::parts). `name` must
    // outlive the frame's timings (a literal). Untimed where the device has no timestamps.
    std::uint32_t begin_part(const char* name) { return r_.begin_part(cmd, row_.pass, name); }
    void end_part(std::uint32_t part) { r_.end_part(cmd, part); }

    template <typename T>
    T& state() {
        std::unique_ptr<PassState>& slot = r_.states_[{&row_, std::type_index(typeid(T))}];
        if (!slot) slot = std::make_unique<T>();
        return static_cast<T&>(*slot);
    }

  private:
    const Renderer::GpuTexture& texture(Tex t) const {
        const Renderer::GpuTexture& g = r_.textures_[int(t)];
        LANTERN_ASSERT(bool(g.buffer), "a pass records a texture the plan did not allocate");
        return g;
    }

    Renderer& r_;
    const PassRow& row_;
};

} // namespace lantern::gi::vk
