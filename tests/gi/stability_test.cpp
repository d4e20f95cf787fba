// Issue 4's invariants and stiff/extreme cases, on both backends: every case must give
// finite, bounded, sensible textures (and the same ones on Vulkan and the reference).
#include "gi_compare.hpp"
#include "test_scenes.hpp"

#include "gpu_test_support.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/gather.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/scene/loader.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace lantern::gi;
using gi_test::max_in;
using gi_test::grid_from_rows;
using lantern::scene::Scene;

namespace {

// Created on first use, after the shared Device, so it is destroyed before the Device.
vk::Renderer* renderer_or_null() {
    static std::unique_ptr<vk::Renderer> renderer = []() -> std::unique_ptr<vk::Renderer> {
        lantern::gpu::Device* d = lantern::test::shared_gpu_device();
        if (!d) return nullptr;
        auto r = vk::Renderer::create(*d);
        return r ? std::move(r.value()) : nullptr;
    }();
    return renderer.get();
}

struct Frames {
    FrameInputs in;
    FrameResult ref;
    std::optional<FrameResult> gpu;
};

Frames run_both(const Scene& s) {
    Frames f;
    auto w = compute_window(s.view, s.gi);
    EXPECT_TRUE(w);
    f.in = gather_frame_inputs(s, *w);
    const PassPlan plan = plan_passes(f.in, true);
    f.ref = run_reference_frame(f.in, plan);
    vk::Renderer* r = renderer_or_null();
    if (!r) {
        // The GPU half is left out: the test reports itself skipped (failed under
        // LANTERN_REQUIRE_GPU=1), its reference half still checked.
        [] { LANTERN_SKIP_NO_GPU("no Vulkan device: only the C++ reference half ran"); }();
    } else {
        r->device().clear_validation_messages();
        auto g = run_vulkan_frame(*r, f.in, plan);
        EXPECT_TRUE(g.ok()) << (g.ok() ? "" : g.error().message);
        if (g) f.gpu = std::move(g.value());
        EXPECT_EQ(r->device().validation_message_count(), 0u) << "Vulkan validation messages (see the log above)";
    }
    return f;
}

// Finite everywhere, within [lo, hi] on colour channels, on both backends, and the two agree.
void expect_sane(const Frames& f, const std::string& what, float indirect_max = 2.0f + 1e-3f) {
    auto check = [&](const FrameResult& r, const char* backend) {
        for (const auto& [name, t] : r.textures) {
            float hi = name == "indirect" || name.rfind("wall_indirect", 0) == 0 ? indirect_max : max_half;
            if (t.format != TexFormat::rgba16f) hi = 1.0f;
            // The distance field's direction channels (1, 2) are a unit vector; the live probes'
            // harmonics past a0 (texels 1..4 of five a probe, rgb) are signed and no larger than a0.
            const bool direction = name == "distance_field", harmonics = name == "probes";
            for (std::size_t i = 0; i < t.texels.size(); ++i) {
                ASSERT_TRUE(std::isfinite(t.texels[i])) << what << " " << backend << " " << name << " value " << i;
                const bool signed_channel = direction && (i % 4 == 1 || i % 4 == 2);
                const bool signed_harmonic = harmonics && (i / 4) % std::size_t(t.width) % 5 != 0 && i % 4 != 3;
                if (signed_harmonic) {
                    ASSERT_GE(t.texels[i], -hi) << what << " " << backend << " " << name;
                    ASSERT_LE(t.texels[i], hi) << what << " " << backend << " " << name;
                    continue;
                }
                ASSERT_GE(t.texels[i], signed_channel ? -1.0f : 0.0f) << what << " " << backend << " " << name;
                ASSERT_LE(t.texels[i], hi) << what << " " << backend << " " << name;
            }
        }
    };
    check(f.ref, "reference");
    if (!f.gpu) return;
    check(*f.gpu, "vulkan");
    for (const auto& [name, t] : f.ref.textures) {
        const float ulps = (name == "indirect" || name.rfind("wall_indirect", 0) == 0) ? 4.0f : 2.0f;
        auto d = gi_test::compare_textures(f.gpu->textures.at(name), t, ulps);
        EXPECT_EQ(d.mismatches, 0u) << gi_test::describe(what + " " + name, d);
    }
}

// Two rooms side by side split by a one-tile wall at x = 10; a light in the left room.
Scene sealed_rooms(float distance, lantern::scene::HeatScale scale, bool segment_check, int res) {
    std::vector<std::string> rows(12, std::string(21, '.'));
    for (int x = 0; x < 21; ++x) rows[0][std::size_t(x)] = rows[11][std::size_t(x)] = '#';
    for (int z = 0; z < 12; ++z) rows[std::size_t(z)][0] = rows[std::size_t(z)][10] = rows[std::size_t(z)][20] = '#';
    Scene s = gi_test::open_scene({10.5f, 6.0f}, {21.0f, 12.0f}, res);
    s.walls = grid_from_rows(rows);
    s.point_lights.push_back(gi_test::point({5.5f, 6.0f}, {1.0f, 0.9f, 0.8f}, 3.0f, 8.0f));
    s.gi.diffusion_distance = distance;
    s.gi.heat_scale = scale;
    s.gi.segment_check = segment_check;
    s.gi.heat_rounds = 40;
    s.gi.blur = true;
    return s;
}

// Stiff scenes several cases share: a one-texel corridor turning a corner (64 x 64 tiles of rock, resolution
// 1, a light in the first leg), a checkerboard, all walls, the minimum window.
Scene corridor_scene() {
    std::vector<std::string> rows(64, std::string(64, '#'));
    for (int x = 1; x < 63; ++x) rows[10][std::size_t(x)] = '.';
    for (int z = 10; z < 40; ++z) rows[std::size_t(z)][62] = '.';
    Scene s = gi_test::open_scene({32, 32}, {64, 64}, 1);
    s.walls = grid_from_rows(rows);
    s.point_lights.push_back(gi_test::point({50.5f, 10.5f}, {1, 1, 1}, 2.0f, 15.0f));
    return s;
}
Scene checkerboard_scene() {
    std::vector<std::string> rows(16, std::string(16, '.'));
    for (int z = 0; z < 16; ++z)
        for (int x = 0; x < 16; ++x) rows[std::size_t(z)][std::size_t(x)] = (x + z) % 2 ? '#' : '.';
    Scene s = gi_test::open_scene({8, 8}, {16, 16}, 4);
    s.walls = grid_from_rows(rows);
    s.point_lights.push_back(gi_test::point({8.5f, 8.5f}, {1, 1, 1}, 1.0f, 6.0f));
    return s;
}
Scene all_walls_scene() {
    Scene s = gi_test::open_scene({8, 8}, {16, 16}, 4);
    s.walls = grid_from_rows(std::vector<std::string>(16, std::string(16, '#')));
    s.point_lights.push_back(gi_test::point({8.5f, 8.5f}, {1, 1, 1}, 1.0f, 6.0f));
    return s;
}
Scene minimum_window_scene() {
    Scene s = gi_test::open_scene({0.5f, 0.5f}, {1.0f, 1.0f}, 1);
    s.walls = grid_from_rows({"#.#", "...", "#.#"});
    s.point_lights.push_back(gi_test::point({1.5f, 1.5f}, {1, 1, 1}, 1.0f, 3.0f));
    return s;
}

} // namespace

