// The sun's shadow map (gi.sun_shadow_method = shadow_map) against the DDA it replaces:
// every texel's visibility (ground texels from their centre, wall texels from just outside
// each face, as the directional pass asks) is the same, for suns from every direction and
// height, on the comparison scenes, the stability grids (one-texel corridors, a
// checkerboard where rays pass through tile corners, all walls, no walls) and the real maps
// den312d and lak303d (skipped without ../shared). The map hands close calls (a ray within
// sun_map_ambiguity of a wall tile's corner) to the DDA: the test counts them and keeps
// them a small share, or the map would be the DDA by another name.
#include "lantern/gi/reference.hpp"
#include "lantern/gi/sun_map.hpp"
#include "test_scenes.hpp"

#include <glm/trigonometric.hpp>
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

// Suns from `azimuths` directions (degrees; 0, 45 and 90 included: axis-parallel and exact
// diagonal rays) at three heights.
std::vector<scene::DirectionalLight> suns(int azimuths) {
    std::vector<scene::DirectionalLight> out;
    for (float elevation : {8.0f, 30.0f, 65.0f})
        for (int a = 0; a < azimuths; ++a) {
            const float az = glm::radians(360.0f * float(a) / float(azimuths));
            const float el = glm::radians(elevation);
            scene::DirectionalLight sun;
            sun.direction = glm::normalize(glm::vec3(std::cos(az) * std::cos(el), -std::sin(el), std::sin(az) * std::cos(el)));
            out.push_back(sun);
        }
    return out;
}

void compare(scene::Scene s, const std::string& name, int azimuths, Tally& total) {
    for (float wall_height : {1.0f, 3.0f}) {
        s.wall_height = wall_height;
        for (const scene::DirectionalLight& sun : suns(azimuths)) {
            s.directional_lights = {sun};
            auto window = compute_window(s.view, s.gi);
            ASSERT_TRUE(window) << name;
            const FrameInputs in = gather_frame_inputs(s, *window);
            ASSERT_EQ(in.directional_lights.size(), 1u);
            const GpuDirectionalLight& g = in.directional_lights[0];
            const std::vector<SunMap> maps = build_sun_maps(in);
            const float max_distance = g.direction_base.w * g.color_multiplier.w;
            const GiWindow& w = in.window;
            auto check = [&](glm::vec2 from) {
                const float dda = directional_shadow_dda(in.walls, from, glm::vec3(g.direction_base), max_distance, in.wall_height);
                int handed = 0;
                const float map = sun_map_visibility(maps[0], in.walls, g, from, in.wall_height, &handed);
                ++total.asked;
                total.lit += dda > 0.0f;
                total.shadowed += dda == 0.0f;
                total.handed += handed;
                if (map != dda) {
                    ++total.different;
                    if (total.different <= 10)
                        ADD_FAILURE() << name << ": sun " << sun.direction.x << ", " << sun.direction.y << ", " << sun.direction.z
                                      << ", wall height " << wall_height << ": from (" << from.x << ", " << from.y
                                      << ") the DDA gives " << dda << ", the map " << map;
                }
            };
            for (int y = 0; y < w.height; ++y)
                for (int x = 0; x < w.width; ++x) {
                    const glm::vec2 p = w.texel_center(x, y);
                    const glm::ivec2 cell(int(std::floor(p.x)), int(std::floor(p.y)));
                    if (!in.walls.is_wall(cell.x, cell.y)) {
                        check(p);
                        continue;
                    }
                    const glm::vec4 mask = wall_face_mask(in.walls, cell);
                    for (int f = 0; f < 4; ++f)
                        if (mask[f] > 0.0f) {
                            // face_position: 1e-3 outside the face (reference_passes.cpp)
                            const glm::vec2 q = f == 0   ? glm::vec2(float(cell.x) + 1.001f, p.y)
                                                : f == 1 ? glm::vec2(float(cell.x) - 0.001f, p.y)
                                                : f == 2 ? glm::vec2(p.x, float(cell.y) + 1.001f)
                                                         : glm::vec2(p.x, float(cell.y) - 0.001f);
                            check(q);
                        }
                }
        }
    }
}

