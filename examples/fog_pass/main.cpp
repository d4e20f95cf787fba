// The fog pass's test: one frame of a lit room on the Vulkan device and on the C++ reference
// through the same pass table; the fog must agree texel by texel (half floats: within two
// units in the last place). Exit 77 (skipped) without a Vulkan device.
#include "fog.hpp"

#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/scene/loader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

int main() {
    using namespace lantern;
    const gi::Tex fogged = fog::register_fog();
    auto scene = scene::parse_scene(R"({
      "lantern_scene": 1,
      "world": { "rows": ["############", "#..........#", "#..##......#", "#......#...#", "#..........#", "############"] },
      "view": { "center": [6.0, 3.0], "size": [12.0, 6.0] },
      "gi": { "resolution": 4, "padding": 1.0, "heat_rounds": 6 },
      "point_lights": [ { "position": [3.5, 3.5], "color": [1.0, 0.7, 0.4], "intensity": 2.0, "radius": 7.0 } ]
    })", "room.json", "");
    if (!scene) {
        std::fprintf(stderr, "%s\n", scene.error().message.c_str());
        return 1;
    }
    const auto window = gi::compute_window(scene->view, scene->gi);
    const gi::FrameInputs in = gi::gather_frame_inputs(*scene, *window);
    const gi::PassPlan plan = gi::plan_passes(in, false);
    bool planned = false;
    for (const gi::PassRow* row : gi::method(scene::GiMethod::heat).rows)
        if (row->name == "fog") planned = plan.run.has(row->pass);
    if (!planned) {
        std::fprintf(stderr, "the fog row is not planned\n");
        return 1;
    }
    auto device = gpu::Device::create();
    if (!device) {
        std::printf("skipped: %s\n", device.error().message.c_str());
        return 77;
    }
    auto renderer = gi::vk::Renderer::create(**device);
    if (!renderer) {
        std::fprintf(stderr, "%s\n", renderer.error().message.c_str());
        return 1;
    }
    auto gpu = gi::run_vulkan_frame(**renderer, in, plan);
    if (!gpu) {
        std::fprintf(stderr, "%s\n", gpu.error().message.c_str());
        return 1;
    }
    const gi::FrameResult ref = gi::run_reference_frame(in, plan);
    const gi::Texture& a = gpu->textures.at(gi::tex_name(fogged));
    const gi::Texture& b = ref.textures.at(gi::tex_name(fogged));
    int bad = 0;
    float worst = 0.0f;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 4; ++c) {
                const float u = a.at(x, y)[c], v = b.at(x, y)[c];
                const float allowed = 2.0f * std::max(std::max(std::abs(u), std::abs(v)) * std::ldexp(1.0f, -10), std::ldexp(1.0f, -24));
                worst = std::max(worst, std::abs(u - v) / allowed);
                bad += std::abs(u - v) > allowed;
            }
    std::printf("fog on %s against the reference: %d of %d values outside two half ulps (worst %.2f x)\n",
                (*device)->name().c_str(), bad, a.width * a.height * 4, double(worst));
    return bad == 0 ? 0 : 1;
}
