// Behaviour of the reference passes on scenes small enough to reason about by hand.
#include "gi_test_util.hpp"

#include "lantern/gi/reference.hpp"
#include "lantern/jobs/job_system.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace lantern::gi;
using gi_test::grid_from_rows;
using lantern::scene::Scene;

namespace {

// A 16x16 world, window exactly [0,16)^2 at 4 texels per tile (64x64 texels).
Scene room(const std::vector<std::string>& rows) {
    Scene s = gi_test::open_scene({8.0f, 8.0f}, {16.0f, 16.0f}, 4);
    s.walls = grid_from_rows(rows);
    return s;
}

std::vector<std::string> open_rows() { return std::vector<std::string>(16, std::string(16, '.')); }

FrameInputs inputs(const Scene& s) {
    auto w = compute_window(s.view, s.gi);
    EXPECT_TRUE(w);
    return gather_frame_inputs(s, *w);
}

glm::vec3 rgb(const Texture& t, int x, int y) {
    const float* v = t.at(x, y);
    return {v[0], v[1], v[2]};
}

} // namespace

TEST(ReferenceWindowSetup, RoomWindowIsExact) {
    Scene s = room(open_rows());
    auto in = inputs(s);
    EXPECT_EQ(in.window.width, 64);
    EXPECT_EQ(in.window.view.min_x, 0.0f);
}

TEST(ReferenceConduction, WallsBlockAirConducts) {
    auto rows = open_rows();
    rows[3][5] = '#';
    Scene s = room(rows);
    auto in = inputs(s);
    Texture c = reference_conduction(in);
    EXPECT_EQ(c.at(5 * 4 + 1, 3 * 4 + 2)[0], 0.0f); // inside the wall tile
    EXPECT_EQ(c.at(6 * 4, 3 * 4)[0], 1.0f);
    // Outside the grid is air: shift the window so half of it is outside.
    s.view = lantern::scene::OrthoView{{0.0f, 0.0f}, {16.0f, 16.0f}};
    auto shifted = inputs(s);
    Texture c2 = reference_conduction(shifted);
    EXPECT_EQ(c2.at(0, 0)[0], 1.0f);
}

TEST(ReferenceAo, OpenFieldIsUnoccludedAndWallsDarken) {
    auto rows = open_rows();
    for (int x = 0; x < 16; ++x) rows[8][x] = '#';
    Scene s = room(rows);
    auto in = inputs(s);
    Texture ao = reference_ao(in);
    EXPECT_EQ(ao.at(8 * 4, 2 * 4)[0], 1.0f);         // far from the wall
    const float near = ao.at(8 * 4 + 2, 7 * 4 + 3)[0]; // just below the wall
    EXPECT_LT(near, 1.0f);
    EXPECT_GE(near, 1.0f - 0.6f);
    in.settings.ao.strength = 0.0f;
    EXPECT_EQ(reference_ao(in).at(8 * 4 + 2, 7 * 4 + 3)[0], 1.0f);
    // Dithering moves values by less than one 8-bit step around the undithered value.
    in.settings.ao.strength = 0.6f;
    in.settings.ao.dither = true;
    Texture dithered = reference_ao(in);
    for (int y = 0; y < 64; y += 3)
        for (int x = 0; x < 64; x += 5) EXPECT_LE(std::abs(dithered.at(x, y)[0] - ao.at(x, y)[0]), 1.0f / 255.0f + 1e-6f);
}

TEST(ReferenceDirect, OpenFieldFalloffAndShadowMap) {
    Scene s = room(open_rows());
    s.point_lights.push_back({{8.0f, 8.0f}, 1.0f, {1.0f, 0.5f, 0.25f}, 2.0f, 4.0f});
    auto in = inputs(s);
    DirectTextures d = reference_direct(in);
    // Texel (40, 32): centre (10.125, 8.125), distance to (8, 8) = 2.1287.
    const glm::vec2 p = in.window.texel_center(40, 32);
    const float dist = glm::distance(p, glm::vec2(8.0f));
    const float expected = 2.0f * (1.0f - dist / 4.0f);
    EXPECT_NEAR(rgb(d.direct, 40, 32).r, expected, expected * 1e-3f);
    EXPECT_NEAR(rgb(d.direct, 40, 32).g, expected * 0.5f, expected * 1e-3f);
    EXPECT_EQ(d.shadow.at(40, 32)[0], 1.0f);
    EXPECT_EQ(d.shadow.at(40, 32)[1], 0.0f);
    // Outside the radius: dark, and the shadow map says no light reaches.
    EXPECT_EQ(rgb(d.direct, 2, 2), glm::vec3(0.0f));
    EXPECT_EQ(d.shadow.at(2, 2)[0], 0.0f);
    // Softness 2 squares the falloff.
    in.settings.light_softness = 2.0f;
    DirectTextures soft = reference_direct(in);
    EXPECT_NEAR(rgb(soft.direct, 40, 32).r, 2.0f * std::pow(1.0f - dist / 4.0f, 2.0f), 2e-3f);
}