// ---- invariants

TEST(GiInvariants, NoLightThroughASealedOneTileWall) {
    for (float distance : {0.5f, 1.0f, 2.0f, 3.0f, 6.0f, 12.0f})
        for (auto scale : {lantern::scene::HeatScale::full, lantern::scene::HeatScale::half, lantern::scene::HeatScale::quarter}) {
            Scene s = sealed_rooms(distance, scale, true, 4);
            Frames f = run_both(s);
            const GiWindow& w = f.in.window;
            // The right room: tiles x in [11, 20), texels from x = 11 * res.
            const int x0 = int((11.0f - w.view.min_x) * float(w.resolution));
            const int x1 = int((20.0f - w.view.min_x) * float(w.resolution));
            const int y1 = int((12.0f - w.view.min_z) * float(w.resolution));
            const std::string what = "distance " + std::to_string(distance) + " scale " + std::to_string(int(scale));
            EXPECT_EQ(max_in(f.ref.textures.at("indirect"), x0, 0, x1, y1), 0.0f) << "reference " << what;
            EXPECT_EQ(max_in(f.ref.textures.at("direct"), x0, 0, x1, y1), 0.0f) << what;
            if (f.gpu) {
                EXPECT_EQ(max_in(f.gpu->textures.at("indirect"), x0, 0, x1, y1), 0.0f) << "vulkan " << what;
            }
        }
}

