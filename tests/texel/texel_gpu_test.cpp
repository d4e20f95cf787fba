// The texel passes on Vulkan (lavapipe in CI) against the C++ reference, texel by texel.
#include "lantern/texel/pass_table.hpp"
#include "lantern/texel/texel.hpp"
#include "lantern/texel/vulkan/texel_passes.hpp"

#include "gpu_test_support.hpp"
#include "lantern/gpu/command_list.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace lantern::texel {
namespace {

// A small world: a room with a pillar, a "player" (body and head in one texture), trees,
// a crate with a random normal map and a model of random triangles.
struct World {
    scene::WallGrid grid;
    Model player, tree, crate, shards;
    std::vector<Placement> placements;
    TexelScene scene;

    // `player_moves`: the player is a placement that moves (Placement::moves).
    explicit World(bool player_moves = false) {
        grid.width = 16;
        grid.height = 12;
        grid.origin = glm::ivec2(-2, -2);
        grid.cells.assign(std::size_t(grid.width) * grid.height, 0);
        const auto wall = [&](int x, int z) { grid.cells[std::size_t(x - grid.origin.x) + std::size_t(z - grid.origin.y) * grid.width] = 1; };
        for (int x = -2; x < 14; ++x) wall(x, -2), wall(x, 9);
        for (int z = -2; z < 10; ++z) wall(-2, z), wall(13, z);
        wall(5, 3), wall(5, 4), wall(6, 4);

        const Model body = box_model(glm::vec3(-0.3f, 0.0f, -0.2f), glm::vec3(0.3f, 1.0f, 0.2f), 8);
        const Model head = box_model(glm::vec3(-0.2f, 1.0f, -0.2f), glm::vec3(0.2f, 1.4f, 0.2f), 8);
        // Two textures side by side, each texel for texel: twice the larger one's size.
        player.size = 2 * std::max(body.size, head.size);
        append_triangles(player, body, glm::mat4(1.0f), glm::vec2(0.0f), glm::vec2(0.5f));
        append_triangles(player, head, glm::mat4(1.0f), glm::vec2(0.5f, 0.0f), glm::vec2(0.5f));
        tree = box_model(glm::vec3(-0.15f, 0.0f, -0.15f), glm::vec3(0.15f, 0.8f, 0.15f), 8);
        const Model crown = box_model(glm::vec3(-0.6f, 0.8f, -0.6f), glm::vec3(0.6f, 1.8f, 0.6f), 8);
        Model tree_all;
        tree_all.size = 2 * std::max(tree.size, crown.size);
        append_triangles(tree_all, tree, glm::mat4(1.0f), glm::vec2(0.0f), glm::vec2(0.5f));
        append_triangles(tree_all, crown, glm::mat4(1.0f), glm::vec2(0.5f, 0.0f), glm::vec2(0.5f));
        tree = tree_all;
        crate = box_model(glm::vec3(-0.4f, 0.0f, -0.4f), glm::vec3(0.4f, 0.8f, 0.4f), 8);
        std::mt19937 rng(5);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        // Draws in sequence (the order of a call's arguments is the compiler's: GCC and clang
        // would build different scenes).
        const auto draw = [&](std::uniform_real_distribution<float>& d) {
            const float x = d(rng), y = d(rng), z = d(rng);
            return glm::vec3(x, y, z);
        };
        for (int i = 0; i < crate.size * crate.size; ++i)
            crate.normal_map.emplace_back(glm::vec3(0.3f, 0.3f, 0.8f) + glm::vec3(0.4f, 0.4f, 0.2f) * draw(unit), 0.0f);
        shards.size = 24;
        std::uniform_real_distribution<float> uv(0.0f, 1.0f), pos(-0.5f, 0.5f);
        for (int i = 0; i < 6; ++i) {
            ModelTriangle t;
            for (int k = 0; k < 3; ++k) {
                t.uv[k] = glm::vec2(draw(uv));
                t.p[k] = draw(pos) + glm::vec3(0.0f, 0.6f, 0.0f);
            }
            shards.triangles.push_back(t);
        }
        const auto at = [](float x, float z, float turn = 0.0f) {
            return glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, z)), turn, glm::vec3(0, 1, 0));
        };
        placements = {{&player, at(3.5f, 3.5f, 0.3f)}, {&tree, at(8.5f, 2.5f)}, {&tree, at(9.5f, 6.5f, 1.0f)},
                      {&crate, at(2.5f, 6.5f)},         {&shards, at(7.0f, 5.0f)}};
        placements[0].moves = player_moves;
        scene = build_scene(placements, gi::WallView::of(grid), 2.0f, 10.0f);
    }
};