void report(const char* what, const Tally& t) {
    std::printf("%s: %lld visibilities (%lld lit, %lld shadowed), %lld differ, %lld (%.3f %%) handed to the DDA\n", what,
                t.asked, t.lit, t.shadowed, t.different, t.handed, 100.0 * double(t.handed) / double(std::max(t.asked, 1LL)));
}

} // namespace

TEST(SunMap, EqualsTheDdaOnTheComparisonScenes) {
    Tally t;
    for (const gi_test::NamedScene& named : gi_test::comparison_scenes()) compare(named.scene, named.name, 24, t);
    report("comparison scenes", t);
    EXPECT_EQ(t.different, 0);
    EXPECT_GT(t.lit, 0);
    EXPECT_GT(t.shadowed, 0);
    EXPECT_LT(double(t.handed), 0.05 * double(t.asked)) << "the map hands most texels to the DDA";
}

TEST(SunMap, EqualsTheDdaOnTheStabilityGrids) {
    Tally t;
    for (const gi_test::GridScene& g : gi_test::shadow_stability_grids()) compare(g.named.scene, g.named.name, g.dense ? 16 : 8, t);
    report("stability grids", t);
    EXPECT_EQ(t.different, 0);
}

TEST(SunMap, EqualsTheDdaOnRealMaps) {
    Tally t;
    for (auto [file, center] : {std::pair{"den312d.map", glm::vec2(32.0f, 40.0f)}, std::pair{"lak303d.map", glm::vec2(100.0f, 100.0f)}}) {
        auto s = gi_test::map_scene(file, center, 1);
        if (!s) GTEST_SKIP() << "needs ../shared/maps";
        compare(s->scene, file, 12, t);
    }
    report("real maps", t);
    EXPECT_EQ(t.different, 0);
    EXPECT_LT(double(t.handed), 0.05 * double(t.asked));
}

// The directional and mixed rows each map only the suns they light (build_sun_maps' kinds):
// a sun of the other kind gets a stand-in with no tiles, and each map keeps its sun's index.
TEST(SunMap, EachPassMapsOnlyTheSunsItLights) {
    scene::Scene s = gi_test::open_scene({20, 15}, {40, 30}, 4);
    s.walls = gi_test::cave(40, 30, 7, 0.42f);
    s.directional_lights = {suns(4)[1], suns(4)[6]};
    auto window = compute_window(s.view, s.gi);
    ASSERT_TRUE(window);
    FrameInputs in = gather_frame_inputs(s, *window);
    ASSERT_EQ(in.directional_lights.size(), 2u);
    in.directional_lights[1].bounce.y = 1.0f; // mixed (is_mixed_sun), as split_for_bake marks it
    ASSERT_TRUE(!is_mixed_sun(in.directional_lights[0]) && is_mixed_sun(in.directional_lights[1]));
    const std::vector<SunMap> all = build_sun_maps(in);
    ASSERT_EQ(all.size(), 2u);
    ASSERT_FALSE(all[0].entries.empty() || all[1].entries.empty()) << "both suns cast grid shadows here";
    auto same = [](const SunMap& a, const SunMap& b) {
        return a.lit_everywhere == b.lit_everywhere && a.bins == b.bins && a.v0 == b.v0 && a.reach == b.reach &&
               a.first == b.first && a.entries == b.entries;
    };
    for (const SunKinds kinds : {SunKinds::realtime, SunKinds::mixed}) {
        const std::vector<SunMap> maps = build_sun_maps(in, kinds);
        ASSERT_EQ(maps.size(), 2u);
        const std::size_t lit = kinds == SunKinds::mixed ? 1 : 0, other = 1 - lit;
        EXPECT_TRUE(same(maps[lit], all[lit]));
        EXPECT_TRUE(maps[other].lit_everywhere);
        EXPECT_TRUE(maps[other].entries.empty());
        EXPECT_EQ(maps[other].first.size(), 1u);
        const PackedSunMaps packed = pack_sun_maps(maps);
        EXPECT_EQ(packed.headers.size(), 4u); // two texels a sun, in the frame's order
    }
}