TEST(GiInvariants, WithoutTheSegmentCheckFarTapsLeak) {
    // The reason for the check: far taps hop a thin wall. docs/gi.md quotes these amounts.
    Scene s = sealed_rooms(3.0f, lantern::scene::HeatScale::full, false, 4);
    Frames f = run_both(s);
    const GiWindow& w = f.in.window;
    const int x0 = int((11.0f - w.view.min_x) * 4.0f), x1 = int((20.0f - w.view.min_x) * 4.0f);
    EXPECT_GT(max_in(f.ref.textures.at("indirect"), x0, 0, x1, 48), 0.0f);
}

TEST(GiInvariants, FiniteAndWithinTheHalfRangeForHugeLights) {
    for (float intensity : {1e-8f, 1e6f, 1e30f}) {
        Scene s = gi_test::comparison_scene("rooms").scene;
        for (auto& l : s.point_lights) l.intensity = intensity;
        for (auto& l : s.emissive_lights) l.intensity = intensity;
        Frames f = run_both(s);
        expect_sane(f, "intensity " + std::to_string(intensity));
        if (intensity >= 1e6f) {
            EXPECT_EQ(max_in(f.ref.textures.at("direct"), 0, 0, 96, 80), max_half);
        }
    }
}

TEST(GiInvariants, MoreLightNeverDarkensATexel) {
    // Scaling every light up keeps every texel at least as bright (brightest channel; the
    // saturation boost and the soft cap move single channels), within rounding.
    for (const char* which : {"rooms", "sun_and_walls", "dense_cave"}) {
        Scene s = gi_test::comparison_scene(which).scene;
        s.directional_lights.clear();
        Frames dim = run_both(s);
        for (auto& l : s.point_lights) l.intensity *= 1.5f;
        for (auto& l : s.emissive_lights) l.intensity *= 1.5f;
        Frames bright = run_both(s);
        for (const char* name : {"direct", "indirect"}) {
            const Texture& a = dim.ref.textures.at(name);
            const Texture& b = bright.ref.textures.at(name);
            std::size_t darker = 0;
            for (int y = 0; y < a.height; ++y)
                for (int x = 0; x < a.width; ++x) {
                    const float* p = a.at(x, y);
                    const float* q = b.at(x, y);
                    const float before = std::max(p[0], std::max(p[1], p[2]));
                    const float after = std::max(q[0], std::max(q[1], q[2]));
                    darker += after < before - gi_test::allowed_difference(TexFormat::rgba16f, before, after, 2.0f);
                }
            EXPECT_EQ(darker, 0u) << which << " " << name;
        }
    }
}

// ---- stiff and extreme cases

TEST(GiStability, DiffusionRateRange) {
    for (float rate : {0.0f, 0.5f, 1.0f, 1.25f}) {
        Scene s = gi_test::comparison_scene("rooms").scene;
        s.gi.diffusion_rate = rate;
        s.gi.heat_rounds = 60;
        Frames f = run_both(s);
        expect_sane(f, "rate " + std::to_string(rate));
    }
    // Rate 0: no diffusion at all, the indirect light is the (blurred) seed, so a dark texel
    // next to a lit one stays dark... and beyond the stable range the scene is rejected.
    Scene s = gi_test::comparison_scene("rooms").scene;
    auto rejected = lantern::scene::apply_override(s, "gi.diffusion_rate=1.3");
    ASSERT_FALSE(rejected.ok());
    EXPECT_NE(rejected.error().message.find("1.25"), std::string::npos) << rejected.error().message;
}