std::vector<TexelLight> live_lights() {
    return {make_light({4.5f, 1.2f, 5.5f}, {1.0f, 0.7f, 0.4f}, 1.5f, 8.0f, ShadowType::hard),
            make_light({7.5f, 1.5f, 3.5f}, {0.4f, 0.6f, 1.0f}, 1.0f, 7.0f, ShadowType::blurred, 1.0f, 1.0f, {0.05f, 0.0f, 0.1f}),
            make_light({1.0f, 0.8f, 1.0f}, {0.9f, 0.9f, 0.9f}, 1.0f, 12.0f, ShadowType::blurred, 1.5f, 2.0f),
            make_light({11.0f, 3.0f, 7.0f}, {0.3f, 1.0f, 0.3f}, 2.0f, 9.0f, ShadowType::none, 1.0f, 1.0f, {0.0f, 0.05f, 0.0f}),
            make_sun({0.7f, -0.45f, 0.3f}, {0.5f, 0.45f, 0.4f}, 1.0f, ShadowType::hard, 30.0f, {0.02f, 0.02f, 0.03f})};
}
std::vector<TexelLight> static_lights() {
    return {make_light({6.0f, 6.0f, 4.0f}, {1.0f, 0.95f, 0.8f}, 1.0f, 14.0f, ShadowType::hard, 1.0f, 1.0f, {0.05f, 0.05f, 0.06f})};
}

// Relative 1e-5 (pow on the GPU is not correctly rounded; everything else is).
bool close(float a, float b) { return std::abs(a - b) <= 1e-5f * std::max(1.0f, std::abs(b)); }
bool close(glm::vec4 a, glm::vec4 b) { return close(a.x, b.x) && close(a.y, b.y) && close(a.z, b.z) && close(a.w, b.w); }

class TexelGpu : public test::GpuTest {
  protected:
    std::unique_ptr<vk::TexelPasses> passes;
    void SetUp() override {
        test::GpuTest::SetUp();
        if (IsSkipped()) return;
        auto created = vk::TexelPasses::create(device());
        ASSERT_TRUE(created.ok()) << created.error().message;
        passes = std::move(*created);
    }
    void TearDown() override {
        passes.reset();
        test::GpuTest::TearDown();
    }
    void expect_surfaces(const std::vector<TexelSurface>& gpu, const std::vector<TexelSurface>& ref) {
        ASSERT_EQ(gpu.size(), ref.size());
        int differ = 0, used = 0;
        for (std::size_t i = 0; i < ref.size(); ++i) {
            used += ref[i].position_used.w != 0.0f;
            const bool same = gpu[i].position_used.w == ref[i].position_used.w &&
                              gpu[i].normal_triangle.w == ref[i].normal_triangle.w &&
                              close(gpu[i].position_used, ref[i].position_used) &&
                              close(gpu[i].normal_triangle, ref[i].normal_triangle) && close(gpu[i].geo_normal, ref[i].geo_normal);
            if (!same && differ++ < 5)
                ADD_FAILURE() << "texel " << i << ": GPU used " << gpu[i].position_used.w << " triangle " << gpu[i].normal_triangle.w
                              << ", reference used " << ref[i].position_used.w << " triangle " << ref[i].normal_triangle.w;
        }
        EXPECT_EQ(differ, 0);
        EXPECT_GT(used, 1000);
    }
    int expect_light(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& ref, const char* what) {
        int differ = 0, lit = 0;
        for (std::size_t i = 0; i < ref.size(); ++i) {
            lit += ref[i].r + ref[i].g + ref[i].b > 0.0f;
            if (close(gpu[i], ref[i])) continue;
            if (differ++ < 5)
                ADD_FAILURE() << what << " texel " << i << ": GPU (" << gpu[i].r << ", " << gpu[i].g << ", " << gpu[i].b
                              << "), reference (" << ref[i].r << ", " << ref[i].g << ", " << ref[i].b << ")";
        }
        EXPECT_EQ(differ, 0) << what;
        return lit;
    }
    // Uploads `w`, bakes `baked_lights`, runs the realtime pass with `lights`, and checks both
    // results against the reference, texel by texel. Returns the reference's surfaces.
    std::vector<TexelSurface> bake_and_light(const World& w, const std::vector<TexelLight>& baked_lights,
                                             const std::vector<TexelLight>& lights) {
        gpu::CommandList cmd = device().begin("texel light");
        passes->upload_scene(cmd, w.scene);
        passes->record_uv_to_world(cmd);
        passes->record_light(cmd, baked_lights, vk::TexelPasses::Mode::bake);
        passes->record_light(cmd, lights, vk::TexelPasses::Mode::realtime);
        device().wait(device().submit(std::move(cmd)));
        const std::size_t n = w.scene.texel_count;
        std::vector<TexelSurface> surfaces = uv_to_world(w.scene);
        const auto ref_baked = reference_light(w.scene, surfaces, baked_lights);
        const auto ref_lit = reference_light(w.scene, surfaces, lights, ref_baked);
        auto gpu_baked = test::read_back_as<glm::vec4>(device(), passes->baked());
        auto gpu_lit = test::read_back_as<glm::vec4>(device(), passes->lit());
        gpu_baked.resize(n);
        gpu_lit.resize(n);
        EXPECT_GT(expect_light(gpu_baked, ref_baked, "baked"), 1000);
        EXPECT_GT(expect_light(gpu_lit, ref_lit, "realtime + baked"), 1000);
        return surfaces;
    }
};

