// Point lights' shadow maps (gi.shadow_method = shadow_map) against the DDA they replace:
// every visibility the direct pass asks (ground texels from their centre, wall texels from
// just outside each face a light can reach) is the same, for the scenes' own lights and for
// lights placed on a lattice that includes tile centres, edges and corners, points a hair
// off them, points inside walls and against them, at several radii. Scenes: the comparison
// scenes, the stability grids (a checkerboard where rays pass through tile corners,
// one-texel corridors, all walls, no walls, giRes 32), the same cave moved 700 tiles from
// the origin (larger float error) and the real maps den312d and lak303d (skipped without
// ../shared). The map hands close calls to the DDA: the test counts them and keeps them a
// small share, or the map would be the DDA by another name.
#include "lantern/gi/point_map.hpp"
#include "lantern/gi/reference.hpp"
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace lantern;
using namespace lantern::gi;

namespace {

struct Tally {
    long long asked = 0, lit = 0, shadowed = 0, handed = 0, different = 0;
};

// face_position (reference_passes.cpp): 1e-3 outside the face.
glm::vec2 face_target(int f, glm::ivec2 cell, glm::vec2 p) {
    return f == 0   ? glm::vec2(float(cell.x) + 1.001f, p.y)
           : f == 1 ? glm::vec2(float(cell.x) - 0.001f, p.y)
           : f == 2 ? glm::vec2(p.x, float(cell.y) + 1.001f)
                    : glm::vec2(p.x, float(cell.y) - 0.001f);
}

// Every visibility of `in`'s point lights against the DDA.
void compare_inputs(const FrameInputs& in, const std::string& name, Tally& total) {
    const PointMaps maps = build_point_maps(in);
    const GiWindow& w = in.window;
    for (std::size_t i = 0; i < in.point_lights.size(); ++i) {
        const glm::vec2 pos(in.point_lights[i].position_radius.x, in.point_lights[i].position_radius.y);
        const float radius = in.point_lights[i].position_radius.z;
        auto check = [&](glm::vec2 target) {
            const float dda = shadow_dda(in.walls, pos, target, radius);
            int handed = 0;
            const float map = point_map_visibility(maps, in.walls, i, pos, target, radius, &handed);
            ++total.asked;
            total.lit += dda > 0.0f;
            total.shadowed += dda == 0.0f;
            total.handed += handed;
            if (map != dda && ++total.different <= 10)
                ADD_FAILURE() << name << ": light (" << pos.x << ", " << pos.y << ") radius " << radius << " to ("
                              << target.x << ", " << target.y << "): the DDA gives " << dda << ", the map " << map;
        };
        for (int y = 0; y < w.height; ++y)
            for (int x = 0; x < w.width; ++x) {
                const glm::vec2 p = w.texel_center(x, y);
                if (glm::distance(p, pos) > radius) continue; // the pass asks only within reach
                const glm::ivec2 cell(int(std::floor(p.x)), int(std::floor(p.y)));
                if (!in.walls.is_wall(cell.x, cell.y)) {
                    check(p);
                    continue;
                }
                const glm::vec4 mask = wall_face_mask(in.walls, cell);
                const glm::vec2 to_light = glm::normalize(pos - p + glm::vec2(1e-9f));
                const glm::vec4 facing = wall_facing(to_light, 1.0f);
                for (int f = 0; f < 4; ++f)
                    if (mask[f] > 0.0f && facing[f] > 0.0f) check(face_target(f, cell, p));
            }
    }
}

// The scene's own lights, then lattices of lights over its window (three radii).
void compare(scene::Scene s, const std::string& name, float lattice_step, Tally& total) {
    auto window = compute_window(s.view, s.gi);
    ASSERT_TRUE(window) << name;
    compare_inputs(gather_frame_inputs(s, *window), name, total);
    const GiWindow& w = *window;
    s.emissive_lights.clear();
    s.gi.max_lights = 4096;
    const float offsets[] = {0.0f, 0.5f, 0.25f, 1e-4f, 0.37f};
    int k = 0;
    for (float radius : {4.5f, 7.0f, 12.0f}) {
        s.point_lights.clear();
        for (float z = std::floor(w.view.min_z); z < w.view.min_z + w.view.height; z += lattice_step)
            for (float x = std::floor(w.view.min_x); x < w.view.min_x + w.view.width; x += lattice_step) {
                const float ox = offsets[std::size_t(k) % 5], oz = offsets[std::size_t(k / 5) % 5];
                ++k;
                s.point_lights.push_back(gi_test::point({x + ox, z + oz}, glm::vec3(1.0f), 1.0f, radius));
            }
        compare_inputs(gather_frame_inputs(s, w), name + " lattice r" + std::to_string(radius), total);
    }
}

void report(const char* what, const Tally& t) {
    std::printf("%s: %lld visibilities (%lld lit, %lld shadowed), %lld differ, %lld (%.3f %%) handed to the DDA\n", what,
                t.asked, t.lit, t.shadowed, t.different, t.handed, 100.0 * double(t.handed) / double(std::max(t.asked, 1LL)));
}

} // namespace