TEST(GiStability, IntensityMultiplierIsBoundedByTheSoftCap) {
    Scene s = gi_test::comparison_scene("light_edge_cases").scene;
    s.gi.intensity_multiplier = 1.5f;
    s.gi.range_boost = 2.0f;
    s.gi.heat_rounds = 200;
    Frames f = run_both(s);
    expect_sane(f, "multiplier 1.5 x 200 rounds");
    EXPECT_GT(max_in(f.ref.textures.at("indirect"), 0, 0, 64, 64), 1.5f); // it did grow, up to the cap
}

TEST(GiStability, TenThousandRounds) {
    Scene s = sealed_rooms(1.0f, lantern::scene::HeatScale::full, true, 2);
    s.gi.heat_rounds = 10000;
    Frames f = run_both(s);
    expect_sane(f, "10000 rounds");
}

TEST(GiStability, ResolutionOneAndThirtyTwo) {
    for (int res : {1, 32}) {
        Scene s = gi_test::comparison_scene("rooms").scene;
        s.gi.resolution = res;
        s.gi.heat_rounds = 8;
        if (res == 32) s.view = lantern::scene::OrthoView{{6.0f, 5.0f}, {8.0f, 6.0f}};
        Frames f = run_both(s);
        expect_sane(f, "resolution " + std::to_string(res));
    }
}

TEST(GiStability, OneTexelCorridorsAndCheckerboard) {
    {   // giRes 1: a corridor one tile (= one texel) wide, zig-zagging.
        std::vector<std::string> rows(64, std::string(64, '#'));
        for (int x = 1; x < 63; ++x) rows[10][std::size_t(x)] = '.';
        for (int z = 10; z < 40; ++z) rows[std::size_t(z)][62] = '.';
        for (int x = 5; x < 63; ++x) rows[40][std::size_t(x)] = '.';
        Scene s = gi_test::open_scene({32, 32}, {64, 64}, 1);
        s.walls = grid_from_rows(rows);
        s.point_lights.push_back(gi_test::point({50.5f, 10.5f}, {1, 1, 1}, 2.0f, 15.0f));
        Frames f = run_both(s);
        expect_sane(f, "one-texel corridor");
        // Round the corner at (62, 10) direct light cannot follow, but indirect light does;
        // the rock stays dark.
        EXPECT_EQ(f.ref.textures.at("direct").at(62, 16)[0], 0.0f);
        EXPECT_GT(f.ref.textures.at("indirect").at(62, 16)[0], 0.0f);
        EXPECT_EQ(f.ref.textures.at("indirect").at(30, 30)[0], 0.0f);
    }
    // Checkerboard: every other tile a wall; light passes only through corners.
    expect_sane(run_both(checkerboard_scene()), "checkerboard");
}

TEST(GiStability, AllWallsAndNoWalls) {
    {
        Scene s = gi_test::open_scene({8, 8}, {16, 16}, 4);
        s.walls = grid_from_rows(std::vector<std::string>(16, std::string(16, '#')));
        s.point_lights.push_back(gi_test::point({8.5f, 8.5f}, {1, 1, 1}, 1.0f, 6.0f));
        s.emissive_lights.push_back(gi_test::emissive({4.5f, 4.5f}, {1, 1, 1}, 1.0f, 6.0f));
        Frames f = run_both(s);
        expect_sane(f, "all walls");
        EXPECT_EQ(max_in(f.ref.textures.at("direct"), 0, 0, 64, 64), 0.0f);
        EXPECT_EQ(max_in(f.ref.textures.at("indirect"), 0, 0, 64, 64), 0.0f);
        EXPECT_EQ(max_in(f.ref.textures.at("conduction"), 0, 0, 64, 64), 0.0f);
    }
    {
        Scene s = gi_test::open_scene({8, 8}, {16, 16}, 4);
        s.point_lights.push_back(gi_test::point({8.5f, 8.5f}, {1, 1, 1}, 1.0f, 6.0f));
        Frames f = run_both(s); // empty grid: everything is air
        expect_sane(f, "no walls");
        EXPECT_FALSE(f.ref.textures.count("wall_indirect_px")); // left out: no walls in view
        EXPECT_EQ(max_in(f.ref.textures.at("wall_direct_px"), 0, 0, 64, 64), 0.0f);
    }
}