TEST_F(TexelGpu, UvToWorldMatchesTheSeedsBruteForce) {
    World w;
    gpu::CommandList cmd = device().begin("texel uv to world");
    passes->upload_scene(cmd, w.scene);
    passes->record_uv_to_world(cmd);
    device().wait(device().submit(std::move(cmd)));
    const auto gpu = test::read_back_as<TexelSurface>(device(), passes->surfaces());
    std::vector<TexelSurface> got(gpu.begin(), gpu.begin() + w.scene.texel_count);
    expect_surfaces(got, uv_to_world_brute(w.scene));
}

TEST_F(TexelGpu, BakeAndRealtimeLightMatchTheReference) {
    World w;
    const std::vector<TexelLight> baked_lights = static_lights(), lights = live_lights();
    const std::vector<TexelSurface> surfaces = bake_and_light(w, baked_lights, lights);
    // The scene has what the comparison is for: texels in the walls' and the models' shadows.
    int wall_shadowed = 0, model_shadowed = 0, blurred = 0;
    for (const TexelSurface& s : surfaces) {
        if (s.position_used.w == 0.0f) continue;
        const glm::vec3 p(s.position_used);
        for (const TexelLight& l : lights) {
            if (is_directional(l)) continue;
            const glm::vec3 dir = p - glm::vec3(l.position_range);
            if (glm::length(dir) >= l.position_range.w || glm::dot(dir, glm::vec3(s.geo_normal)) >= 0.0f) continue;
            if (wall_visibility(w.scene.walls, w.scene.wall_height, glm::vec3(l.position_range), p) == 0.0f) {
                ++wall_shadowed;
                continue;
            }
            const float v = occluder_visibility(w.scene, l, glm::vec3(l.position_range), p, int(s.normal_triangle.w + 0.5f));
            model_shadowed += v == 0.0f;
            blurred += v > 0.0f && v < 1.0f;
        }
    }
    EXPECT_GT(wall_shadowed, 500);
    EXPECT_GT(model_shadowed, 20);
    EXPECT_GT(blurred, 150);
}

// Seed 001's static lights with a model that moves: the bake leaves the player out (as a
// receiver and as an occluder), the realtime pass adds the baked light to the player only.
TEST_F(TexelGpu, BakedLightsLeaveMovingModelsToTheRealtimePass) {
    World w(true);
    const std::vector<TexelLight> baked_lights = static_lights();
    std::vector<TexelLight> lights = live_lights();
    for (const TexelLight& l : baked_lights) lights.push_back(as_baked(l));
    const std::vector<TexelSurface> surfaces = bake_and_light(w, baked_lights, lights);
    const auto gpu_baked = test::read_back_as<glm::vec4>(device(), passes->baked());
    const auto gpu_lit = test::read_back_as<glm::vec4>(device(), passes->lit());
    // The player's texels have no bake and are lit all the same.
    const GpuPlacement& player = w.scene.placements[0];
    int player_lit = 0;
    for (std::uint32_t i = player.ranges.z; i < player.ranges.z + player.ranges.w * player.ranges.w; ++i) {
        if (surfaces[i].position_used.w == 0.0f) continue;
        EXPECT_EQ(gpu_baked[i], glm::vec4(0.0f)) << "texel " << i;
        player_lit += gpu_lit[i].r + gpu_lit[i].g + gpu_lit[i].b > 0.0f;
    }
    EXPECT_GT(player_lit, 100);
}

