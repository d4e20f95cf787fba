// The texel passes' C++ reference (engine/texel/texel.hpp): UV to world against the seed's
// brute-force search, the wall DDA against seed 000's, the light term, shadows and blur.
#include "lantern/texel/texel.hpp"

#include "lantern/gi/reference.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace lantern::texel {
namespace {

gi::WallView no_walls() { return gi::WallView{}; }

TexelScene scene_of(const std::vector<Placement>& placements, const gi::WallView& walls = no_walls(),
                    float wall_height = 2.0f, float reach = 16.0f) {
    return build_scene(placements, walls, wall_height, reach);
}

// A model of `count` random triangles in UV space (overlapping ones included: the first wins)
// with random corners in the world.
Model random_model(std::mt19937& rng, int size, int count) {
    std::uniform_real_distribution<float> uv(-0.1f, 1.1f), pos(-2.0f, 2.0f);
    Model m;
    m.size = size;
    // Draws in sequence (a call's arguments are evaluated in the compiler's order).
    const auto draw3 = [&](std::uniform_real_distribution<float>& d) {
        const float x = d(rng), y = d(rng), z = d(rng);
        return glm::vec3(x, y, z);
    };
    for (int i = 0; i < count; ++i) {
        ModelTriangle t;
        for (int k = 0; k < 3; ++k) {
            t.uv[k] = glm::vec2(draw3(uv));
            t.p[k] = draw3(pos);
        }
        m.triangles.push_back(t);
    }
    // Triangles sharing an edge, as meshes have them, and one with no area in UV.
    m.triangles.push_back({{glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0)}, {glm::vec2(0.2f), glm::vec2(0.8f, 0.2f), glm::vec2(0.8f)}});
    m.triangles.push_back({{glm::vec3(0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)}, {glm::vec2(0.2f), glm::vec2(0.8f), glm::vec2(0.2f, 0.8f)}});
    m.triangles.push_back({{glm::vec3(0), glm::vec3(1), glm::vec3(2)}, {glm::vec2(0.5f), glm::vec2(0.5f), glm::vec2(0.5f)}});
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < size * size; ++i)
        m.normal_map.emplace_back(draw3(unit) * glm::vec3(1.0f, 1.0f, 0.5f) + glm::vec3(0.0f, 0.0f, 0.5f), 0.0f);
    return m;
}

bool same_bits(const TexelSurface& a, const TexelSurface& b) { return std::memcmp(&a, &b, sizeof(a)) == 0; }

TEST(UvToWorld, ScanMatchesTheSeedsBruteForceBitForBit) {
    std::mt19937 rng(7);
    int used = 0;
    for (int round = 0; round < 60; ++round) {
        std::vector<Model> models;
        for (int k = 0; k < 3; ++k) {
            const int size = 4 + int(rng() % 29), count = 1 + int(rng() % 6);
            models.push_back(random_model(rng, size, count));
        }
        std::vector<Placement> placements;
        for (const Model& m : models) {
            const float x = float(rng() % 9), z = float(rng() % 9);
            placements.push_back({&m, glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, z))});
        }
        const TexelScene scene = scene_of(placements);
        const std::vector<TexelSurface> brute = uv_to_world_brute(scene), scan = uv_to_world(scene);
        ASSERT_EQ(brute.size(), scan.size());
        for (std::size_t i = 0; i < brute.size(); ++i) {
            ASSERT_TRUE(same_bits(brute[i], scan[i])) << "round " << round << " texel " << i;
            used += brute[i].position_used.w != 0.0f;
        }
    }
    EXPECT_GT(used, 1000); // the comparison saw texels on triangles, not only empty ones
}

