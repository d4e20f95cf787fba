// The gather method (gi.method = gather) against the transport reference it models, at the
// same resolution, albedo and domain (gather.margin = the reference's margin): the ground's
// indirect fluence and the faces' indirect irradiance, in total and texel by texel.
#include "transport_test_util.hpp"

#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/window.hpp"
#include "lantern/jobs/job_system.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace lantern;

namespace {

gi::ReferenceStore gather_frames(const gi::FrameInputs& in, int frames) {
    gi::Convergence convergence;
    gi::ReferenceStore store;
    for (int f = 0; f < frames; ++f) {
        gi::PassPlan plan = gi::plan_passes(in, false);
        gi::derive_keys(in, plan, gi::input_keys_of(in), &convergence);
        gi::execute_reference(in, plan, plan.run, {}, store);
        convergence.advance(plan.run);
    }
    return store;
}

struct Agreement {
    double ground_ratio = 0, ground_rrmse = 0, face_ratio = 0, reference_se = 0;
};

// Converged gather (8 frames, 16 bounces) against the reference over the reference's window.
Agreement compare(scene::Scene s, const transport::TransportSettings& t, int channel = 1) {
    s.gi.method = scene::GiMethod::gather;
    s.gi.resolution = t.resolution;
    s.gi.gather.scale = scene::HeatScale::full;
    s.gi.gather.rays = 256;
    s.gi.gather.bounces = std::max(2, s.gi.gather.bounces);
    s.gi.gather.face_rays = 128;
    s.gi.gather.margin = t.margin;
    s.gi.wall_albedo = t.albedo;
    s.gi.blur = false;
    jobs::JobSystem jobs;
    transport::SolveOptions o;
    o.jobs = &jobs;
    auto ref = transport::solve_transport(s, t, o);
    EXPECT_TRUE(ref.ok()) << (ref.ok() ? "" : ref.error().message);
    if (!ref.ok()) return {};
    auto window = gi::compute_window(s.view, s.gi);
    EXPECT_TRUE(window);
    const gi::FrameInputs in = gi::gather_frame_inputs(s, *window);
    const gi::ReferenceStore store = gather_frames(in, 8);
    const gi::Texture& indirect = store.at(gi::Tex::indirect);
    const gi::GiWindow& rw = ref->window, &lw = *window;
    // The reference's window lies `margin` tiles inside Lantern's.
    const int shift = t.margin * t.resolution;
    EXPECT_EQ(lw.width, rw.width + 2 * shift);
    double g_lan = 0, g_ref = 0, err2 = 0, ref2 = 0, se2 = 0, f_lan = 0, f_ref = 0;
    for (int y = 0; y < rw.height; ++y)
        for (int x = 0; x < rw.width; ++x) {
            const glm::vec2 c = rw.texel_center(x, y);
            if (!s.walls.is_wall_tile(int(std::floor(c.x)), int(std::floor(c.y)))) {
                const double l = indirect.at(x + shift, y + shift)[channel], r = ref->indirect.at(x, y)[channel];
                g_lan += l, g_ref += r;
                err2 += (l - r) * (l - r), ref2 += r * r;
                se2 += double(ref->indirect_error.at(x, y)[channel]) * ref->indirect_error.at(x, y)[channel];
                continue;
            }
            // Face light is compared on each face's edge texel (where the gather keeps it).
            for (int f = 0; f < 4; ++f) {
                const glm::vec2 across = c + glm::vec2(f == 0 ? 1.0f : f == 1 ? -1.0f : 0.0f,
                                                       f == 2 ? 1.0f : f == 3 ? -1.0f : 0.0f) /
                                                 float(t.resolution);
                if (int(std::floor(across.x)) == int(std::floor(c.x)) && int(std::floor(across.y)) == int(std::floor(c.y)))
                    continue; // not on the tile's edge
                f_lan += store.at(gi::Tex(int(gi::Tex::wall_indirect_px) + f)).at(x + shift, y + shift)[channel];
                f_ref += ref->face_indirect.at(f, x, y)[channel];
            }
        }
    Agreement a;
    a.ground_ratio = g_lan / g_ref;
    a.ground_rrmse = std::sqrt(err2 / ref2);
    a.reference_se = std::sqrt(se2 / ref2);
    a.face_ratio = f_lan / f_ref;
    std::printf("channel %d: ground indirect %.2f %% of the reference's, rRMSE %.2f %% (its own noise %.2f %%); face "
                "indirect %.2f %%\n",
                channel, 100.0 * a.ground_ratio, 100.0 * a.ground_rrmse, 100.0 * a.reference_se, 100.0 * a.face_ratio);
    return a;
}

transport::TransportSettings settings(float albedo, int margin) {
    transport::TransportSettings t = transport_test::quick(albedo, 1u << 16);
    t.max_batches = 16;
    t.min_batches = 16;
    t.margin = margin;
    return t;
}

} // namespace