TEST(ReferenceDirect, WallsCastShadowsAndLightFacingFaces) {
    auto rows = open_rows();
    rows[8][10] = '#'; // one wall tile at x in [10, 11), z in [8, 9)
    Scene s = room(rows);
    s.point_lights.push_back({{8.5f, 8.5f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 6.0f});
    auto in = inputs(s);
    DirectTextures d = reference_direct(in);
    // Behind the wall (x = 12.5) on the light's row: shadowed. In front: lit.
    EXPECT_EQ(d.shadow.at(12 * 4 + 2, 8 * 4 + 2)[0], 0.0f);
    EXPECT_EQ(rgb(d.direct, 12 * 4 + 2, 8 * 4 + 2), glm::vec3(0.0f));
    EXPECT_EQ(d.shadow.at(9 * 4 + 2, 8 * 4 + 2)[0], 1.0f);
    // The wall texel itself: no ground light, shadow masked; its -X face (towards the
    // light) is lit, its +X face is not.
    const int wx = 10 * 4 + 1, wz = 8 * 4 + 2;
    EXPECT_EQ(rgb(d.direct, wx, wz), glm::vec3(0.0f));
    EXPECT_EQ(d.shadow.at(wx, wz)[0], 0.0f);
    EXPECT_GT(rgb(d.wall_direct[face_neg_x], wx, wz).r, 0.0f);
    EXPECT_EQ(rgb(d.wall_direct[face_pos_x], wx, wz), glm::vec3(0.0f));
    // Ground texels have no wall-face light.
    EXPECT_EQ(rgb(d.wall_direct[face_neg_x], 9 * 4, 8 * 4), glm::vec3(0.0f));
}

// gi.wall_face_exponent k: each face's weight saturate(dot(n, to_light)) becomes its k-th
// power, so with one light a face texel's light at k = 3 is its light at k = 1 times w^2.
TEST(ReferenceDirect, WallFaceExponentRaisesEachFacesWeight) {
    auto rows = open_rows();
    rows[8][10] = '#';
    Scene s = room(rows);
    s.point_lights.push_back({{7.3f, 5.9f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 9.0f}); // off both axes
    const DirectTextures linear = reference_direct(inputs(s));
    s.gi.wall_face_exponent = 3.0f;
    const DirectTextures cubed = reference_direct(inputs(s));
    const glm::vec2 normals[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    int checked = 0;
    for (int z = 8 * 4; z < 9 * 4; ++z)
        for (int x = 10 * 4; x < 11 * 4; ++x)
            for (int f = 0; f < 4; ++f) {
                const float one = rgb(linear.wall_direct[std::size_t(f)], x, z).r;
                const float three = rgb(cubed.wall_direct[std::size_t(f)], x, z).r;
                if (one == 0.0f) {
                    EXPECT_EQ(three, 0.0f);
                    continue;
                }
                const glm::vec2 p((float(x) + 0.5f) / 4.0f, (float(z) + 0.5f) / 4.0f);
                const float w = std::max(glm::dot(normals[f], glm::normalize(glm::vec2(7.3f, 5.9f) - p)), 0.0f);
                // The face textures hold half floats (11 significant bits): 2e-3 covers two roundings.
                EXPECT_NEAR(three, one * w * w, 2e-3f * one) << "face " << f << " texel " << x << ", " << z;
                ++checked;
            }
    EXPECT_GE(checked, 16); // the -x and -z faces of the tile's texels are lit
    // Ground light does not depend on it.
    EXPECT_EQ(rgb(linear.direct, 20, 20), rgb(cubed.direct, 20, 20));
}

TEST(ReferenceDirect, EmissivesIgnoreWallsAndTheCap) {
    auto rows = open_rows();
    rows[8][10] = '#';
    Scene s = room(rows);
    s.gi.max_lights = 0; // caps point lights only
    s.emissive_lights.push_back({{8.5f, 8.5f}, {0.2f, 0.4f, 1.0f}, 1.0f, 6.0f});
    auto in = inputs(s);
    EXPECT_TRUE(in.point_lights.empty());
    ASSERT_EQ(in.emissive_lights.size(), 1u);
    DirectTextures d = reference_direct(in);
    EXPECT_GT(rgb(d.direct, 12 * 4 + 2, 8 * 4 + 2).b, 0.0f); // lit through the wall
    EXPECT_EQ(d.shadow.at(12 * 4 + 2, 8 * 4 + 2)[0], 0.0f);   // emissives do not touch the shadow map
    // Both faces along x get light (no shadows), weighted by facing.
    const int wx = 10 * 4 + 1, wz = 8 * 4 + 2;
    EXPECT_GT(rgb(d.wall_direct[face_neg_x], wx, wz).b, 0.0f);
    EXPECT_EQ(rgb(d.wall_direct[face_pos_x], wx, wz), glm::vec3(0.0f)); // faces away
}

TEST(ReferenceDirect, LightInsideAWall) {
    auto rows = open_rows();
    rows[8][8] = '#';
    Scene s = room(rows);
    s.point_lights.push_back({{8.5f, 8.5f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 5.0f});
    auto in = inputs(s);
    DirectTextures d = reference_direct(in);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            ASSERT_EQ(rgb(d.direct, x, y), glm::vec3(0.0f)) << x << "," << y;
            ASSERT_EQ(d.shadow.at(x, y)[0], 0.0f);
        }
}

TEST(ReferenceDirect, LightOutsideTheWindowReachesIn) {
    Scene s = room(open_rows());
    s.point_lights.push_back({{-2.0f, 8.0f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 5.0f}); // 2 units left of the window
    s.point_lights.push_back({{-9.0f, 8.0f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 5.0f}); // too far
    auto in = inputs(s);
    ASSERT_EQ(in.point_lights.size(), 1u);
    EXPECT_EQ(in.point_light_ids[0], 0u);
    DirectTextures d = reference_direct(in);
    EXPECT_GT(rgb(d.direct, 0, 32).r, 0.0f);
    EXPECT_EQ(rgb(d.direct, 20, 32).r, 0.0f); // beyond the radius
}

TEST(ReferenceDirect, WallsOutsideTheWindowCastShadowsIn) {
    // Grid wider than the window: a wall column at x = -1 between an outside light and the
    // window's left edge.
    auto g = grid_from_rows(std::vector<std::string>(16, std::string("..#") + std::string(19, '.')), {-3, 0});
    Scene s = gi_test::open_scene({8.0f, 8.0f}, {16.0f, 16.0f}, 4);
    s.walls = g;
    s.point_lights.push_back({{-2.5f, 8.5f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 6.0f});
    auto in = inputs(s);
    DirectTextures d = reference_direct(in);
    EXPECT_EQ(d.shadow.at(2, 8 * 4 + 2)[0], 0.0f);
    EXPECT_EQ(rgb(d.direct, 2, 8 * 4 + 2), glm::vec3(0.0f));
}

TEST(ReferenceDirect, MaxLightsKeepsTheClosest) {
    Scene s = room(open_rows());
    s.gi.max_lights = 2;
    s.point_lights.push_back({{1.0f, 1.0f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 3.0f}); // far from centre
    s.point_lights.push_back({{8.0f, 8.0f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 3.0f}); // at the centre
    s.point_lights.push_back({{9.0f, 8.0f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 3.0f});
    auto in = inputs(s);
    EXPECT_EQ(in.point_light_ids, (std::vector<std::uint32_t>{1, 2}));
}

TEST(ReferenceDirectional, SunLightsGroundAndFacesShadowedByTallWalls) {
    auto rows = open_rows();
    rows[8][8] = '#';
    Scene s = room(rows);
    s.directional_lights.push_back({glm::normalize(glm::vec3(-1.0f, -0.5f, 0.0f)), {1.0f, 0.9f, 0.8f}, 1.0f, 4.0f, 0.5f});
    auto in = inputs(s);
    DirectTextures d = reference_direct(in);
    reference_directional(in, d);
    // Sun towards +x (travelling -x): the ground just -x of the wall is in its shadow.
    EXPECT_EQ(d.shadow.at(7 * 4 + 2, 8 * 4 + 2)[1], 0.0f);
    EXPECT_EQ(d.shadow.at(12 * 4, 2 * 4)[1], 1.0f);
    // Angle modulation: saturate(-dir.y * 2) = 2 * 0.447 = 0.894.
    const float angle = std::clamp(0.5f / std::sqrt(1.25f) * 2.0f, 0.0f, 1.0f);
    EXPECT_NEAR(rgb(d.direct, 12 * 4, 2 * 4).r, angle, 2e-3f);
    // The wall's +X face looks at the sun; -X does not.
    EXPECT_GT(rgb(d.wall_direct[face_pos_x], 8 * 4 + 1, 8 * 4 + 1).r, 0.0f);
    EXPECT_EQ(rgb(d.wall_direct[face_neg_x], 8 * 4 + 1, 8 * 4 + 1), glm::vec3(0.0f));
    // Angle scale 1 removes the modulation.
    in.settings.directional_angle_scale = 1.0f;
    DirectTextures flat = reference_direct(in);
    reference_directional(in, flat);
    EXPECT_NEAR(rgb(flat.direct, 12 * 4, 2 * 4).r, 1.0f, 1e-3f);
    // A sun below the horizon lights nothing.
    in.directional_lights[0] = pack_directional({{-1.0f, 0.5f, 0.0f}, {1, 1, 1}, 1.0f, 4.0f, 0.5f});
    DirectTextures night = reference_direct(in);
    reference_directional(in, night);
    EXPECT_EQ(rgb(night.direct, 12 * 4, 2 * 4), glm::vec3(0.0f));
}

TEST(Reference, ParallelRowsEqualSerial) {
    auto rows = open_rows();
    rows[5][5] = rows[6][9] = rows[10][3] = '#';
    Scene s = room(rows);
    s.point_lights.push_back({{7.3f, 7.9f}, 1.0f, {1.0f, 0.7f, 0.2f}, 3.0f, 7.0f});
    s.emissive_lights.push_back({{3.3f, 11.2f}, {0.1f, 0.7f, 0.9f}, 1.0f, 4.0f});
    s.shadow_proxies.push_back({});
    s.shadow_proxies.back().position = {9.0f, 9.0f};
    s.directional_lights.push_back({glm::normalize(glm::vec3(0.3f, -0.6f, 0.4f)), {1, 1, 1}, 1.0f, 4.0f, 0.5f});
    auto in = inputs(s);
    DirectTextures serial = reference_direct(in);
    reference_directional(in, serial);
    lantern::jobs::JobSystem::Config c;
    c.worker_threads = 2;
    lantern::jobs::JobSystem jobs(c);
    DirectTextures parallel = reference_direct(in, {&jobs});
    reference_directional(in, parallel, {&jobs});
    EXPECT_EQ(serial.direct.texels, parallel.direct.texels);
    EXPECT_EQ(serial.shadow.texels, parallel.shadow.texels);
    for (int f = 0; f < 4; ++f) EXPECT_EQ(serial.wall_direct[f].texels, parallel.wall_direct[f].texels);
    EXPECT_EQ(reference_ao(in).texels, reference_ao(in, {&jobs}).texels);
}

// A proxy's strength (GpuShadowProxy::fade.x, the cap's fade) scales its occlusion: 1 is the
// proxy's whole shadow bit for bit, 0 none, 0.5 half.
TEST(ReferenceDirect, ProxyStrengthScalesItsOcclusion) {
    lantern::scene::ShadowProxy shape;
    shape.position = {0.0f, 0.0f};
    shape.shape = lantern::scene::ProxyShape::circle;
    shape.size = {0.5f, 0.5f};
    const GpuShadowProxy whole = pack_proxy(shape), half = pack_proxy(shape, 0.5f), none = pack_proxy(shape, 0.0f);
    EXPECT_EQ(whole.fade.x, 1.0f);
    EXPECT_EQ(pack_proxy(shape, 7.0f).fade.x, 1.0f) << "clamped";
    const glm::vec2 light(-3.0f, 0.0f);
    int shaded = 0;
    for (float x = 0.2f; x < 4.0f; x += 0.13f)
        for (float z = -1.0f; z <= 1.0f; z += 0.11f) {
            const glm::vec2 p(x, z);
            const float s1 = point_proxy_shadow(std::span(&whole, 1), light, p);
            const float s05 = point_proxy_shadow(std::span(&half, 1), light, p);
            const float s0 = point_proxy_shadow(std::span(&none, 1), light, p);
            EXPECT_EQ(s0, 1.0f);
            EXPECT_NEAR(1.0f - s05, 0.5f * (1.0f - s1), 1e-6f) << x << ", " << z;
            shaded += s1 < 0.5f ? 1 : 0;
        }
    EXPECT_GT(shaded, 20) << "the proxy shades something behind it";
}