TEST(UvToWorld, BoxTexelsLieOnTheirFacesWithTheFacesNormals) {
    const Model box = box_model(glm::vec3(-0.5f, 0.0f, -0.25f), glm::vec3(0.5f, 1.5f, 0.25f), 8);
    ASSERT_EQ(box.triangles.size(), 10u);
    const glm::mat4 at = glm::translate(glm::mat4(1.0f), glm::vec3(3.5f, 0.0f, 2.5f));
    const std::vector<Placement> placements = {{&box, at}};
    const TexelScene scene = scene_of(placements);
    const std::vector<TexelSurface> s = uv_to_world(scene);
    // Texel counts per face: +-x 4 x 12, +-z 8 x 12, top 8 x 4.
    int used = 0;
    int by_axis[3] = {0, 0, 0};
    for (const TexelSurface& t : s) {
        if (t.position_used.w == 0.0f) continue;
        ++used;
        const glm::vec3 p = glm::vec3(t.position_used) - glm::vec3(3.5f, 0.0f, 2.5f);
        const glm::vec3 n(t.normal_triangle);
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        EXPECT_EQ(n, glm::vec3(t.geo_normal)); // a flat normal map leaves the normal alone
        // On the face its normal names, inside the face's extent.
        const glm::vec3 half(0.5f, 0.75f, 0.25f), centre(0.0f, 0.75f, 0.0f);
        for (int a = 0; a < 3; ++a) {
            if (std::abs(n[a]) < 0.5f) {
                EXPECT_LE(std::abs(p[a] - centre[a]), half[a] + 1e-5f);
                continue;
            }
            EXPECT_NEAR(p[a], centre[a] + half[a] * n[a], 1e-5f);
            ++by_axis[a];
        }
    }
    EXPECT_EQ(by_axis[0], 2 * 4 * 12);
    EXPECT_EQ(by_axis[2], 2 * 8 * 12);
    EXPECT_EQ(by_axis[1], 8 * 4);
    EXPECT_EQ(used, 2 * 4 * 12 + 2 * 8 * 12 + 8 * 4);
    // The gutters between faces hold nothing.
    EXPECT_LT(used, box.size * box.size);
}

