// Seed 000's wall options on the reference (the GPU side is compared with it texel by texel
// in gpu_compare_test.cpp, scenes culled_faces_wall_ao and no_wall_lighting):
//  - gi.wall_lighting off leaves out every wall-face pass and texture and shades walls as
//    ground, changing nothing else;
//  - gi.wall_faces culls faces: a face left out is neither traced nor stored, and every other
//    texture stays bit for bit what it was;
//  - gi.ao.walls darkens a face by the AO of the ground texel just outside it.
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/reference.hpp"
#include "lantern/scene/loader.hpp"
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace lantern;
using namespace lantern::gi;

namespace {

struct FrameRun {
    FrameInputs in;
    PassPlan plan;
    FrameResult result;
};

FrameRun run(const scene::Scene& s) {
    FrameRun r;
    auto window = compute_window(s.view, s.gi.padding, s.gi.resolution);
    EXPECT_TRUE(window);
    r.in = gather_frame_inputs(s, *window);
    r.plan = plan_passes(r.in, true);
    r.result = run_reference_frame(r.in, r.plan);
    return r;
}

bool is_face_texture(const std::string& name) { return name.rfind("wall_", 0) == 0; }

bool same(const Texture& a, const Texture& b) { return a.width == b.width && a.height == b.height && a.texels == b.texels; }

// Rooms with a sun, a proxy and point and emissive lights: every pass runs.
scene::Scene walled_scene() {
    scene::Scene s = gi_test::comparison_scene("rooms").scene;
    s.directional_lights.push_back({glm::normalize(glm::vec3(0.4f, -0.8f, -0.3f)), {1.0f, 0.9f, 0.8f}, 0.4f, 4.0f, 0.3f});
    scene::ShadowProxy proxy;
    proxy.position = {6.5f, 6.5f};
    s.shadow_proxies.push_back(proxy);
    s.gi.heat_rounds = 6;
    return s;
}

} // namespace

TEST(WallOptions, WallLightingOffLeavesOutEveryFacePassAndTexture) {
    scene::Scene s = walled_scene();
    const FrameRun on = run(s);
    s.gi.wall_lighting = false;
    const FrameRun off = run(s);

    EXPECT_FALSE(off.plan.run.has(Pass::wall_indirect));
    EXPECT_EQ(off.plan.reason[int(Pass::wall_indirect)], "wall lighting off");
    const TexSet written = textures_written(off.in, off.plan);
    for (int t = 0; t < registered_texture_count(); ++t) {
        if (is_face_texture(tex_name(Tex(t)))) {
            EXPECT_FALSE(written.has(Tex(t))) << tex_name(Tex(t)) << " allocated";
        }
    }
    EXPECT_LT(texture_bytes(off.in, off.plan, TextureStorage::gpu), texture_bytes(on.in, on.plan, TextureStorage::gpu));

    // Every other texture is what it was: a wall texel's ground light is zero either way.
    int faces_on = 0;
    for (const auto& [name, texture] : on.result.textures) {
        if (is_face_texture(name)) {
            ++faces_on;
            EXPECT_EQ(off.result.textures.count(name), 0u) << name << " produced with wall lighting off";
            continue;
        }
        ASSERT_EQ(off.result.textures.count(name), 1u) << name;
        EXPECT_TRUE(same(texture, off.result.textures.at(name))) << name << " changed";
    }
    EXPECT_EQ(faces_on, 8);

    // The lit image: walls shade as ground, which conduction makes black; the ground is as it was.
    ASSERT_TRUE(on.result.lit && off.result.lit);
    const GiWindow& w = off.in.window;
    int lit_walls_on = 0, walls = 0;
    for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            const std::size_t i = (std::size_t(y) * std::size_t(w.width) + std::size_t(x)) * 3;
            const bool wall = off.in.walls.is_wall(int(std::floor(p.x)), int(std::floor(p.y)));
            for (int c = 0; c < 3; ++c) {
                if (wall) {
                    EXPECT_EQ(off.result.lit->rgb[i + std::size_t(c)], 0) << "wall texel " << x << ", " << y;
                } else {
                    EXPECT_EQ(off.result.lit->rgb[i + std::size_t(c)], on.result.lit->rgb[i + std::size_t(c)]);
                }
            }
            if (wall) {
                ++walls;
                lit_walls_on += on.result.lit->rgb[i] + on.result.lit->rgb[i + 1] + on.result.lit->rgb[i + 2] > 0;
            }
        }
    EXPECT_GT(walls, 0);
    EXPECT_GT(lit_walls_on, walls / 4) << "with wall lighting on, walls show their faces and tops";
}