TEST(GiStability, LightInsideAWall) {
    Frames f = run_both(gi_test::comparison_scene("light_edge_cases").scene);
    expect_sane(f, "light inside a wall");
}

TEST(GiStability, MinimumWindow) {
    Scene s = gi_test::open_scene({0.5f, 0.5f}, {1.0f, 1.0f}, 1);
    s.walls = grid_from_rows({"#.#", "...", "#.#"});
    s.point_lights.push_back(gi_test::point({1.5f, 1.5f}, {1, 1, 1}, 1.0f, 3.0f));
    Frames f = run_both(s);
    EXPECT_EQ(f.in.window.width, 64);
    EXPECT_EQ(f.in.window.height, 64);
    expect_sane(f, "64-texel window");
}

TEST(GiStability, WindowBeyondTheDeviceLimitIsAClearError) {
    vk::Renderer* r = renderer_or_null();
    if (!r) LANTERN_SKIP_NO_GPU("no Vulkan device");
    const auto& caps = r->device().capabilities();
    // A square window just over the texel-buffer limit (lavapipe: 2^27 texels).
    const int side = int(std::ceil(std::sqrt(double(caps.max_texel_buffer_elements) + 1.0) / 4.0)) * 4 + 4;
    Scene s = gi_test::open_scene({float(side) / 2.0f, float(side) / 2.0f}, {float(side), float(side)}, 1);
    auto w = compute_window(s.view, s.gi.padding, 1, nullptr, 1 << 20);
    ASSERT_TRUE(w);
    FrameInputs in = gather_frame_inputs(s, *w);
    // Conduction alone (one byte per texel) stays within the memory budget, so the device's
    // own limit is what refuses it: a runtime failure (exit 1) naming the device.
    auto result = run_vulkan_frame(*r, in, plan_passes(in, false, Pass::conduction));
    ASSERT_FALSE(result.ok());
    EXPECT_NE(result.error().message.find("does not fit the device"), std::string::npos) << result.error().message;
    EXPECT_EQ(result.error().exit_code, 1);
    // The whole pipeline is over the memory budget first: bad input (exit 2), nothing allocated.
    auto whole = run_vulkan_frame(*r, in, plan_passes(in, false));
    ASSERT_FALSE(whole.ok());
    EXPECT_NE(whole.error().message.find("over the budget"), std::string::npos) << whole.error().message;
    EXPECT_EQ(whole.error().exit_code, 2);
    // And a window just inside it still works (allocation only; not rendered here).
}

// Seed 003's radiosity (gi.method = radiosity) on the stiff cases above: huge and tiny
// lights, resolutions 1 and 32, one-texel corridors, a checkerboard, all walls and none, a
// light inside a wall, the minimum window. Finite, bounded and equal on both backends.
TEST(GiStability, RadiosityOnTheStiffCases) {
    auto radiosity = [](Scene s, lantern::scene::HeatScale scale = lantern::scene::HeatScale::full) {
        s.gi.method = lantern::scene::GiMethod::radiosity;
        s.gi.radiosity.scale = scale;
        return s;
    };
    for (float intensity : {1e-8f, 1e30f}) {
        Scene s = gi_test::comparison_scene("rooms").scene;
        for (auto& l : s.point_lights) l.intensity = intensity;
        for (auto& l : s.emissive_lights) l.intensity = intensity;
        for (auto& m : s.materials) m.emission *= intensity; // glowing walls as bright
        expect_sane(run_both(radiosity(s, lantern::scene::HeatScale::half)), "radiosity, intensity " + std::to_string(intensity));
    }
    for (int res : {1, 32}) {
        Scene s = gi_test::comparison_scene("rooms").scene;
        s.gi.resolution = res;
        if (res == 32) s.view = lantern::scene::OrthoView{{6.0f, 5.0f}, {8.0f, 6.0f}};
        expect_sane(run_both(radiosity(s, res == 1 ? lantern::scene::HeatScale::full : lantern::scene::HeatScale::quarter)),
                    "radiosity, resolution " + std::to_string(res));
    }
    {
        Frames f = run_both(radiosity(corridor_scene()));
        expect_sane(f, "radiosity, one-texel corridor");
        EXPECT_EQ(f.ref.textures.at("indirect").at(30, 30)[0], 0.0f) << "the rock stays dark";
    }
    expect_sane(run_both(radiosity(checkerboard_scene())), "radiosity, checkerboard");
    {
        const Scene s = all_walls_scene();
        Frames f = run_both(radiosity(s));
        expect_sane(f, "radiosity, all walls");
        EXPECT_EQ(max_in(f.ref.textures.at("indirect"), 0, 0, 64, 64), 0.0f);
        Scene open = gi_test::open_scene({8, 8}, {16, 16}, 4);
        open.point_lights = s.point_lights;
        expect_sane(run_both(radiosity(open)), "radiosity, no walls");
    }
    expect_sane(run_both(radiosity(gi_test::comparison_scene("light_edge_cases").scene)), "radiosity, light inside a wall");
    expect_sane(run_both(radiosity(minimum_window_scene(), lantern::scene::HeatScale::quarter)), "radiosity, 64-texel window");
}

