// lantern-bench dirty-bins: the direct pass with dirty light bins (docs/gi.md) against the
// same pass recording every workgroup, on seed 000's scene (caves, proxies, a window of the
// seed's size), frame after frame while some of the lights change: one light, a quarter of
// them, all of them (every torch flickering, the game's case), and the same with game-sized
// radii. Two renderers see the same frames, alternating, so both see the same machine; the
// GPU time of the direct pass is the median over the measured frames.
#include "bench.hpp"
#include "seed_scene.hpp"

#include "lantern/core/machine.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/vulkan/renderer.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace lantern::bench {
namespace {

struct Case {
    std::string name;
    int points = 0, emissives = 0;
    float radius = 10.0f; // the point lights' (the seed's: 10; the game's torches 6.5)
    int changing = 0;     // point lights whose intensity changes every frame (the first ones)
};

struct Numbers {
    double dirty_ms = 0.0, all_ms = 0.0;
    double recorded = 0.0; // the share of workgroups the dirty renderer recorded
    int width = 0, height = 0;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

double direct_ms(const gi::FrameResult& f) {
    for (const gi::PassReport& p : f.passes)
        if (p.pass == gi::Pass::direct && p.ran) return p.gpu_ms;
    return 0.0;
}

Result<Numbers> run_case(gi::vk::Renderer& dirty, gi::vk::Renderer& all, const Case& c, int resolution, int frames) {
    SeedRow row;
    row.resolution = resolution;
    row.scale = scene::HeatScale::quarter;
    row.points = c.points;
    row.emissives = c.emissives;
    scene::Scene s = seed_scene(row);
    for (auto& l : s.point_lights) l.radius = c.radius;
    std::string why;
    auto window = gi::compute_window(s.view, s.gi, &why);
    if (!window) return make_error("seed scene has no GI window: " + why, 1);
    Numbers n;
    n.width = window->width, n.height = window->height;
    std::vector<double> dirty_ms, all_ms;
    gi::vk::Renderer::PartialWork measured_from; // after the warm-up frame
    for (int frame = 0; frame <= frames; ++frame) { // frame 0 warms up (pipelines, the first full run)
        for (int i = 0; i < std::min<int>(c.changing, int(s.point_lights.size())); ++i)
            s.point_lights[std::size_t(i)].intensity = 1.5f * (0.85f + 0.15f * float((frame * 7 + i * 3) % 11) / 10.0f);
        const gi::FrameInputs in = gi::gather_frame_inputs(s, *window);
        const gi::PassPlan plan = gi::plan_passes(in, false, gi::Pass::direct);
        auto a = gi::run_vulkan_frame(dirty, in, plan, false);
        if (!a) return a.error();
        auto b = gi::run_vulkan_frame(all, in, plan, false);
        if (!b) return b.error();
        if (frame == 0) {
            measured_from = dirty.partial_work(gi::Pass::direct);
            continue;
        }
        dirty_ms.push_back(direct_ms(*a));
        all_ms.push_back(direct_ms(*b));
    }
    const gi::vk::Renderer::PartialWork after = dirty.partial_work(gi::Pass::direct);
    n.dirty_ms = median(dirty_ms);
    n.all_ms = median(all_ms);
    const double workgroups = double(after.workgroups - measured_from.workgroups);
    n.recorded = workgroups > 0 ? double(after.recorded - measured_from.recorded) / workgroups : 0.0;
    return n;
}

} // namespace

int dirty_bins(const DirtyBinsOptions& o) {
    auto device = gpu::Device::create();
    if (!device) {
        std::fprintf(stderr, "lantern-bench: %s\n", device.error().message.c_str());
        return 1;
    }
    auto dirty = gi::vk::Renderer::create(**device);
    auto all = gi::vk::Renderer::create(**device, {.dirty_bins = false});
    if (!dirty || !all) {
        std::fprintf(stderr, "lantern-bench: %s\n", (!dirty ? dirty.error() : all.error()).message.c_str());
        return 1;
    }
    std::printf("lantern-bench dirty-bins\ndevice: %s\nmachine: %s\ngiRes %d, seed 000's scene (caves, 38 proxies); "
                "the direct pass's GPU time, median of %d frames after a warm-up, the two renderers alternating\n\n",
                (*device)->name().c_str(), describe_machine().c_str(), o.resolution, o.frames);
    const std::vector<Case> cases = {
        {"64 point + 256 emissive, one light changes", 64, 256, 10.0f, 1},
        {"64 point + 256 emissive, 16 lights change", 64, 256, 10.0f, 16},
        {"64 point + 256 emissive, every point light changes", 64, 256, 10.0f, 64},
        {"game-like: 6 lights of radius 6.5, one changes", 6, 0, 6.5f, 1},
        {"game-like: 6 lights of radius 6.5, all change", 6, 0, 6.5f, 6},
        {"one light of radius 6.5, it changes", 1, 0, 6.5f, 1},
    };
    std::printf("| case | window (texels) | workgroups recorded | direct, dirty bins (ms) | direct, every bin (ms) | "
                "speed-up |\n|---|---|---|---|---|---|\n");
    for (const Case& c : cases) {
        auto r = run_case(**dirty, **all, c, o.resolution, o.frames);
        if (!r) {
            std::fprintf(stderr, "lantern-bench: %s: %s\n", c.name.c_str(), r.error().message.c_str());
            return 1;
        }
        std::printf("| %s | %d x %d | %.0f %% | %.2f | %.2f | %.2fx |\n", c.name.c_str(), r->width, r->height,
                    100.0 * r->recorded, r->dirty_ms, r->all_ms, r->dirty_ms > 0 ? r->all_ms / r->dirty_ms : 0.0);
        std::fflush(stdout);
    }
    return 0;
}

} // namespace lantern::bench