TEST_F(TexelGpu, AMovedPlacementIsCarriedAgain) {
    World w;
    const std::vector<TexelLight> lights = live_lights();
    gpu::CommandList cmd = device().begin("texel scene");
    passes->upload_scene(cmd, w.scene);
    passes->record_uv_to_world(cmd);
    device().wait(device().submit(std::move(cmd)));
    // The player walks and turns.
    move_placement(w.scene, 0, w.player,
                   glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(4.2f, 0.0f, 5.0f)), 2.0f, glm::vec3(0, 1, 0)));
    cmd = device().begin("texel move");
    passes->upload_triangles(cmd, w.scene);
    passes->record_uv_to_world(cmd);
    passes->record_light(cmd, lights, vk::TexelPasses::Mode::realtime);
    device().wait(device().submit(std::move(cmd)));
    const auto surfaces = uv_to_world(w.scene);
    auto gpu = test::read_back_as<TexelSurface>(device(), passes->surfaces());
    gpu.resize(w.scene.texel_count);
    expect_surfaces(gpu, surfaces);
    auto gpu_lit = test::read_back_as<glm::vec4>(device(), passes->lit());
    gpu_lit.resize(w.scene.texel_count);
    // Nothing baked: the realtime light alone, saturated.
    const std::vector<glm::vec4> zero(w.scene.texel_count, glm::vec4(0.0f));
    expect_light(gpu_lit, reference_light(w.scene, surfaces, lights, zero), "after the move");
}

// The pass table's frames (pass_table.hpp) recorded on Vulkan equal the reference backend's,
// frame after frame: the player walks (its texels only), a light flickers, the static lamp
// dims (a bake), a tree is replanted, a wall mined. Every frame's light is compared.
TEST_F(TexelGpu, PlannedFramesEqualTheReferenceBackend) {
    World w(true);
    std::vector<TexelLight> lights = live_lights();
    for (const TexelLight& l : static_lights()) lights.push_back(as_baked(l));
    TexelHistory history;
    TexelReferenceStore store;
    const auto frame = [&](const char* what) {
        const TexelFrame f{w.scene, lights};
        const TexelPlan plan = plan_texel_frame(f, history);
        gpu::CommandList cmd = device().begin("texel plan");
        passes->record_plan(cmd, f, plan);
        device().wait(device().submit(std::move(cmd)));
        execute_reference(f, plan, store);
        auto gpu_lit = test::read_back_as<glm::vec4>(device(), passes->lit());
        gpu_lit.resize(w.scene.texel_count);
        EXPECT_GT(expect_light(gpu_lit, store.lit, what), 1000);
        return plan;
    };
    frame("the first frame");
    const auto move = [&](std::uint32_t k, const Model& m, glm::mat4 to) {
        w.placements[k].transform = to;
        move_placement(w.scene, k, m, to);
    };
    move(0, w.player, glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(4.2f, 0.0f, 5.0f)), 2.0f, glm::vec3(0, 1, 0)));
    EXPECT_EQ(frame("the player walked").moved, std::vector<std::uint32_t>{0u});
    lights[0].color_type *= 0.8f;
    EXPECT_FALSE(frame("a light flickered").runs(TexelPass::bake));
    lights.back().color_type *= 0.5f;
    EXPECT_TRUE(frame("the static lamp dimmed").runs(TexelPass::bake));
    move(1, w.tree, glm::translate(glm::mat4(1.0f), glm::vec3(8.0f, 0.0f, 3.0f)));
    const TexelPlan replanted = frame("a tree replanted");
    EXPECT_EQ(replanted.moved, std::vector<std::uint32_t>{1u});
    EXPECT_TRUE(replanted.runs(TexelPass::bake));
    w.grid.cells[std::size_t(5 - w.grid.origin.x) + std::size_t(4 - w.grid.origin.y) * w.grid.width] = 0;
    w.scene = build_scene(w.placements, gi::WallView::of(w.grid), 2.0f, 10.0f);
    EXPECT_TRUE(frame("a wall mined").upload_walls);
}

} // namespace
} // namespace lantern::texel