// The gather method (gi.method = gather, physical) on the stiff cases: huge and tiny lights,
// albedo 0 / 0.5 / 0.99 / 1, resolutions 1 and 32, a one-texel corridor, a checkerboard, all
// walls and none, a light inside a wall, the minimum window, a sealed one-tile wall, and
// 10,000 face bounces. Physical light is not capped (as heat's is): the bound is the half
// range.
TEST(GiStability, GatherOnTheStiffCases) {
    auto gather = [](Scene s, lantern::scene::HeatScale scale = lantern::scene::HeatScale::full) {
        s.gi.method = lantern::scene::GiMethod::gather;
        s.gi.gather.scale = scale;
        s.gi.gather.margin = 1;
        return s;
    };
    auto sane = [](const Frames& f, const std::string& what) { expect_sane(f, what, max_half); };
    for (float intensity : {1e-8f, 1e30f}) {
        Scene s = gi_test::comparison_scene("rooms").scene;
        for (auto& l : s.point_lights) l.intensity = intensity;
        for (auto& l : s.emissive_lights) l.intensity = intensity;
        for (auto& m : s.materials) m.emission *= intensity; // glowing walls as bright
        sane(run_both(gather(s, lantern::scene::HeatScale::half)), "gather, intensity " + std::to_string(intensity));
    }
    for (float albedo : {0.0f, 0.5f, 0.99f, 1.0f}) {
        Scene s = gather(gi_test::comparison_scene("rooms").scene);
        s.gi.wall_albedo = albedo;
        for (auto& m : s.materials) m.albedo = glm::vec3(albedo), m.emission = glm::vec3(0.0f); // no glow
        Frames f = run_both(s);
        sane(f, "gather, albedo " + std::to_string(albedo));
        const Texture& indirect = f.ref.textures.at("indirect");
        if (albedo == 0.0f) {
            EXPECT_EQ(max_in(indirect, 0, 0, indirect.width, indirect.height), 0.0f) << "albedo 0";
        } else {
            EXPECT_GT(max_in(indirect, 0, 0, indirect.width, indirect.height), 0.0f) << "albedo " << albedo;
        }
    }
    for (int res : {1, 32}) {
        Scene s = gi_test::comparison_scene("rooms").scene;
        s.gi.resolution = res;
        if (res == 32) s.view = lantern::scene::OrthoView{{6.0f, 5.0f}, {8.0f, 6.0f}};
        sane(run_both(gather(s, res == 1 ? lantern::scene::HeatScale::full : lantern::scene::HeatScale::quarter)),
             "gather, resolution " + std::to_string(res));
    }
    {
        Scene s = corridor_scene();
        s.gi.gather.rays = 256; // rays 0.025 rad apart: some go down the corridor
        Frames f = run_both(gather(s));
        sane(f, "gather, one-texel corridor");
        const GiWindow& w = f.in.window;
        const int tx = int(std::floor(62.5f - w.view.min_x)), tz = int(std::floor(30.5f - w.view.min_z));
        EXPECT_GT(max_in(f.ref.textures.at("indirect"), tx, tz, tx + 1, tz + 1), 0.0f)
            << "light turns the corner into the second corridor";
    }
    sane(run_both(gather(checkerboard_scene())), "gather, checkerboard");
    {
        const Scene s = all_walls_scene();
        Frames f = run_both(gather(s));
        sane(f, "gather, all walls");
        const Texture& indirect = f.ref.textures.at("indirect");
        EXPECT_EQ(max_in(indirect, 0, 0, indirect.width, indirect.height), 0.0f);
        Scene open = gi_test::open_scene({8, 8}, {16, 16}, 4);
        open.point_lights = s.point_lights;
        Frames g = run_both(gather(open));
        sane(g, "gather, no walls");
        const Texture& none = g.ref.textures.at("indirect");
        EXPECT_EQ(max_in(none, 0, 0, none.width, none.height), 0.0f) << "nothing to reflect";
    }
    sane(run_both(gather(gi_test::comparison_scene("light_edge_cases").scene)), "gather, light inside a wall");
    sane(run_both(gather(minimum_window_scene(), lantern::scene::HeatScale::quarter)), "gather, 64-texel window");
    for (auto scale : {lantern::scene::HeatScale::full, lantern::scene::HeatScale::half, lantern::scene::HeatScale::quarter}) {
        Scene s = gather(sealed_rooms(1.0f, scale, true, 4), scale);
        s.gi.wall_albedo = 1.0f;
        s.gi.gather.bounces = 8;
        Frames f = run_both(s);
        const GiWindow& w = f.in.window;
        const int x0 = int((11.0f - w.view.min_x) * float(w.resolution));
        const int x1 = int((20.0f - w.view.min_x) * float(w.resolution));
        const int y1 = int((12.0f - w.view.min_z) * float(w.resolution));
        EXPECT_EQ(max_in(f.ref.textures.at("indirect"), x0, 0, x1, y1), 0.0f) << "sealed wall, scale " << int(scale);
        if (f.gpu) {
            EXPECT_EQ(max_in(f.gpu->textures.at("indirect"), x0, 0, x1, y1), 0.0f) << "vulkan, scale " << int(scale);
        }
        const int left = int((10.0f - w.view.min_x) * float(w.resolution));
        EXPECT_GT(max_in(f.ref.textures.at("indirect"), 0, 0, left, y1), 0.0f) << "the lit room has bounce light";
    }
}