TEST(UvToWorld, NormalMapTiltsTheNormalAlongTheTangentFrame) {
    Model box = box_model(glm::vec3(0.0f), glm::vec3(1.0f), 4);
    ASSERT_EQ(box.size, 16); // five 4 x 4 faces with gutters: +x at texels (1..4, 1..4)
    box.normal_map.assign(std::size_t(box.size) * box.size, glm::vec4(0.5f, 0.5f, 1.0f, 0.0f));
    const int texel = 2 * box.size + 2; // inside the first face (+x): rows 1..4, columns 1..4
    box.normal_map[texel] = glm::vec4(1.0f, 0.5f, 0.5f, 0.0f); // all tangent (+u)
    box.normal_map[texel + 1] = glm::vec4(0.5f, 1.0f, 0.5f, 0.0f); // all green: up the image
    const std::vector<Placement> placements = {{&box, glm::mat4(1.0f)}};
    const TexelScene scene = scene_of(placements);
    const std::vector<TexelSurface> s = uv_to_world(scene);
    ASSERT_NE(s[texel].position_used.w, 0.0f);
    EXPECT_EQ(glm::vec3(s[texel].geo_normal), glm::vec3(1, 0, 0));
    // +x face: +u runs along -z seen from outside; green (up the image) is world +y.
    EXPECT_NEAR(glm::distance(glm::vec3(s[texel].normal_triangle), glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(glm::vec3(s[texel + 1].normal_triangle), glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
}

TEST(TexelWalls, BelowTheWallTopsItIsSeedZerosDda) {
    std::mt19937 rng(11);
    for (int round = 0; round < 40; ++round) {
        scene::WallGrid grid;
        grid.width = 12;
        grid.height = 10;
        grid.origin = glm::ivec2(-2, -3);
        grid.cells.resize(std::size_t(grid.width) * grid.height);
        for (auto& c : grid.cells) c = (rng() % 4) == 0 ? 1 : 0;
        const gi::WallView view = gi::WallView::of(grid);
        Model tiny = box_model(glm::vec3(0.0f), glm::vec3(0.1f), 1);
        const std::vector<Placement> placements = {{&tiny, glm::translate(glm::mat4(1.0f), glm::vec3(4.0f, 0.0f, 2.0f))}};
        const TexelScene scene = scene_of(placements, view, 2.0f, 30.0f);
        std::uniform_real_distribution<float> x(-3.0f, 11.0f), z(-4.0f, 8.0f), y(0.0f, 1.9f);
        for (int i = 0; i < 400; ++i) {
            glm::vec3 a, b;
            for (glm::vec3* p : {&a, &b}) { // one draw after the other (argument order is the compiler's)
                p->x = x(rng);
                p->y = y(rng);
                p->z = z(rng);
            }
            const float radius = glm::distance(glm::vec2(a.x, a.z), glm::vec2(b.x, b.z)) + 1.0f;
            ASSERT_EQ(wall_visibility(scene.walls, 2.0f, a, b),
                      gi::shadow_dda(view, glm::vec2(a.x, a.z), glm::vec2(b.x, b.z), radius))
                << "round " << round << " ray " << i;
        }
    }
}

TEST(TexelWalls, ALightAboveTheWallsShinesOverThem) {
    scene::WallGrid grid;
    grid.width = 8;
    grid.height = 3;
    grid.cells.assign(24, 0);
    for (int z = 0; z < 3; ++z) grid.cells[4 + z * 8] = 1; // a wall along x = 4
    const gi::WallView view = gi::WallView::of(grid);
    Model tiny = box_model(glm::vec3(0.0f), glm::vec3(0.1f), 1);
    const std::vector<Placement> placements = {{&tiny, glm::mat4(1.0f)}};
    const TexelScene scene = scene_of(placements, view, 2.0f, 30.0f);
    const glm::vec3 point(6.5f, 0.5f, 1.5f);
    EXPECT_EQ(wall_visibility(scene.walls, 2.0f, glm::vec3(1.5f, 1.5f, 1.5f), point), 0.0f);
    // From 2.5 above the ground at x = 1.5 to 0.5 at x = 6.5: at the wall (x 4..5) the ray is
    // 1.5..1.1 high: still blocked by walls of 2, clear of walls of 1.
    EXPECT_EQ(wall_visibility(scene.walls, 2.0f, glm::vec3(1.5f, 2.5f, 1.5f), point), 0.0f);
    EXPECT_EQ(wall_visibility(scene.walls, 1.0f, glm::vec3(1.5f, 2.5f, 1.5f), point), 1.0f);
    EXPECT_EQ(wall_visibility(scene.walls, 2.0f, glm::vec3(1.5f, 6.0f, 1.5f), point), 1.0f);
}

TEST(TexelLight, TheSeedsTermFallsOffWithDistanceAndAngle) {
    const Model box = box_model(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f), 4);
    const std::vector<Placement> placements = {{&box, glm::mat4(1.0f)}};
    const TexelScene scene = scene_of(placements);
    const std::vector<TexelSurface> s = uv_to_world(scene);
    const TexelLight light = make_light(glm::vec3(3.0f, 0.5f, 0.2f), glm::vec3(1.0f, 0.5f, 0.25f), 2.0f, 6.0f);
    int lit = 0, dark = 0;
    for (const TexelSurface& t : s) {
        if (t.position_used.w == 0.0f) continue;
        const glm::vec3 got = texel_light(scene, std::span(&light, 1), t);
        const glm::vec3 p(t.position_used), n(t.normal_triangle);
        const glm::vec3 dir = glm::normalize(p - glm::vec3(3.0f, 0.5f, 0.2f));
        const float c = glm::dot(dir, n), d = glm::distance(p, glm::vec3(3.0f, 0.5f, 0.2f));
        if (c >= 0.0f) {
            EXPECT_EQ(got, glm::vec3(0.0f));
            ++dark;
            continue;
        }
        const float v = (1.0f - d / 6.0f) * std::abs(c);
        const glm::vec3 want = glm::vec3(2.0f, 1.0f, 0.5f) * v * v;
        EXPECT_NEAR(got.r, want.r, 1e-5f);
        EXPECT_NEAR(got.g, want.g, 1e-5f);
        EXPECT_NEAR(got.b, want.b, 1e-5f);
        ++lit;
    }
    EXPECT_GT(lit, 0);
    EXPECT_GT(dark, 0);
}

TEST(TexelLight, AModelBehindAWallIsUnlitByALightOnTheOtherSide) {
    scene::WallGrid grid;
    grid.width = 10;
    grid.height = 10;
    grid.cells.assign(100, 0);
    for (int z = 0; z < 10; ++z) grid.cells[5 + z * 10] = 1; // wall column x = 5
    const gi::WallView view = gi::WallView::of(grid);
    const Model box = box_model(glm::vec3(-0.3f, 0.0f, -0.3f), glm::vec3(0.3f, 1.0f, 0.3f), 8);
    const std::vector<Placement> placements = {{&box, glm::translate(glm::mat4(1.0f), glm::vec3(7.5f, 0.0f, 5.5f))}};
    const TexelScene scene = scene_of(placements, view, 2.0f, 8.0f);
    const std::vector<TexelSurface> s = uv_to_world(scene);
    const TexelLight behind = make_light(glm::vec3(2.5f, 1.0f, 5.5f), glm::vec3(1.0f), 1.0f, 8.0f);
    const TexelLight same_side = make_light(glm::vec3(9.5f, 1.0f, 5.5f), glm::vec3(1.0f), 1.0f, 8.0f);
    TexelLight unshadowed = behind;
    unshadowed.color_type.w = float(ShadowType::none);
    float total_behind = 0.0f, total_same = 0.0f, total_none = 0.0f;
    for (const TexelSurface& t : s) {
        total_behind += texel_light(scene, std::span(&behind, 1), t).r;
        total_same += texel_light(scene, std::span(&same_side, 1), t).r;
        total_none += texel_light(scene, std::span(&unshadowed, 1), t).r;
    }
    EXPECT_EQ(total_behind, 0.0f);
    EXPECT_GT(total_same, 1.0f);
    EXPECT_GT(total_none, 1.0f); // shadow type none: the wall does not stop it
}

// A unit quad at height `h` over a receiver at y = 0, facing a light straight above.
struct BlurRig {
    Model floor_model, occluder;
    TexelScene scene;
    std::vector<TexelSurface> s;
    BlurRig(float h) {
        floor_model = box_model(glm::vec3(-2.0f, -0.2f, -2.0f), glm::vec3(2.0f, 0.0f, 2.0f), 4);
        occluder = box_model(glm::vec3(-0.25f, h - 0.01f, -0.25f), glm::vec3(0.25f, h, 0.25f), 4);
        const std::vector<Placement> placements = {{&floor_model, glm::mat4(1.0f)}, {&occluder, glm::mat4(1.0f)}};
        scene = scene_of(placements);
        s = uv_to_world(scene);
    }
    // The floor's top texel nearest the origin.
    const TexelSurface& centre() const {
        const TexelSurface* best = nullptr;
        for (std::uint32_t i = 0; i < scene.placements[1].ranges.z; ++i) {
            const TexelSurface& t = s[i];
            if (t.position_used.w == 0.0f || t.geo_normal.y < 0.5f) continue;
            if (!best || glm::length(glm::vec3(t.position_used)) < glm::length(glm::vec3(best->position_used))) best = &t;
        }
        return *best;
    }
};

TEST(TexelLight, BlurredShadowsLightenWithNlrOverLrAsTheSeedStates) {
    const glm::vec3 lamp(0.0f, 4.0f, 0.0f);
    float previous = -1.0f;
    for (float h : {0.5f, 1.0f, 2.0f, 3.0f}) {
        const BlurRig rig(h);
        const TexelSurface& t = rig.centre();
        const glm::vec3 p(t.position_used);
        const int own = int(t.normal_triangle.w + 0.5f);
        const TexelLight blurred = make_light(lamp, glm::vec3(1.0f), 1.0f, 10.0f, ShadowType::blurred, 1.0f, 1.0f);
        const TexelLight hard = make_light(lamp, glm::vec3(1.0f), 1.0f, 10.0f, ShadowType::hard);
        const TexelLight sharper = make_light(lamp, glm::vec3(1.0f), 1.0f, 10.0f, ShadowType::blurred, 0.5f, 2.0f);
        EXPECT_EQ(occluder_visibility(rig.scene, hard, glm::vec3(hard.position_range), p, own), 0.0f);
        // NLR: the texel to the occluder's lit top face (its other faces face away), along
        // the ray: the heights' ratio of LR.
        const float lr = glm::distance(lamp, p), nlr = (h - p.y) / (lamp.y - p.y) * lr;
        const float v = occluder_visibility(rig.scene, blurred, glm::vec3(blurred.position_range), p, own);
        EXPECT_NEAR(v, nlr / lr, 1e-5f) << "occluder at " << h;
        EXPECT_NEAR(occluder_visibility(rig.scene, sharper, glm::vec3(sharper.position_range), p, own), std::pow(nlr / lr, 2.0f) * 0.5f, 1e-5f);
        EXPECT_GT(v, previous); // nearer the light: more blur, a lighter shadow
        previous = v;
    }
}

TEST(TexelLight, OccludersFacingAwayOrBeyondTheTexelCastNothing) {
    const BlurRig rig(1.0f);
    const TexelSurface& t = rig.centre();
    const glm::vec3 p(t.position_used);
    const int own = int(t.normal_triangle.w + 0.5f);
    // A light between the occluder and the floor: the occluder is behind it.
    const TexelLight under = make_light(glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(1.0f), 1.0f, 10.0f, ShadowType::hard);
    EXPECT_EQ(occluder_visibility(rig.scene, under, glm::vec3(under.position_range), p, own), 1.0f);
    // A light inside the occluder (its faces all face away from it) casts no occluder shadow.
    const TexelLight inside = make_light(glm::vec3(0.0f, 0.995f, 0.0f), glm::vec3(1.0f), 1.0f, 10.0f, ShadowType::hard);
    EXPECT_EQ(occluder_visibility(rig.scene, inside, glm::vec3(inside.position_range), p, own), 1.0f);
}

TEST(TexelLight, AmbientBlendsBetweenLightsAndFallsOffWithRange) {
    const Model box = box_model(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f), 2);
    const std::vector<Placement> placements = {{&box, glm::mat4(1.0f)}};
    const TexelScene scene = scene_of(placements);
    const std::vector<TexelSurface> s = uv_to_world(scene);
    // Lights far above (no direct light reaches the faces turned away): red and blue ambient.
    const TexelLight red = make_light(glm::vec3(0, 20, 0), glm::vec3(0.0f), 1.0f, 40.0f, ShadowType::none, 1, 1, glm::vec3(1, 0, 0));
    const TexelLight blue = make_light(glm::vec3(0, 20, 0), glm::vec3(0.0f), 1.0f, 40.0f, ShadowType::none, 1, 1, glm::vec3(0, 0, 1));
    const TexelLight both[2] = {red, blue};
    for (const TexelSurface& t : s) {
        if (t.position_used.w == 0.0f) continue;
        const glm::vec3 got = texel_light(scene, both, t);
        const float falloff = 1.0f - glm::distance(glm::vec3(t.position_used), glm::vec3(0, 20, 0)) / 40.0f;
        EXPECT_NEAR(got.r, falloff, 1e-5f);
        EXPECT_NEAR(got.b, falloff, 1e-5f); // purple
        EXPECT_EQ(got.g, 0.0f);
    }
    // Beyond its range a light adds nothing, not even ambient.
    const TexelLight near = make_light(glm::vec3(0, 20, 0), glm::vec3(1.0f), 1.0f, 5.0f, ShadowType::none, 1, 1, glm::vec3(1));
    for (const TexelSurface& t : s) EXPECT_EQ(texel_light(scene, std::span(&near, 1), t), glm::vec3(0.0f));
}

TEST(TexelLight, ALowSunLeavesAModelInAWallsShadowAHighOneDoesNot) {
    scene::WallGrid grid;
    grid.width = 12;
    grid.height = 6;
    grid.cells.assign(72, 0);
    for (int z = 0; z < 6; ++z) grid.cells[std::size_t(4 + z * 12)] = 1; // a wall along x = 4, 2 high
    const gi::WallView view = gi::WallView::of(grid);
    // A box 1 high, 1.5 .. 2.1 tiles beyond the wall's far side.
    const Model box = box_model(glm::vec3(-0.3f, 0.0f, -0.3f), glm::vec3(0.3f, 1.0f, 0.3f), 8);
    const std::vector<Placement> placements = {{&box, glm::translate(glm::mat4(1.0f), glm::vec3(6.8f, 0.0f, 3.0f))}};
    const TexelScene scene = scene_of(placements, view, 2.0f, 40.0f);
    const std::vector<TexelSurface> s = uv_to_world(scene);
    // Suns travelling +x: slope 0.4 throws the wall's shadow 5 tiles (over the box), slope 3
    // 0.67 tiles (short of it).
    const auto total = [&](float slope, ShadowType shadow) {
        const TexelLight sun = make_sun(glm::vec3(1.0f, -slope, 0.0f), glm::vec3(1.0f), 1.0f, shadow, 40.0f);
        float sum = 0.0f;
        int lit = 0;
        for (const TexelSurface& t : s) {
            const float r = texel_light(scene, std::span(&sun, 1), t).r;
            sum += r;
            lit += r > 0.0f;
        }
        return std::pair{sum, lit};
    };
    EXPECT_EQ(total(0.4f, ShadowType::hard).second, 0);
    EXPECT_GT(total(0.4f, ShadowType::none).second, 50); // the -x face and the top face the sun
    EXPECT_GT(total(3.0f, ShadowType::hard).second, 50);
    // No falloff: a texel facing the sun squarely gets its colour x cos^2.
    const TexelLight overhead = make_sun(glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(0.5f, 1.0f, 2.0f), 1.0f, ShadowType::hard,
                                         40.0f, glm::vec3(0.01f));
    for (const TexelSurface& t : s) {
        if (t.position_used.w == 0.0f) continue;
        const glm::vec3 got = texel_light(scene, std::span(&overhead, 1), t);
        if (t.geo_normal.y > 0.5f) EXPECT_LT(glm::distance(got, glm::vec3(0.51f, 1.01f, 2.01f)), 1e-6f);
        else EXPECT_EQ(got, glm::vec3(0.01f)); // sides: edge-on to the sun, ambient only
    }
}

TEST(TexelLight, ModelsShadeEachOtherFromTheSun) {
    // A tall box west of a short one, a low sun from the west: the short one's -x face is dark.
    const Model tall = box_model(glm::vec3(-0.4f, 0.0f, -0.4f), glm::vec3(0.4f, 2.0f, 0.4f), 4);
    const Model small = box_model(glm::vec3(-0.3f, 0.0f, -0.3f), glm::vec3(0.3f, 0.6f, 0.3f), 8);
    const std::vector<Placement> placements = {{&tall, glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 1.0f))},
                                               {&small, glm::translate(glm::mat4(1.0f), glm::vec3(2.5f, 0.0f, 1.0f))}};
    const TexelScene scene = scene_of(placements);
    const std::vector<TexelSurface> s = uv_to_world(scene);
    const TexelLight sun = make_sun(glm::vec3(1.0f, -0.5f, 0.0f), glm::vec3(1.0f), 1.0f, ShadowType::hard, 30.0f);
    int dark_west_faces = 0, west_faces = 0;
    for (std::uint32_t i = scene.placements[1].ranges.z; i < s.size(); ++i) {
        if (s[i].position_used.w == 0.0f || s[i].geo_normal.x > -0.5f) continue;
        ++west_faces;
        dark_west_faces += texel_light(scene, std::span(&sun, 1), s[i]) == glm::vec3(0.0f);
    }
    EXPECT_GT(west_faces, 0);
    EXPECT_EQ(dark_west_faces, west_faces);
}