// A closed room around a light: every bounce stays inside (albedo 0.5 and 0.9).
TEST(GatherAgainstTransport, ClosedRoom) {
    scene::Scene s = transport_test::scene(transport_test::closed_room(), {8, 8}, {16, 16});
    s.point_lights = {{{6.3f, 7.1f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.5f, 12.0f}};
    for (float albedo : {0.5f, 0.9f}) {
        // 0.9: 48 bounces (0.9^48 = 0.6 % of the light left unbounced).
        s.gi.gather.bounces = albedo > 0.5f ? 6 : 2;
        const Agreement a = compare(s, settings(albedo, 2));
        EXPECT_NEAR(a.ground_ratio, 1.0, 0.02) << "albedo " << albedo;
        EXPECT_NEAR(a.face_ratio, 1.0, 0.03) << "albedo " << albedo;
        EXPECT_LT(a.ground_rrmse, 0.05 + 2.0 * a.reference_se) << "albedo " << albedo;
    }
}

// Rooms with doorways, lights outside the window: light reflected by walls in the margin
// reaches the window, and must be there (margin 8, the accuracy benchmark's).
TEST(GatherAgainstTransport, RoomsWithLightFromTheMargin) {
    const int w = 48, h = 30;
    std::vector<std::string> rows(h, std::string(w, '.'));
    auto wall = [&](int x, int z) { rows[std::size_t(z)][std::size_t(x)] = '#'; };
    for (int x = 0; x < w; ++x) wall(x, 0), wall(x, h - 1), wall(x, 15);
    for (int z = 0; z < h; ++z) wall(0, z), wall(w - 1, z), wall(16, z), wall(32, z);
    for (int z : {6, 7, 22, 23}) rows[std::size_t(z)][16] = rows[std::size_t(z)][32] = '.';
    for (int x : {8, 9, 40, 41}) rows[15][std::size_t(x)] = '.';
    scene::Scene s = transport_test::scene(rows, {24.0f, 15.0f}, {30.0f, 16.875f});
    s.point_lights = {{{7.5f, 7.5f}, 1.0f, {1.0f, 0.62f, 0.32f}, 1.5f, 10.0f},
                      {{40.5f, 22.5f}, 1.0f, {0.45f, 0.65f, 1.0f}, 1.5f, 10.0f},
                      {{24.5f, 21.0f}, 1.0f, {1.0f, 0.9f, 0.7f}, 1.2f, 8.0f}};
    transport::TransportSettings t = settings(0.5f, 8);
    t.resolution = 8; // the face light sits half a texel inside the face: at 4 texels a tile
                      // that alone costs 6 % of the indirect light here (docs/gi.md)
    const Agreement a = compare(s, t);
    EXPECT_NEAR(a.ground_ratio, 1.0, 0.05);
    EXPECT_NEAR(a.face_ratio, 1.0, 0.05);
    EXPECT_LT(a.ground_rrmse, 0.06 + 2.0 * a.reference_se);
}

// Materials (seed 004): a closed room of red rock, white and default walls, one side glowing
// lava: every channel agrees, the lava's light and the rock's tint included.
TEST(GatherAgainstTransport, ColouredAndGlowingWalls) {
    scene::Scene s = transport_test::scene(transport_test::closed_room(), {8, 8}, {16, 16});
    s.materials = {{"red_rock", {0.8f, 0.15f, 0.1f}, {}},
                   {"white", {0.9f, 0.9f, 0.9f}, {}},
                   {"lava", {0.3f, 0.1f, 0.05f}, {0.6f, 0.2f, 0.04f}}};
    for (int i = 5; i <= 10; ++i) {
        s.walls.cells[std::size_t(4 * 16 + i)] = scene::material_cell(0);  // z = 4: red rock
        s.walls.cells[std::size_t(i * 16 + 4)] = scene::material_cell(1);  // x = 4: white
        s.walls.cells[std::size_t(11 * 16 + i)] = scene::material_cell(2); // z = 11: lava
    }
    s.point_lights = {{{6.3f, 7.1f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.5f, 12.0f}};
    s.gi.gather.bounces = 3;
    for (int channel = 0; channel < 3; ++channel) {
        const Agreement a = compare(s, settings(0.5f, 2), channel);
        EXPECT_NEAR(a.ground_ratio, 1.0, 0.02) << "channel " << channel;
        EXPECT_NEAR(a.face_ratio, 1.0, 0.03) << "channel " << channel;
        EXPECT_LT(a.ground_rrmse, 0.05 + 2.0 * a.reference_se) << "channel " << channel;
    }
}