// 10,000 face bounces in a sealed room at albedo 1 (the reference's bounce step, fed its own
// output): the light grows with every bounce (nothing absorbs it: energy is conserved, so
// the series has no limit) yet stays finite, within the half range, where it saturates; the
// ground gathered from the last bounce too.
TEST(GiStability, GatherTenThousandBounces) {
    Scene s = sealed_rooms(1.0f, lantern::scene::HeatScale::full, true, 1);
    s.gi.method = lantern::scene::GiMethod::gather;
    s.gi.gather.margin = 0;
    s.gi.gather.face_rays = 2;
    s.gi.wall_albedo = 1.0f;
    auto w = compute_window(s.view, s.gi);
    ASSERT_TRUE(w);
    const FrameInputs in = gather_frame_inputs(s, *w);
    const FrameResult direct = run_reference_frame(in, plan_passes(in, false));
    FaceTextures faces{};
    for (int f = 0; f < 4; ++f) faces[std::size_t(f)] = &direct.textures.at(std::string("wall_direct_") + face_suffix[f]);
    Texture bounce = reference_gather_faces(in, faces, nullptr);
    float last = 0.0f;
    for (int i = 1; i < 10000; ++i) {
        bounce = reference_gather_faces(in, faces, &bounce);
        const float now = max_in(bounce, 0, 0, bounce.width, bounce.height);
        ASSERT_TRUE(std::isfinite(now)) << "bounce " << i;
        ASSERT_LE(now, max_half) << "bounce " << i;
        ASSERT_GE(now, last) << "bounce " << i << ": albedo 1 loses no light";
        last = now;
    }
    EXPECT_GT(last, 100.0f) << "10,000 bounces of a lossless room";
    const Texture ground = reference_gather_ground(in, faces, bounce);
    EXPECT_TRUE(std::isfinite(max_in(ground, 0, 0, ground.width, ground.height)));
}