TEST(TexelLight, ApplyAddsTheBakeAndSaturates) {
    const Model box = box_model(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f), 4);
    const std::vector<Placement> placements = {{&box, glm::mat4(1.0f)}};
    const TexelScene scene = scene_of(placements);
    const std::vector<TexelSurface> s = uv_to_world(scene);
    const TexelLight sun_lamp = make_light(glm::vec3(0, 3, 0), glm::vec3(4.0f, 0.2f, 0.1f), 1.0f, 8.0f);
    const TexelLight torch = make_light(glm::vec3(2, 0.5f, 0), glm::vec3(0.3f, 0.3f, 0.1f), 1.0f, 5.0f);
    const std::vector<glm::vec4> baked = reference_light(scene, s, std::span(&sun_lamp, 1));
    const std::vector<glm::vec4> live = reference_light(scene, s, std::span(&torch, 1));
    const std::vector<glm::vec4> lit = reference_light(scene, s, std::span(&torch, 1), baked);
    bool saturated = false;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i].position_used.w == 0.0f) {
            EXPECT_EQ(lit[i], glm::vec4(0.0f));
            continue;
        }
        const glm::vec4 want = glm::clamp(live[i] + baked[i], glm::vec4(0.0f), glm::vec4(1.0f));
        EXPECT_EQ(lit[i], want);
        saturated |= live[i].r + baked[i].r > 1.0f;
    }
    EXPECT_TRUE(saturated); // the case the clamp is for was met
}

