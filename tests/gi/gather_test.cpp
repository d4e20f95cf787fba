// The gather method (gi.method = gather, physical): its ground gather against an independent
// quadrature in front of a lit wall, Vulkan against the C++ reference texel by texel (one
// frame and several frames of bounces, every comparison scene and both real maps), a sealed
// room that keeps its light in, albedo 0 giving no indirect light, energy in a closed room
// bounded by the geometric series, and a still scene that stops.
#include "gi_compare.hpp"
#include "test_scenes.hpp"

#include "gpu_test_support.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/gather.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "shared_renderer.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace lantern::gi;
using gi_test::grid_from_rows;
using gi_test::inputs_of;
using gi_test::NamedScene;
using lantern::scene::HeatScale;
using lantern::scene::Scene;

namespace {

Scene as_gather(Scene s, HeatScale scale = HeatScale::full) {
    s.gi.method = lantern::scene::GiMethod::gather;
    s.gi.gather.scale = scale;
    return s;
}


// Frames of a still scene on the reference with the history the frame systems keep.
ReferenceStore run_frames(const FrameInputs& in, int frames) {
    Convergence convergence;
    ReferenceStore store;
    for (int f = 0; f < frames; ++f) {
        PassPlan plan = plan_passes(in, false);
        derive_keys(in, plan, input_keys_of(in), &convergence);
        execute_reference(in, plan, plan.run, {}, store);
        convergence.advance(plan.run);
    }
    return store;
}

glm::vec3 texel(const Texture& t, int x, int y) {
    const float* v = t.at(x, y);
    return {v[0], v[1], v[2]};
}

} // namespace

// One wall (a row of tiles) lit by a point light in front of it, nothing else to bounce
// from: the indirect fluence at a ground point q is the integral over the wall's face of
// radiance albedo x E(x) / 2 times the angle the face element subtends at q,
// cos(theta_face) / distance dx. E(x) is Lantern's own face light (wall_direct_pz), so this
// checks the gather's geometry and normalisation alone.
TEST(GatherReference, GroundGatherMatchesAQuadratureInFrontOfALitWall) {
    Scene s = as_gather(gi_test::open_scene({16, 12}, {32, 24}, 2));
    std::vector<std::string> rows(24, std::string(32, '.'));
    for (int x = 0; x < 32; ++x) rows[6][std::size_t(x)] = '#'; // its ends out of the light's reach
    s.walls = grid_from_rows(rows);
    s.point_lights = {{{16.0f, 10.0f}, 1.0f, {1.0f, 1.0f, 1.0f}, 2.0f, 14.0f}};
    s.gi.gather.rays = 1024;
    s.gi.gather.bounces = 1;
    s.gi.blur = false;
    s.gi.wall_albedo = 0.5f;
    const FrameInputs in = inputs_of(s);
    const ReferenceStore store = run_frames(in, 1);
    const Texture& face = store.at(Tex::wall_direct_pz);
    const Texture& indirect = store.at(Tex::indirect);
    const GiWindow& w = in.window;
    const int res = w.resolution;
    // The +Z face of the wall row z = 6 lies on z = 7; its texels along x are the wall
    // texels of row z = 7 - 1 / res.
    const int face_row = int(std::floor((7.0f - 0.5f / float(res) - w.view.min_z) * float(res)));
    int checked = 0;
    double worst = 0.0;
    // Fluence at a point from the lit face: albedo x E / 2 times the angle each of 32 points per
    // face texel subtends, cos(theta_face) / distance dx.
    auto quadrature = [&](glm::vec2 q) {
        glm::vec3 sum(0.0f);
        for (int x = 0; x < w.width; ++x) {
            const int tile = int(std::floor(w.texel_center(x, face_row).x));
            if (tile < 0 || tile >= 32) continue;
            for (int k = 0; k < 32; ++k) {
                const glm::vec2 p(w.view.min_x + (float(x) + (float(k) + 0.5f) / 32.0f) / float(res), 7.0f);
                const glm::vec2 d = q - p;
                sum += 0.5f * texel(face, x, face_row) / 2.0f * (d.y / glm::dot(d, d)) / (32.0f * float(res));
            }
        }
        return sum;
    };
    for (glm::vec2 q : {glm::vec2(16.1f, 9.1f), glm::vec2(10.3f, 12.2f), glm::vec2(22.6f, 8.3f),
                        glm::vec2(16.4f, 16.7f), glm::vec2(5.2f, 7.6f)}) {
        const int tx = int(std::floor((q.x - w.view.min_x) * float(res))),
                  ty = int(std::floor((q.y - w.view.min_z) * float(res)));
        const glm::vec3 got = texel(indirect, tx, ty);
        const glm::vec3 expected = quadrature(w.texel_center(tx, ty)); // the gather's point: the texel centre
        const double rel = std::abs(double(got.g) - double(expected.g)) / double(expected.g);
        std::printf("q (%.1f, %.1f): gather %.5f, quadrature %.5f (%.2f %%)\n", q.x, q.y, got.g, expected.g,
                    100.0 * rel);
        worst = std::max(worst, rel);
        ++checked;
    }
    EXPECT_EQ(checked, 5);
    EXPECT_LT(worst, 0.03) << "1024 rays: the ray pattern's error is well below 3 %";
}

