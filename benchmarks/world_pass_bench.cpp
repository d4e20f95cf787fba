// GPU time of the game's world pass (game::WorldRenderer) on a typical cave view, and what
// each part of it costs: the view as the game shows it, then variants that leave out the GI,
// the ground, faces by direction. Prints the machine and the Vulkan device first.
//
//   lantern-bench-world [--frames N]      (default 15 per variant; the minimum is reported)
//
// A cave around the player: procedural caves, walls as boxes with exposed faces, a few
// torches, the player; GI at resolution 4 computed once (only the world pass is timed),
// 480x270. Numbers go in docs/game.md ("Performance"); compare ratios from one run.
#include "lantern/core/cli.hpp"
#include "lantern/core/machine.hpp"
#include "lantern/game/gameplay.hpp"
#include "lantern/game/world_renderer.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/passes.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gi/window.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/gpu/timestamps.hpp"
#include "lantern/scene/procedural.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace lantern;
using game::BoxInstance;
using game::DrawList;
using game::WorldView;

namespace {

constexpr glm::ivec2 target_size{480, 270};

BoxInstance glow_box(glm::vec3 center, glm::vec3 half, glm::vec3 color) {
    BoxInstance b;
    b.center = center;
    b.half = half;
    b.material = float(int(game::Material::glow));
    b.face_mask = float(game::face_all);
    b.color = color;
    b.emissive = 1.0f;
    return b;
}

int fail(const std::string& message) {
    std::fprintf(stderr, "lantern-bench-world: %s\n", message.c_str());
    return 1;
}

} // namespace

