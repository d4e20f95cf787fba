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

#include <cstdio>
#include <optional>
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
    auto window = compute_window(s.view, s.gi);
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
    s.gi.probe_rays = 0; // the live probes read every face (tests/gi/probes_test.cpp)
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

// gi.window_snap "texel": the window steps by texels, so each step changes the light at a
// fixed place in the view less than a whole-tile step does: heat light near the window's
// edges "swims" as the edges jump. Measured on the indirect light over the visible texels
// (the view before padding) as the view moves one tile along x. With the edges on screen
// (padding 1) a texel step changes the light a quarter as much; with the game's padding
// the edges are off screen and neither mode changes the visible light beyond half-float
// rounding (docs/gi.md, "The window").
TEST(WindowSnap, TexelStepsChangeTheVisibleLightLessThanTileSteps) {
    struct Steps {
        int count = 0;
        float largest = 0.0f, mean = 0.0f;
    };
    auto measure = [](scene::WindowSnap snap, float padding) {
        scene::Scene s = gi_test::comparison_scene("rooms").scene;
        s.gi.window_snap = snap;
        s.gi.padding = padding;
        std::optional<FrameRun> last;
        Steps steps;
        double sum = 0.0;
        std::size_t n = 0;
        const scene::OrthoView start = std::get<scene::OrthoView>(s.view);
        for (int i = 0; i <= 8; ++i) {
            scene::OrthoView& view = std::get<scene::OrthoView>(s.view);
            view.center = start.center + glm::vec2(0.125f * float(i), 0.0f);
            FrameRun now = run(s);
            if (last && !(last->in.window == now.in.window)) {
                ++steps.count;
                const Texture& a = last->result.textures.at("indirect");
                const Texture& b = now.result.textures.at("indirect");
                const GiWindow& w = now.in.window;
                const glm::ivec2 shift = window_texel_origin(w) - window_texel_origin(last->in.window);
                for (int y = 0; y < b.height; ++y)
                    for (int x = 0; x < b.width; ++x) {
                        const glm::vec2 p = w.texel_center(x, y);
                        if (glm::any(glm::lessThan(p, view.center - view.size * 0.5f)) ||
                            glm::any(glm::greaterThan(p, view.center + view.size * 0.5f)))
                            continue; // not visible
                        const glm::ivec2 q = glm::ivec2(x, y) + shift; // the same place, last window
                        if (q.x < 0 || q.y < 0 || q.x >= a.width || q.y >= a.height) continue;
                        for (int c = 0; c < 3; ++c) {
                            const float d = std::abs(a.at(q.x, q.y)[c] - b.at(x, y)[c]);
                            steps.largest = std::max(steps.largest, d);
                            sum += d;
                            ++n;
                        }
                    }
            }
            last = std::move(now);
        }
        steps.mean = n ? float(sum / double(n)) : 0.0f;
        return steps;
    };
    for (float padding : {1.0f, 1.5f}) {
        const Steps tile = measure(scene::WindowSnap::tile, padding);
        const Steps texel = measure(scene::WindowSnap::texel, padding);
        std::printf("padding %.1f: change of the visible indirect light in one window step: whole tiles %d steps, "
                    "largest %.4f, mean %.5f; texels %d steps, largest %.4f, mean %.5f\n",
                    double(padding), tile.count, double(tile.largest), double(tile.mean), texel.count,
                    double(texel.largest), double(texel.mean));
        EXPECT_EQ(tile.count, 1);
        EXPECT_EQ(texel.count, 4);
        if (padding == 1.0f) {
            EXPECT_GT(tile.mean, 0.0f);
            EXPECT_LT(texel.mean, 0.5f * tile.mean) << "texel steps swim less";
        } else {
            EXPECT_LT(tile.largest, 1e-3f) << "the padding hides the edges";
            EXPECT_LT(texel.largest, 1e-3f);
        }
    }
}