// Coloured bounce (seed 004's materials): a white wall meeting red rock at a corner, lit
// by a white light, takes the rock's red from its bounce light; with the rock white too the
// same face's indirect light stays white. A glowing wall lights a room with no light.
TEST(GatherReference, AWhiteWallBesideRedRockTurnsPink) {
    std::vector<std::string> rows(16, std::string(16, '.'));
    for (int x = 2; x < 14; ++x) rows[4][std::size_t(x)] = '#'; // white, its +Z face on z = 5
    for (int z = 5; z < 13; ++z) rows[std::size_t(z)][2] = '#'; // red rock, its +X face on x = 3
    auto face_light = [&](glm::vec3 rock) {
        Scene s = as_gather(gi_test::open_scene({8, 8}, {16, 16}, 4));
        s.walls = grid_from_rows(rows);
        s.materials = {{"white", {0.9f, 0.9f, 0.9f}, {}}, {"rock", rock, {}}};
        for (int x = 2; x < 14; ++x) s.walls.cells[std::size_t(4 * 16 + x)] = lantern::scene::material_cell(0);
        for (int z = 5; z < 13; ++z) s.walls.cells[std::size_t(z * 16 + 2)] = lantern::scene::material_cell(1);
        s.point_lights = {{{8.5f, 9.5f}, 1.0f, {1.0f, 1.0f, 1.0f}, 2.0f, 12.0f}};
        const FrameInputs in = inputs_of(s);
        const ReferenceStore store = run_frames(in, 4);
        // The white wall's +Z face one tile from the corner: wall tile (3, 4), its top texel row.
        const GiWindow& w = in.window;
        const int x = int((3.5f - w.view.min_x) * 4.0f), y = int((5.0f - 0.125f - w.view.min_z) * 4.0f);
        return std::pair{texel(store.at(Tex::wall_direct_pz), x, y), texel(store.at(Tex::wall_indirect_pz), x, y)};
    };
    const auto [direct, indirect] = face_light({0.8f, 0.1f, 0.1f});
    std::printf("white face by red rock: direct (%.4f %.4f %.4f), indirect (%.4f %.4f %.4f)\n", direct.r, direct.g,
                direct.b, indirect.r, indirect.g, indirect.b);
    EXPECT_EQ(direct.r, direct.g) << "a white light";
    EXPECT_GT(indirect.r, 2.0f * indirect.g) << "the rock's bounce is red";
    EXPECT_NEAR(indirect.g, indirect.b, 1e-6f * indirect.g);
    const glm::vec3 total = direct + indirect;
    EXPECT_GT(total.r, 1.1f * total.g) << "pink: more red than green and blue, which stay equal";
    const auto [direct_w, indirect_w] = face_light({0.9f, 0.9f, 0.9f});
    EXPECT_EQ(indirect_w.r, indirect_w.g) << "white rock: no tint";
    EXPECT_GT(indirect_w.g, indirect.g) << "white rock reflects more green than red rock";
}