TEST(WallOptions, CulledFacesAreNeitherComputedNorStored) {
    const scene::Scene base = walled_scene();
    const FrameRun all = run(base);
    const char* suffix[4] = {"px", "nx", "pz", "nz"};
    for (int face = 0; face < 4; ++face) {
        scene::Scene s = base;
        ASSERT_TRUE(scene::apply_override(s, std::string("gi.wall_faces.") + suffix[face] + "=false"));
        const FrameRun culled = run(s);
        EXPECT_EQ(computed_faces(culled.in.settings), 15u & ~(1u << face));
        for (const auto& [name, texture] : all.result.textures) {
            const bool this_face = is_face_texture(name) && name.ends_with(suffix[face]);
            if (this_face) {
                EXPECT_EQ(culled.result.textures.count(name), 0u) << name << " stored";
                continue;
            }
            ASSERT_EQ(culled.result.textures.count(name), 1u) << name;
            EXPECT_TRUE(same(texture, culled.result.textures.at(name))) << name << " changed with -" << suffix[face];
        }
        const TexSet written = textures_written(culled.in, culled.plan);
        EXPECT_FALSE(written.has(Tex(int(Tex::wall_direct_px) + face)));
        EXPECT_FALSE(written.has(Tex(int(Tex::wall_indirect_px) + face)));
    }
    // Every face culled: the face pass goes too.
    scene::Scene none = base;
    none.gi.wall_faces = {false, false, false, false};
    const FrameRun bare = run(none);
    EXPECT_EQ(bare.plan.reason[int(Pass::wall_indirect)], "no wall face computed");
}

// A face lit the same along its length: with gi.ao.walls its light is multiplied by the AO of
// the ground texel just outside it, darker in an inner corner than along the open wall.
TEST(WallOptions, AoOnWallFacesTakesTheGroundTexelOutside) {
    std::vector<std::string> rows(16, std::string(16, '.'));
    for (int x = 3; x < 13; ++x) rows[8][std::size_t(x)] = '#'; // a wall along x ...
    for (int z = 4; z < 8; ++z) rows[std::size_t(z)][3] = '#';  // ... and one meeting it at x = 3
    scene::Scene s = gi_test::open_scene({8.0f, 8.0f}, {16.0f, 16.0f}, 4);
    s.walls = gi_test::grid_from_rows(rows);
    s.gi.ao.strength = 1.0f;
    s.point_lights.push_back(gi_test::point({8.0f, 2.0f}, {1, 1, 1}, 1.0f, 12.0f));
    const FrameRun plain = run(s);
    s.gi.ao.walls = true;
    const FrameRun with_ao = run(s);
    ASSERT_TRUE(plain.result.lit && with_ao.result.lit);
    EXPECT_NE(plain.result.lit->rgb, with_ao.result.lit->rgb) << "the lit image shows the faces' AO";

    auto inputs = [](const FrameRun& r) {
        ShadingInputs si;
        si.frame = &r.in;
        auto find = [&](const char* name) { auto it = r.result.textures.find(name); return it == r.result.textures.end() ? nullptr : &it->second; };
        si.direct = find("direct");
        si.indirect = find("indirect");
        si.ao = find("ao");
        si.shadow = find("shadow");
        const char* faces[4] = {"px", "nx", "pz", "nz"};
        for (int f = 0; f < 4; ++f) {
            si.wall_direct[std::size_t(f)] = find((std::string("wall_direct_") + faces[f]).c_str());
            si.wall_indirect[std::size_t(f)] = find((std::string("wall_indirect_") + faces[f]).c_str());
        }
        return si;
    };
    const ShadingInputs a = inputs(plain), b = inputs(with_ao);
    ASSERT_TRUE(b.ao);
    const Texture& ao = *b.ao;
    // The -z face of the wall along x (the plane z = 8), seen from the light's side.
    const glm::vec3 n(0.0f, 0.0f, -1.0f);
    float corner = 0.0f, open = 0.0f;
    for (float x : {4.1f, 5.5f, 8.5f, 10.3f}) {
        const glm::vec3 pos(x, 0.5f, 8.0f);
        const glm::vec3 light = surface_light(a, pos, n), darkened = surface_light(b, pos, n);
        ASSERT_GT(light.r, 0.0f) << x;
        const int tx = int(std::floor(x * 4.0f)), tz = 8 * 4 - 1; // the ground texel outside
        const float expected = ao.at(tx, tz)[0];
        EXPECT_NEAR(darkened.r, light.r * expected, 1e-6f * light.r) << "x = " << x;
        EXPECT_LT(expected, 1.0f) << "the wall itself occludes its foot";
        if (x < 5.0f) corner = expected;
        if (x > 10.0f) open = expected;
    }
    EXPECT_LT(corner, open) << "an inner corner is darker than the open wall";
    // Ground and wall tops do not change.
    EXPECT_EQ(surface_light(a, {8.5f, 0.0f, 4.5f}, {0, 1, 0}), surface_light(b, {8.5f, 0.0f, 4.5f}, {0, 1, 0}));
}
