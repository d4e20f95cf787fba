// GPU timings of a frame's render passes (scene, upscale, overlay, ...) with
// gpu::TimestampQueries, one query set per frame in a ring, read without stalling.
//
//   auto timer = PassTimer::create(device);           // an error where the queue has no timestamps
//   timer->begin_frame(cmd, frame_number);            // before any pass, outside rendering scopes
//   auto scene = timer->begin(cmd, "scene"); ...; timer->end(cmd, scene);
//   device.submit(...) / swapchain.present(...);
//   for (const FrameTimings& t : timer->take_completed())  // frames the GPU finished
//       for (const gpu::TimestampRegion& pass : t.passes) hud.add(pass.name, pass.duration_ns);
//
// The ring has frames_in_flight + 1 sets: begin_frame reuses the set of three frames ago,
// reading it first; that frame has completed whenever the Swapchain paces the frames, so
// begin_frame only blocks when more frames are in flight. Feed results to the profiler with
// gpu::record_gpu_timestamps.
// Ownership: move-only; destroy before the Device. Threads: the submission thread.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gpu/timestamps.hpp"

#include <cstdint>
#include <vector>

namespace lantern::gpu {
class CommandList;
class Device;
} // namespace lantern::gpu

namespace lantern::render {

struct FrameTimings {
    std::uint64_t frame = 0;                  // as given to begin_frame
    std::vector<gpu::TimestampRegion> passes; // in begin() order
};

class PassTimer {
  public:
    static constexpr std::uint32_t ring_size = 3;

    static Result<PassTimer> create(gpu::Device& device, std::uint32_t max_passes = 8);
    PassTimer() = default;

    // Starts timing `frame` in `cmd`. Each frame's passes go into one command list.
    void begin_frame(gpu::CommandList& cmd, std::uint64_t frame);
    // At most max_passes per frame; `pass` must outlive the results (a string literal).
    std::uint32_t begin(gpu::CommandList& cmd, const char* pass);
    void end(gpu::CommandList& cmd, std::uint32_t pass);

    // Timings of the frames whose submissions completed, oldest first, each returned once.
    // Never blocks.
    std::vector<FrameTimings> take_completed();

  private:
    struct Set {
        gpu::TimestampQueries queries;
        std::uint64_t frame = 0;
        bool pending = false; // recorded, results not yet taken
    };
    void collect(Set& set, const gpu::TimestampResult& result);

    std::vector<Set> sets_;
    std::uint32_t current_ = 0;
    std::vector<FrameTimings> done_; // read before reuse, not yet taken
};

} // namespace lantern::render