// Seed 004's albedo boost: every wall albedo a becomes a^(1 / boost), materials' and the
// default's; boost 1 leaves them bit for bit.
TEST(GatherReference, AlbedoBoostRaisesEveryWallAlbedo) {
    Scene s = as_gather(gi_test::comparison_scene("rooms").scene);
    s.materials[0].albedo = {0.25f, 0.64f, 0.01f};
    s.gi.wall_albedo = 0.36f;
    FrameInputs in = inputs_of(s);
    EXPECT_EQ(glm::vec3(material_of(in, lantern::scene::material_cell(0)).albedo), s.materials[0].albedo);
    in.settings.albedo_boost = 2.0f;
    EXPECT_EQ(glm::vec3(material_of(in, lantern::scene::material_cell(0)).albedo), glm::vec3(0.5f, 0.8f, 0.1f));
    EXPECT_FLOAT_EQ(material_of(in, lantern::scene::default_wall_cell).albedo.g, 0.6f);
    EXPECT_EQ(material_of(in, lantern::scene::material_cell(2)).emission, in.materials[2].emission) << "emission unchanged";
}

TEST(GatherReference, AGlowingWallLightsARoomWithoutLights) {
    std::vector<std::string> rows(12, std::string(12, '#'));
    for (int z = 3; z < 9; ++z) rows[std::size_t(z)].replace(3, 6, "......");
    Scene s = as_gather(gi_test::open_scene({6, 6}, {12, 12}, 4));
    s.walls = grid_from_rows(rows);
    s.materials = {{"lava", {0.0f, 0.0f, 0.0f}, {2.0f, 0.5f, 0.0f}}};
    for (int x = 3; x < 9; ++x) s.walls.cells[std::size_t(2 * 12 + x)] = lantern::scene::material_cell(0);
    s.gi.wall_albedo = 0.0f; // only the lava's own light, no bounce
    s.gi.gather.rays = 1024;
    s.gi.blur = false;
    const FrameInputs in = inputs_of(s);
    ASSERT_TRUE(has_emissive_materials(in));
    const ReferenceStore store = run_frames(in, 1);
    const Texture& indirect = store.at(Tex::indirect);
    const GiWindow& w = in.window;
    // Near the room's centre: lit by the 6-tile glowing face on z = 3 (x 3..9), in the lava's
    // colour. Fluence from a face of constant radiosity B: B / 2 x the angle it subtends.
    const int tx = int((6.0f - w.view.min_x) * 4.0f), ty = int((6.0f - w.view.min_z) * 4.0f);
    const glm::vec2 q = w.texel_center(tx, ty);
    const glm::vec3 c = texel(indirect, tx, ty);
    EXPECT_NEAR(c.g / c.r, 0.25f, 1e-4f);
    EXPECT_EQ(c.b, 0.0f);
    const float angle = std::atan((9.0f - q.x) / (q.y - 3.0f)) + std::atan((q.x - 3.0f) / (q.y - 3.0f));
    const float expected = 2.0f / 2.0f * angle;
    std::printf("fluence %.4f, expected %.4f\n", c.r, expected);
    EXPECT_NEAR(c.r, expected, 0.01f * expected);
}

