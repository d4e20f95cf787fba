// The GI backend a frame is handed to: Vulkan (the renderer) or the C++ reference. The
// frame systems (systems/gi_frame.hpp: gpu_submit) and tools drive one; the pass table
// (pass_table.hpp) tells it which rows exist, the caller which of them to run.
//
// A backend keeps every texture between frames; each frame it runs only the passes it is
// told to, and the other textures keep last frame's (still valid) results.
//
// Threads: a backend is used from one thread at a time (the frame's submission thread,
// gpu_submit's main thread in the game); the Vulkan backend must be on its Device's
// submission thread. Nothing in it is safe to call concurrently.
// Ownership: make_vulkan_backend borrows the renderer, which must outlive the backend;
// make_reference_backend borrows the job system (may be null). The backend owns its
// textures (GPU buffers or CPU Textures); read() returns copies.
// Failure: an execute() that returns an error has recorded or submitted nothing for that
// frame, but may have reallocated textures (a new window size), so every texture is to be
// treated as stale: the caller reruns every pass next frame (gpu_submit clears the camera's
// cache keys and the convergence history). read() of a texture the failed frame would
// have written returns whatever the backend still holds, or nullopt.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/passes.hpp"
#include "lantern/gi/shading.hpp"
#include "lantern/gi/texture.hpp"

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace lantern::jobs {
class JobSystem;
}

namespace lantern::gi {

namespace vk {
class Renderer;
}

// What changed in the wall buffer since the backend last saw it.
struct WallUpdate {
    bool whole = true;               // upload everything (first frame, new size)
    std::span<const WallRange> ranges; // otherwise only these bytes
};

struct PassTime {
    Pass pass;
    double ms = 0.0;
    std::int64_t cpu_begin_ns = 0, cpu_end_ns = 0; // on the now_ns() clock
};
struct FrameTimes {
    std::uint64_t frame = 0;
    std::vector<PassTime> passes;
};

class Backend {
  public:
    virtual ~Backend() = default;
    virtual std::string name() const = 0;
    // Runs the passes of `run` (within plan.run) for frame `frame`. Vulkan: records and
    // submits (at most two frames in flight), never waits for this frame. Errors: the
    // window does not fit the device, too many lights for one pass (see "Failure" above).
    virtual Result<void> execute(std::uint64_t frame, const FrameInputs& in, const PassPlan& plan, PassSet run,
                                 const WallUpdate& walls) = 0;
    // Timings of frames that completed since the last call (never blocks).
    virtual std::vector<FrameTimes> completed_times() = 0;
    // Blocking: waits for all work, then reads a texture by its --dump name (the contract
    // textures only); nullopt when the backend does not hold it.
    virtual std::optional<Texture> read(const std::string& name) = 0;
    virtual std::optional<Image> read_lit() = 0;
    // The contract textures currently allocated, by --dump name.
    virtual std::vector<std::string> texture_names() const = 0;
    virtual void wait_idle() = 0;
};

std::unique_ptr<Backend> make_vulkan_backend(vk::Renderer& renderer);
// `jobs` (optional) runs the reference's rows in parallel.
std::unique_ptr<Backend> make_reference_backend(jobs::JobSystem* jobs);

} // namespace lantern::gi
