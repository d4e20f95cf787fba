// Per-texel lighting (engine::texel, docs/texel.md): GPU time of the two passes on a game-like
// scene, and the C++ reference's time for the same work on one core. Prints the machine and
// the Vulkan device first.
//
//   lantern-bench-texel [--frames N] [--density T] [--models M]
//
// The scene: a 48 x 48 tile cave (walls about a third of the tiles), M models (a third each
// player-like (body and head), tree-like (trunk and crown) and crates) at T texels per world
// unit, lights that are torches (hard shadows) and lamps (blurred shadows). Reported: UV to
// world for every model and for one moving player (its per-model cost), the light pass for
// 1, 8 and 32 lights, and seed 001's static lights: 24 of the 32 baked (the bake, then the
// realtime pass that skips them on the still models and lights the moving players with
// them). Numbers go in docs/texel.md; compare ratios from one run.
#include "lantern/core/cli.hpp"
#include "lantern/core/machine.hpp"
#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/gpu/timestamps.hpp"
#include "lantern/texel/texel.hpp"
#include "lantern/texel/vulkan/texel_passes.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace lantern;
using namespace lantern::texel;

namespace {

int fail(const std::string& message) {
    std::fprintf(stderr, "lantern-bench-texel: %s\n", message.c_str());
    return 1;
}

Model two_part(const Model& a, const Model& b) {
    Model m;
    m.size = 2 * std::max(a.size, b.size);
    append_triangles(m, a, glm::mat4(1.0f), glm::vec2(0.0f), glm::vec2(0.5f));
    append_triangles(m, b, glm::mat4(1.0f), glm::vec2(0.5f, 0.0f), glm::vec2(0.5f));
    return m;
}

double now_ms() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

} // namespace