int main(int argc, char** argv) {
    int frames = 15;
    cli::Parser args("lantern-bench-world", "[--frames N]",
                  "GPU time of the game's world pass on a typical cave view, and what each part of it\n"
                  "costs (docs/game.md, \"Performance\").");
    args.integer("--frames", "N", "frames per variant; the minimum and median are reported (default 15)", frames, 2,
                 10000);
    if (auto exit = args.parse(argc, argv)) return *exit;
    std::printf("machine: %s\n", describe_machine().c_str());
    auto device = gpu::Device::create({.application_name = "lantern-bench-world", .graphics = true});
    if (!device) return fail(device.error().message);
    gpu::Device& dev = **device;
    std::printf("device: %s\n", dev.name().c_str());
    auto world = game::WorldRenderer::create(dev, target_size);
    if (!world) return fail(world.error().message);
    auto gi = gi::vk::Renderer::create(dev);
    if (!gi) return fail(gi.error().message);

    // The game's caves; the player on an open tile whose surroundings (the view, about
    // 30 x 20 tiles) are about 40 % wall.
    scene::Scene s;
    s.walls = scene::generate_caves({-60, -60}, {120, 120}, scene::CaveParams{1, 0.52f});
    s.wall_height = 2.0f;
    s.gi.resolution = 4;
    s.gi.heat_rounds = 8;
    const gi::WallView walls = gi::WallView::of(s.walls);
    glm::vec2 player{0.5f};
    float best = 1.0f;
    for (int z = -40; z <= 40; z += 2)
        for (int x = -40; x <= 40; x += 2) {
            if (walls.is_wall(x, z)) continue;
            int n = 0;
            for (int dz = -12; dz < 8; ++dz)
                for (int dx = -15; dx < 15; ++dx) n += walls.is_wall(x + dx, z + dz);
            const float off = std::abs(float(n) / 600.0f - 0.4f);
            if (off < best) best = off, player = {float(x) + 0.5f, float(z) + 0.5f};
        }
    for (int i = 0; i < 6; ++i) {
        const glm::vec2 p = player + glm::vec2(float(i % 3) * 5.0f - 5.0f, float(i / 3) * 6.0f - 3.0f);
        if (!walls.is_wall(int(std::floor(p.x)), int(std::floor(p.y))))
            s.point_lights.push_back({p, 1.0f, {1.0f, 0.62f, 0.28f}, 1.6f, 7.0f});
    }
    s.view = game::follow_camera({player.x, 0.0f, player.y}, game::CameraRig{});
    std::string why;
    auto window = gi::compute_window(s.view, s.gi, &why);
    if (!window) return fail(why);
    const gi::FrameInputs in = gi::gather_frame_inputs(s, *window);
    const gi::PassPlan plan = gi::plan_passes(in, false);

    DrawList list;
    const gi::CameraView& v = in.window.view;
    list.boxes.push_back(game::ground_box({v.min_x - 8.0f, v.min_z - 8.0f}, {v.min_x + v.width + 8.0f, v.min_z + v.height + 8.0f},
                                          {0.75f, 0.7f, 0.62f}));
    game::append_wall_boxes(list, [&](int x, int z) { return in.walls.is_wall(x, z); }, in.walls.origin - 1,
                            in.walls.origin + glm::ivec2(in.walls.width, in.walls.height) + 1, in.wall_height,
                            {0.6f, 0.63f, 0.72f});
    for (const auto& l : s.point_lights) {
        list.boxes.push_back(glow_box({l.position.x, 0.35f, l.position.y}, {0.08f, 0.35f, 0.08f}, {0.4f, 0.25f, 0.1f}));
        list.boxes.push_back(glow_box({l.position.x, 0.8f, l.position.y}, {0.12f, 0.12f, 0.12f}, {1.0f, 0.6f, 0.2f}));
    }
    list.boxes.push_back(glow_box({player.x, 0.5f, player.y}, {0.3f, 0.5f, 0.3f}, {0.2f, 0.4f, 0.9f}));

    // GI once.
    if (auto ok = (*gi)->prepare(in, plan); !ok) return fail(ok.error().message);
    {
        gpu::CommandList cmd = dev.begin("cave gi");
        (*gi)->upload_walls(cmd, in.walls);
        (*gi)->upload_lights(cmd, in);
        (*gi)->record_plan(cmd, in, plan);
        dev.submit(std::move(cmd));
    }
    WorldView view;
    view.camera = std::get<scene::PerspectiveCamera>(s.view);
    view.gi = &in;
    view.renderer = gi->get();
    auto queries = dev.create_timestamp_queries(1, "world pass");
    if (!queries) return fail(queries.error().message);

    std::printf("world pass at %dx%d, GI window %dx%d texels, %d frames per variant (min / median ms):\n", target_size.x,
                target_size.y, in.window.width, in.window.height, frames);
    auto time_it = [&](const char* what, const WorldView& wv, const DrawList& l) {
        std::vector<double> t;
        for (int i = 0; i < frames; ++i) {
            gpu::CommandList cmd = dev.begin("cave world");
            queries->reset(cmd);
            const auto region = queries->begin(cmd, "world");
            (*world)->record(cmd, wv, l);
            queries->end(cmd, region);
            dev.submit(std::move(cmd));
            t.push_back(double(queries->resolve().regions[0].duration_ns) * 1e-6);
        }
        std::sort(t.begin() + 1, t.end()); // the first frame warms up
        std::printf("  %-28s %7.2f %7.2f   (%zu boxes, %zu faces drawn)\n", what, t[1], t[t.size() / 2 + 1],
                    l.boxes.size(), (*world)->faces_drawn());
    };
    WorldView no_gi = view;
    no_gi.gi = nullptr;
    time_it("the game's view", view, list);
    WorldView styled = view; // seed 002's knobs moved: the pipelines with their branch compiled in
    styled.world_bounce = {0.5f, 0.25f};
    time_it("bounce knobs moved", styled, list);
    time_it("no gi", no_gi, list);
    time_it("empty", view, DrawList{});
    DrawList ground;
    ground.boxes.push_back(list.boxes[0]);
    time_it("ground only", view, ground);
    time_it("ground only, no gi", no_gi, ground);
    for (float r : {3.0f, 12.0f, 30.0f}) {
        DrawList small;
        small.boxes.push_back(game::ground_box(player - r, player + r, {1, 1, 1}));
        char name[64];
        std::snprintf(name, sizeof name, "ground %gx%g tiles", 2 * r, 2 * r);
        time_it(name, view, small);
    }
    DrawList walls_only(list);
    walls_only.boxes.erase(walls_only.boxes.begin());
    time_it("no ground", view, walls_only);
    time_it("no ground, no gi", no_gi, walls_only);
    for (int mask : {game::face_top, game::face_pos_x | game::face_neg_x | game::face_pos_z | game::face_neg_z}) {
        DrawList l2 = walls_only;
        for (auto& b : l2.boxes) b.face_mask = float(int(b.face_mask) & mask);
        time_it(mask == game::face_top ? "no ground, tops only" : "no ground, sides only", view, l2);
    }
    dev.wait_idle();
    return 0;
}