// gi.proxy_wall_shadows = unfold: a hard-edged proxy's shadow, 4.5 tiles long, meets a wall
// 3 tiles behind the proxy; folded up the wall, it covers the face's lower 1.5 tiles and
// the face above is lit as if the proxy were not there. "full" shades the face top to bottom.
TEST(WallOptions, UnfoldedProxyShadowsReachUpTheWallAsFarAsTheirLength) {
    std::vector<std::string> rows(16, std::string(16, '.'));
    for (int x = 2; x < 14; ++x) rows[10][std::size_t(x)] = '#'; // the -z face is the plane z = 10
    scene::Scene s = gi_test::open_scene({8.0f, 8.0f}, {16.0f, 16.0f}, 4);
    s.walls = gi_test::grid_from_rows(rows);
    s.wall_height = 2.5f;
    s.point_lights.push_back(gi_test::point({8.125f, 2.0f}, {1, 1, 1}, 1.0f, 12.0f));
    const FrameRun open_run = run(s); // no proxy: the light the face gets unshadowed
    scene::ShadowProxy post;
    post.position = {8.125f, 7.0f};
    post.size = {0.4f, 0.4f};
    post.max_length = 4.5f;
    post.penumbra_width = 0.0f;
    post.penumbra_length = 0.0f;
    s.shadow_proxies.push_back(post);
    const FrameRun full = run(s);
    s.gi.proxy_wall_shadows = scene::ProxyWallShadows::unfold;
    const FrameRun unfolded = run(s);

    EXPECT_EQ(full.result.textures.count("wall_upper_nz"), 0u) << "full: no upper textures";
    ASSERT_EQ(unfolded.result.textures.count("wall_upper_nz"), 1u);
    const Texture& open_face = open_run.result.textures.at("wall_direct_nz");
    const Texture& full_face = full.result.textures.at("wall_direct_nz");
    const Texture& low = unfolded.result.textures.at("wall_direct_nz");
    const Texture& upper = unfolded.result.textures.at("wall_upper_nz");
    const int x = 32, z = 40; // texel centre (8.125, 10.125), in the wall, behind the proxy
    ASSERT_GT(open_face.at(x, z)[0], 0.0f);
    EXPECT_EQ(full_face.at(x, z)[0], 0.0f) << "full: the face is shadowed top to bottom";
    EXPECT_EQ(low.at(x, z)[0], 0.0f) << "unfold: the face's foot is in the shadow";
    EXPECT_EQ(upper.at(x, z)[0], open_face.at(x, z)[0]) << "unfold: the top is lit as without the proxy";
    // The shadow's remaining length: 4.5 - (10 - 7) = 1.5 tiles up the wall (half-float edge).
    EXPECT_NEAR(upper.at(x, z)[3], 1.5f, 2e-3f);
    // Far from the shadow the upper light equals the foot's and no edge is stored.
    EXPECT_EQ(upper.at(4, z)[0], low.at(4, z)[0]);
    EXPECT_EQ(upper.at(4, z)[3], 0.0f);

    // Shading: below the edge the face shows the foot's light, above it the top's.
    ShadingInputs si;
    si.frame = &unfolded.in;
    si.wall_direct[face_neg_z] = &low;
    si.wall_upper[face_neg_z] = &upper;
    const glm::vec3 n(0.0f, 0.0f, -1.0f);
    EXPECT_EQ(surface_light(si, {8.125f, 1.0f, 10.0f}, n).r, 0.0f);
    EXPECT_EQ(surface_light(si, {8.125f, 2.0f, 10.0f}, n).r, open_face.at(x, z)[0]);
    // Every other texture is what "full" gave.
    for (const auto& [name, texture] : full.result.textures)
        if (name != "lit") {
            ASSERT_EQ(unfolded.result.textures.count(name), 1u) << name;
            EXPECT_TRUE(same(texture, unfolded.result.textures.at(name))) << name << " changed";
        }
}