TEST(PointMap, PseudoAngleIsMonotoneAndWraps) {
    float last = -1.0f;
    for (int i = 0; i < 3600; ++i) {
        const float a = 2.0f * 3.14159265f * float(i) / 3600.0f;
        const float p = pseudo_angle({std::cos(a), std::sin(a)});
        EXPECT_GE(p, last) << i;
        EXPECT_GE(p, 0.0f);
        EXPECT_LE(p, 4.0f);
        last = p;
    }
    EXPECT_EQ(pseudo_angle({1, 0}), 0.0f);
    EXPECT_EQ(pseudo_angle({0, 1}), 1.0f);
    EXPECT_EQ(pseudo_angle({-1, 0}), 2.0f);
    EXPECT_EQ(pseudo_angle({0, -1}), 3.0f);
}

TEST(PointMap, EqualsTheDdaOnTheComparisonScenes) {
    Tally t;
    for (const gi_test::NamedScene& named : gi_test::comparison_scenes()) compare(named.scene, named.name, 2.5f, t);
    report("comparison scenes", t);
    EXPECT_EQ(t.different, 0);
    EXPECT_GT(t.lit, 0);
    EXPECT_GT(t.shadowed, 0);
    EXPECT_LT(double(t.handed), 0.05 * double(t.asked)) << "the map hands most texels to the DDA";
}

TEST(PointMap, EqualsTheDdaOnTheStabilityGrids) {
    Tally t;
    for (const gi_test::GridScene& g : gi_test::shadow_stability_grids())
        compare(g.named.scene, g.named.name, g.dense ? 1.5f : 2.5f, t);
    {   // A cave 700 tiles from the origin: coarser floats, wider margins.
        scene::Scene s = gi_test::open_scene({712, -688}, {24, 24}, 8);
        s.walls = gi_test::cave(24, 24, 7u);
        s.walls.origin = {700, -700};
        compare(s, "far cave", 2.5f, t);
    }
    report("stability grids", t);
    EXPECT_EQ(t.different, 0);
}

TEST(PointMap, EqualsTheDdaOnRealMaps) {
    Tally t;
    for (auto [file, center] : {std::pair{"den312d.map", glm::vec2(32.0f, 40.0f)}, std::pair{"lak303d.map", glm::vec2(100.0f, 100.0f)}}) {
        auto s = gi_test::map_scene(file, center, 4);
        if (!s) GTEST_SKIP() << "needs ../shared/maps";
        compare(s->scene, file, 3.0f, t);
    }
    report("real maps", t);
    EXPECT_EQ(t.different, 0);
    EXPECT_LT(double(t.handed), 0.05 * double(t.asked));
}