// Seed 001's static lights beside a model that moves: baked once for still models, without
// the moving model's shadow, and live on the moving model (its bake is 0), never twice.
TEST(TexelLight, ABakedLightIsInTheBakeOnStillModelsAndLiveOnMovingOnes) {
    const Model crate = box_model(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f), 4);
    const Model slab = box_model(glm::vec3(-0.4f, 0.0f, -0.4f), glm::vec3(0.4f, 0.2f, 0.4f), 4);
    // The slab (the mover) hovers over the crate, under the lamp.
    std::vector<Placement> placements = {{&crate, glm::mat4(1.0f)},
                                         {&slab, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.6f, 0.0f)), true}};
    const TexelScene scene = scene_of(placements);
    const TexelScene crate_alone = scene_of({placements[0]});
    const std::vector<TexelSurface> s = uv_to_world(scene);
    const TexelLight lamp = make_light(glm::vec3(0.0f, 3.0f, 0.0f), glm::vec3(0.8f, 0.6f, 0.4f), 1.0f, 8.0f);
    const TexelLight torch = make_light(glm::vec3(2.0f, 0.5f, 0.0f), glm::vec3(0.3f, 0.3f, 0.1f), 1.0f, 5.0f);
    const std::vector<glm::vec4> baked = reference_light(scene, s, std::span(&lamp, 1));
    const std::vector<TexelLight> frame = {torch, as_baked(lamp)};
    const std::vector<glm::vec4> lit = reference_light(scene, s, frame, baked);
    const std::uint32_t first_slab = scene.placements[1].ranges.z;
    int crate_top_lit = 0, slab_texels = 0;
    for (std::uint32_t i = 0; i < s.size(); ++i) {
        if (s[i].position_used.w == 0.0f) continue;
        if (i >= first_slab) { // the mover: no bake; the lamp and the torch live, with all shadows
            ++slab_texels;
            EXPECT_EQ(baked[i], glm::vec4(0.0f));
            const glm::vec3 live = texel_light(scene, std::span(&lamp, 1), s[i]) + texel_light(scene, std::span(&torch, 1), s[i]);
            EXPECT_EQ(lit[i], glm::clamp(glm::vec4(live, 1.0f), glm::vec4(0.0f), glm::vec4(1.0f)));
            continue;
        }
        // The crate: the bake as if the mover were not there (its shadow is not frozen in)...
        EXPECT_EQ(baked[i], glm::vec4(texel_light(crate_alone, std::span(&lamp, 1), s[i]), 1.0f)) << "texel " << i;
        crate_top_lit += s[i].geo_normal.y > 0.5f && baked[i].r > 0.0f;
        // ...and the realtime pass adds the torch alone to it: the lamp is not counted twice.
        const glm::vec4 want = glm::clamp(glm::vec4(texel_light(scene, std::span(&torch, 1), s[i]), 1.0f) + baked[i],
                                          glm::vec4(0.0f), glm::vec4(1.0f));
        EXPECT_EQ(lit[i], want) << "texel " << i;
    }
    EXPECT_GT(slab_texels, 10);
    EXPECT_GT(crate_top_lit, 8); // under the mover, lit in the bake
    // Live, the mover does shade the crate's top from the lamp.
    int shaded_live = 0;
    for (std::uint32_t i = 0; i < first_slab; ++i)
        if (s[i].position_used.w != 0.0f && s[i].geo_normal.y > 0.5f)
            shaded_live += texel_light(scene, std::span(&lamp, 1), s[i]).r < baked[i].r;
    EXPECT_GT(shaded_live, 8);
}