int main(int argc, char** argv) {
    int frames = 9, density = 16, models = 24;
    cli::Parser args("lantern-bench-texel", "[--frames N] [--density T] [--models M]",
                     "GPU time of the per-texel lighting passes on a game-like scene, and the C++\n"
                     "reference's time for the same work (docs/texel.md).");
    args.integer("--frames", "N", "runs per case; the minimum and median are reported (default 9)", frames, 2, 1000);
    args.integer("--density", "T", "texels per world unit (default 16)", density, 1, 64);
    args.integer("--models", "M", "models in the scene (default 24)", models, 1, 1000);
    if (auto exit = args.parse(argc, argv)) return *exit;
    std::printf("machine: %s\n", describe_machine().c_str());
    auto device = gpu::Device::create({.application_name = "lantern-bench-texel"});
    if (!device) return fail(device.error().message);
    gpu::Device& dev = **device;
    std::printf("device: %s\n", dev.name().c_str());
    auto created = vk::TexelPasses::create(dev);
    if (!created) return fail(created.error().message);
    vk::TexelPasses& passes = **created;

    const int n = 48;
    scene::WallGrid grid;
    grid.width = grid.height = n;
    grid.cells.assign(std::size_t(n) * n, 0);
    std::mt19937 rng(3);
    for (auto& c : grid.cells) c = rng() % 100 < 33 ? 1 : 0;
    const Model player = two_part(box_model({-0.3f, 0.0f, -0.2f}, {0.3f, 1.0f, 0.2f}, density),
                                  box_model({-0.2f, 1.0f, -0.2f}, {0.2f, 1.4f, 0.2f}, density));
    const Model tree = two_part(box_model({-0.15f, 0.0f, -0.15f}, {0.15f, 0.8f, 0.15f}, density),
                                box_model({-0.6f, 0.8f, -0.6f}, {0.6f, 1.8f, 0.6f}, density));
    const Model crate = box_model({-0.4f, 0.0f, -0.4f}, {0.4f, 0.8f, 0.4f}, density);
    std::vector<Placement> placements;
    std::vector<glm::vec2> open;
    for (int z = 2; z < n - 2; ++z)
        for (int x = 2; x < n - 2; ++x)
            if (!grid.cells[std::size_t(z * n + x)]) open.emplace_back(float(x) + 0.5f, float(z) + 0.5f);
    std::shuffle(open.begin(), open.end(), rng);
    for (int i = 0; i < models && i < int(open.size()); ++i) {
        const Model* m = i % 3 == 0 ? &player : (i % 3 == 1 ? &tree : &crate);
        placements.push_back({m, glm::translate(glm::mat4(1.0f), glm::vec3(open[i].x, 0.0f, open[i].y)), m == &player});
    }
    TexelScene scene = build_scene(placements, gi::WallView::of(grid), 2.0f, 10.0f);
    std::vector<TexelLight> lights;
    for (int i = 0; i < 32; ++i) {
        const glm::vec2 p = open[std::size_t(models + i) % open.size()];
        lights.push_back(i % 4 == 3 ? make_light({p.x, 2.5f, p.y}, {0.6f, 0.7f, 1.0f}, 1.0f, 10.0f, ShadowType::blurred)
                                    : make_light({p.x, 1.2f, p.y}, {1.0f, 0.6f, 0.3f}, 1.5f, 7.0f, ShadowType::hard));
    }
    std::printf("scene: %zu models, %zu triangles, %u texels (%d per unit), cave %dx%d\n", placements.size(),
                scene.triangles.size(), scene.texel_count, density, n, n);

    auto queries = dev.create_timestamp_queries(1, "texel");
    if (!queries) return fail(queries.error().message);
    {
        gpu::CommandList cmd = dev.begin("texel scene");
        passes.upload_scene(cmd, scene);
        dev.wait(dev.submit(std::move(cmd)));
    }
    const auto time_gpu = [&](const char* what, auto&& record) {
        std::vector<double> t;
        for (int i = 0; i < frames; ++i) {
            gpu::CommandList cmd = dev.begin("texel bench");
            queries->reset(cmd);
            const auto region = queries->begin(cmd, "texel");
            record(cmd);
            queries->end(cmd, region);
            dev.submit(std::move(cmd));
            t.push_back(double(queries->resolve().regions[0].duration_ns) * 1e-6);
        }
        std::sort(t.begin(), t.end());
        std::printf("  GPU %-34s %8.3f %8.3f\n", what, t[0], t[t.size() / 2]);
    };
    const auto time_cpu = [&](const char* what, auto&& run) {
        std::vector<double> t;
        for (int i = 0; i < std::min(frames, 3); ++i) {
            const double start = now_ms();
            run();
            t.push_back(now_ms() - start);
        }
        std::sort(t.begin(), t.end());
        std::printf("  C++ %-34s %8.3f %8.3f\n", what, t[0], t[t.size() / 2]);
    };
    std::printf("per case (min / median ms; GPU: %d runs, C++ reference: one core, %d runs):\n", frames,
                std::min(frames, 3));
    time_gpu("uv to world, every model", [&](gpu::CommandList& cmd) { passes.record_uv_to_world(cmd); });
    std::vector<TexelSurface> surfaces;
    const std::vector<glm::vec4> nothing_baked(scene.texel_count, glm::vec4(0.0f)); // the realtime pass's
    time_cpu("uv to world, every model", [&] { surfaces = uv_to_world(scene); });
    time_cpu("uv to world, every model (brute)", [&] { surfaces = uv_to_world_brute(scene); });
    // One player moving: its triangles re-uploaded and its texels carried again, over the
    // whole atlas (one dispatch) and over its own texels (what the pass table plans).
    time_gpu("player moved (upload + uv to world)", [&](gpu::CommandList& cmd) {
        move_placement(scene, 0, player, glm::translate(glm::mat4(1.0f), glm::vec3(open[0].x + 0.1f, 0.0f, open[0].y)));
        passes.upload_triangles(cmd, scene);
        passes.record_uv_to_world(cmd);
    });
    const std::uint32_t moved[] = {0u};
    time_gpu("player moved (upload + its texels)", [&](gpu::CommandList& cmd) {
        move_placement(scene, 0, player, glm::translate(glm::mat4(1.0f), glm::vec3(open[0].x + 0.1f, 0.0f, open[0].y)));
        passes.upload_triangles(cmd, scene);
        passes.record_uv_to_world(cmd, moved);
    });
    time_cpu("player moved (uv to world)", [&] { uv_to_world_placement(scene, 0, surfaces); });
    for (int count : {1, 8, 32}) {
        const std::span<const TexelLight> some(lights.data(), std::size_t(count));
        char name[64];
        std::snprintf(name, sizeof name, "light pass, %d lights", count);
        time_gpu(name, [&](gpu::CommandList& cmd) { passes.record_light(cmd, some, vk::TexelPasses::Mode::realtime); });
        time_cpu(name, [&] { (void)reference_light(scene, surfaces, some, nothing_baked); });
    }
    // Static lights: the first 24 baked (players move: they take those 24 live).
    const std::span<const TexelLight> static_lights(lights.data(), 24);
    std::vector<TexelLight> marked = lights;
    for (int i = 0; i < 24; ++i) marked[std::size_t(i)] = as_baked(lights[std::size_t(i)]);
    time_gpu("bake, 24 static lights", [&](gpu::CommandList& cmd) {
        passes.record_light(cmd, static_lights, vk::TexelPasses::Mode::bake);
    });
    time_gpu("light pass, 32 lights, 24 baked", [&](gpu::CommandList& cmd) {
        passes.record_light(cmd, marked, vk::TexelPasses::Mode::realtime);
    });
    // The pass table's planning (pass_table.hpp), each frame on the CPU: the inputs' keys
    // (hashes of the scene and the lights) and the rows to run.
    // Without a layout key it hashes the atlas's normal maps; the game gives one.
    TexelHistory history;
    time_cpu("plan a frame (pass table)", [&] {
        const TexelFrame frame{scene, marked};
        (void)plan_texel_frame(frame, history);
    });
    time_cpu("plan a frame, with a layout key", [&] {
        const TexelFrame frame{scene, marked, 42u};
        (void)plan_texel_frame(frame, history);
    });
    dev.wait_idle();
    return 0;
}