namespace {

class Gather : public lantern::test::GpuTest {
  protected:
    // `frames` frames of a still scene on both backends (the history the frame systems
    // keep); every texture of the last one equal (gi_compare.hpp).
    void compare_frames(const NamedScene& named, int frames = 1) {
        const FrameInputs in = inputs_of(named.scene);
        Convergence convergence;
        ReferenceStore store;
        vk::Renderer& renderer = gi_test::shared_renderer(device());
        FrameResult gpu_frame;
        for (int f = 0; f < frames; ++f) {
            PassPlan plan = plan_passes(in, true);
            derive_keys(in, plan, input_keys_of(in), &convergence);
            execute_reference(in, plan, plan.run, {}, store);
            auto gpu = run_vulkan_frame(renderer, in, plan);
            ASSERT_TRUE(gpu.ok()) << gpu.error().message;
            gpu_frame = std::move(gpu.value());
            convergence.advance(plan.run);
        }
        ASSERT_TRUE(store.find(Tex::gather_ground)) << named.name;
        int compared = 0;
        for (int t = 0; t < registered_texture_count(); ++t) {
            const Texture* reference = store.find(Tex(t));
            if (!reference || texture_row(Tex(t)).internal) continue;
            const std::string name = tex_name(Tex(t));
            auto it = gpu_frame.textures.find(name);
            ASSERT_NE(it, gpu_frame.textures.end()) << named.name << ": GPU did not produce " << name;
            // Sums of many rays: the GPU may fuse a multiply-add the reference rounds twice.
            const float ulps = (name == "indirect" || name == "gather_ground" || name.rfind("wall_indirect", 0) == 0)
                                   ? 4.0f
                                   : 2.0f;
            auto diff = gi_test::compare_textures(it->second, *reference, ulps);
            EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe(named.name + " " + name, diff);
            ++compared;
        }
        EXPECT_GT(compared, 5);
    }
};

class GatherScenes : public Gather, public ::testing::WithParamInterface<std::string> {};

} // namespace

TEST_P(GatherScenes, OneFrameMatchesTheReference) {
    NamedScene named = gi_test::comparison_scene(GetParam());
    named.scene = as_gather(named.scene, HeatScale::half);
    compare_frames(named);
}

INSTANTIATE_TEST_SUITE_P(Scenes, GatherScenes, ::testing::ValuesIn(gi_test::comparison_scene_names()),
                         [](const auto& p) { return p.param; });

// Bounces across frames (the face textures ping-pong and carry over), every setting changed.
TEST_F(Gather, FramesOfBouncesAndEverySettingMatchTheReference) {
    const Scene base = as_gather(gi_test::comparison_scene("rooms").scene);
    struct Case {
        const char* name;
        void (*apply)(Scene&);
    };
    const Case cases[] = {
        {"defaults", [](Scene&) {}},
        {"quarter grid, 3 rays, 5 face rays, 3 bounces",
         [](Scene& s) {
             s.gi.gather.scale = HeatScale::quarter, s.gi.gather.rays = 3, s.gi.gather.face_rays = 5,
             s.gi.gather.bounces = 3;
         }},
        {"albedo 0.9, margin 0, no blur",
         [](Scene& s) { s.gi.wall_albedo = 0.9f, s.gi.gather.margin = 0, s.gi.blur = false; }},
        {"texel snap, resolution 3",
         [](Scene& s) { s.gi.window_snap = lantern::scene::WindowSnap::texel, s.gi.resolution = 3; }},
        {"two faces computed", [](Scene& s) { s.gi.wall_faces.px = false, s.gi.wall_faces.nz = false; }},
        {"no materials", [](Scene& s) {
             s.materials.clear();
             for (auto& c : s.walls.cells) c = c != 0 ? 1 : 0;
         }},
    };
    for (const Case& c : cases) {
        Scene s = base;
        c.apply(s);
        compare_frames({c.name, s}, 3);
    }
}

TEST_F(Gather, RealMapsMatchTheReference) {
    for (auto [file, center, seed] : {std::tuple{"den312d.map", glm::vec2(32.0f, 40.0f), 1u},
                                      std::tuple{"lak303d.map", glm::vec2(100.0f, 100.0f), 2u}}) {
        auto s = gi_test::map_scene(file, center, seed);
        if (!s) GTEST_SKIP() << "../shared is absent";
        s->scene = as_gather(s->scene, HeatScale::half);
        compare_frames(*s, 2);
    }
}
