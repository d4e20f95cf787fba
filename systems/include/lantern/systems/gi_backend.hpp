// The GI backend the GPU-submission system drives: Vulkan (the renderer) or the C++
// reference. A backend keeps every texture between frames; each frame it runs only the
// passes it is told to, and the other textures keep last frame's (still valid) results.
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

namespace lantern::gpu {
class Device;
}
namespace lantern::jobs {
class JobSystem;
}
namespace lantern::gi::vk {
class Renderer;
}

namespace lantern::systems {

// What changed in the wall buffer since the backend last saw it.
struct WallUpdate {
    bool whole = true;                   // upload everything (first frame, new size)
    std::span<const gi::WallRange> ranges; // otherwise only these bytes
};

struct PassTime {
    gi::Pass pass;
    double ms = 0.0;
    std::int64_t cpu_begin_ns = 0, cpu_end_ns = 0; // on the now_ns() clock
};
struct FrameTimes {
    std::uint64_t frame = 0;
    std::vector<PassTime> passes;
};

class GiBackend {
  public:
    virtual ~GiBackend() = default;
    virtual std::string name() const = 0;
    // Runs the passes of `run` (within plan.run) for frame `frame`. Vulkan: records and
    // submits (at most two frames in flight), never waits for this frame.
    virtual Result<void> execute(std::uint64_t frame, const gi::FrameInputs& in, const gi::PassPlan& plan,
                                 gi::PassSet run, const WallUpdate& walls) = 0;
    // Timings of frames that completed since the last call (never blocks).
    virtual std::vector<FrameTimes> completed_times() = 0;
    // Blocking: waits for all work, then reads a texture by its --dump name (the contract
    // textures only); nullopt when the backend does not hold it.
    virtual std::optional<gi::Texture> read(const std::string& name) = 0;
    virtual std::optional<gi::Image> read_lit() = 0;
    // The contract textures currently allocated, by --dump name.
    virtual std::vector<std::string> texture_names() const = 0;
    virtual void wait_idle() = 0;
};

std::unique_ptr<GiBackend> make_vulkan_backend(gi::vk::Renderer& renderer);
// `jobs` (optional) runs the reference's rows in parallel.
std::unique_ptr<GiBackend> make_reference_backend(jobs::JobSystem* jobs);

} // namespace lantern::systems
