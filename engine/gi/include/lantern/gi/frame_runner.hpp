// One GI frame, start to finish, on either backend, returning every texture it produced by
// name (the --dump names: conduction, ao, direct, shadow, wall_direct_px, ..., emission,
// indirect, wall_indirect_px, ...) and the lit image. Used by lantern-render, the tests and
// the benchmarks; the game drives vk::Renderer pass by pass instead.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gi/passes.hpp"
#include "lantern/gi/shading.hpp"
#include "lantern/gi/texture.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace lantern::gi {

namespace vk {
class Renderer;
}

struct PartReport {
    std::string name;    // PassRecorder::begin_part's
    double gpu_ms = 0.0; // within its pass's gpu_ms
};

struct PassReport {
    Pass pass;
    bool ran = false;
    std::string reason; // why it was left out
    double gpu_ms = 0.0; // timestamps (Vulkan) or wall time (reference)
    std::vector<PartReport> parts; // timed parts of the pass (Vulkan), summed by name
};

struct FrameResult {
    std::map<std::string, Texture> textures; // only those the frame produced
    std::optional<Image> lit;
    std::vector<PassReport> passes; // every pass, in pipeline order
    double total_ms = 0.0;          // sum of pass times
    double cpu_record_ms = 0.0;     // recording + submission on the CPU (Vulkan)
};

FrameResult run_reference_frame(const FrameInputs& in, const PassPlan& plan, const RefOptions& options = {});
// Uploads, records the plan, submits, waits, reads everything back. Errors: the window does
// not fit the device, too many lights for one pass.
Result<FrameResult> run_vulkan_frame(vk::Renderer& renderer, const FrameInputs& in, const PassPlan& plan,
                                     bool read_textures = true);

} // namespace lantern::gi