TEST(TexelScene, MovingAPlacementMovesItsTexels) {
    const Model box = box_model(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f), 4);
    const std::vector<Placement> placements = {{&box, glm::mat4(1.0f)}, {&box, glm::mat4(1.0f)}};
    TexelScene scene = scene_of(placements);
    std::vector<TexelSurface> s = uv_to_world(scene);
    const std::vector<TexelSurface> before = s;
    const glm::mat4 moved = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(3, 0, 1)), 0.7f, glm::vec3(0, 1, 0));
    move_placement(scene, 1, box, moved);
    uv_to_world_placement(scene, 1, s);
    const std::uint32_t first = scene.placements[1].ranges.z;
    for (std::uint32_t i = 0; i < s.size(); ++i) {
        if (i < first) {
            EXPECT_TRUE(same_bits(s[i], before[i]));
            continue;
        }
        EXPECT_EQ(s[i].position_used.w, before[i].position_used.w);
        if (s[i].position_used.w == 0.0f) continue;
        const glm::vec3 want(moved * glm::vec4(glm::vec3(before[i].position_used), 1.0f));
        EXPECT_NEAR(glm::distance(glm::vec3(s[i].position_used), want), 0.0f, 1e-4f);
    }
    EXPECT_TRUE(same_bits(uv_to_world_brute(scene)[first + 40], s[first + 40]));
}

} // namespace
} // namespace lantern::texel
