// The game's per-texel lit models on Vulkan (lavapipe in CI): seed 001's static lights. The
// baked-mode lights are baked into the still parts' texels once and added to the moving
// player live (app/texel_world.hpp), every frame equal to the texel passes' C++ reference.
#include "app/texel_world.hpp"

#include "app/draw_list.hpp"

#include "gpu/gpu_test_support.hpp"
#include "lantern/gpu/command_list.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lantern::game {
namespace {

class TexelWorldTest : public test::GpuTest {
  protected:
    std::unique_ptr<TexelWorld> texels;
    void SetUp() override {
        test::GpuTest::SetUp();
        if (IsSkipped()) return;
        auto created = TexelWorld::create(device());
        ASSERT_TRUE(created.ok()) << created.error().message;
        texels = std::move(*created);
    }
    void TearDown() override {
        texels.reset();
        test::GpuTest::TearDown();
    }

    void frame(const std::vector<TexelPart>& parts, const std::vector<texel::TexelLight>& lights) {
        gpu::CommandList cmd = device().begin("texel world test");
        texels->record(cmd, parts, lights, gi::WallView{}, 2.0f);
        device().wait(device().submit(std::move(cmd)));
    }

    struct Compared {
        int differ = 0;       // texels where the GPU is not the reference
        int player_lit = 0;   // the moving player's texels with light
        int still_baked = 0;  // still parts' texels with baked light
    };
    // The frame's light per texel as the C++ reference computes it: the baked-mode lights
    // baked (without the movers), then the realtime pass, against what the GPU lit.
    Compared compare(const std::vector<TexelPart>& parts, const std::vector<texel::TexelLight>& lights) {
        std::vector<texel::Placement> placements;
        for (const TexelPart& p : parts)
            placements.push_back({&texel_model(TexelModel(p.model), p.lod), glm::translate(glm::mat4(1.0f), p.center), p.moves});
        float reach = 1.0f;
        for (const texel::TexelLight& l : lights) reach = std::max(reach, l.position_range.w);
        const texel::TexelScene scene = texel::build_scene(placements, gi::WallView{}, 2.0f, reach);
        const std::vector<texel::TexelSurface> surfaces = texel::uv_to_world(scene);
        std::vector<texel::TexelLight> baked_lights;
        for (const texel::TexelLight& l : lights)
            if (texel::is_baked(l)) baked_lights.push_back(l);
        const auto baked = texel::reference_light(scene, surfaces, baked_lights);
        const auto want = texel::reference_light(scene, surfaces, lights, baked);
        auto got = test::read_back_as<glm::vec4>(device(), texels->lit());
        EXPECT_GE(got.size(), want.size());
        Compared c;
        // The reference lays the parts out in their order; the game's atlas may not (its records
        // say where each part's texels are). A texel's light does not depend on the order.
        const auto records = texels->records();
        EXPECT_EQ(records.size(), parts.size());
        for (std::size_t k = 0; k < parts.size() && k < records.size(); ++k) {
            const glm::uvec4 r = scene.placements[k].ranges;
            const std::uint32_t at = std::uint32_t(records[k].texture.x);
            for (std::uint32_t i = r.z; i < r.z + r.w * r.w; ++i) {
                const glm::vec4 g = got[at + (i - r.z)];
                const glm::vec4 d = glm::abs(g - want[i]);
                if (std::max({d.r, d.g, d.b, d.a}) > 1e-5f && c.differ++ < 5)
                    ADD_FAILURE() << "part " << k << " texel " << i << ": GPU " << g.r << " " << g.g << " " << g.b
                                  << ", reference " << want[i].r << " " << want[i].g << " " << want[i].b;
                if (parts[k].moves) c.player_lit += want[i].r > 0.0f;
                else c.still_baked += baked[i].r > 0.0f;
            }
        }
        return c;
    }
};

// A tree (trunk and crown) stands still under a baked lamp; the player walks beside it under
// a torch. The lamp is baked once, not each step the player takes; a change of the lamp, of a
// still part or of the parts in view bakes again; the torch's flicker never does.
TEST_F(TexelWorldTest, StaticLightsAreBakedOnceAndReachTheWalkingPlayerLive) {
    std::vector<TexelPart> parts(3);
    parts[0].key = 1, parts[0].model = int(TexelModel::tree_trunk), parts[0].center = {5.5f, 0.45f, 5.5f};
    parts[1].key = 2, parts[1].model = int(TexelModel::tree_crown), parts[1].center = {5.5f, 1.25f, 5.5f};
    parts[2].key = 3, parts[2].model = int(TexelModel::player_body), parts[2].center = {3.5f, 0.42f, 5.0f};
    parts[2].moves = true;
    texel::TexelLight lamp = texel::as_baked(
        texel::make_light({4.5f, 2.5f, 4.0f}, {1.0f, 0.8f, 0.6f}, 1.0f, 8.0f, texel::ShadowType::hard, 1.0f, 1.0f, {0.02f, 0.02f, 0.02f}));
    texel::TexelLight torch = texel::make_light({3.0f, 1.0f, 6.5f}, {0.4f, 0.3f, 0.1f}, 1.0f, 6.0f);

    frame(parts, {torch, lamp});
    EXPECT_EQ(texels->bakes(), 1u);
    const Compared first = compare(parts, {torch, lamp});
    EXPECT_EQ(first.differ, 0);
    EXPECT_GT(first.player_lit, 50);
    EXPECT_GT(first.still_baked, 50);
    // The player walks towards the tree's shadow side; the torch flickers.
    for (int step = 0; step < 4; ++step) {
        parts[2].center.x += 0.3f;
        torch.color_type *= 0.9f;
        frame(parts, {torch, lamp});
        EXPECT_EQ(compare(parts, {torch, lamp}).differ, 0) << "step " << step;
    }
    EXPECT_EQ(texels->bakes(), 1u) << "walking and a flickering torch bake nothing";
    // The lamp dims: baked again.
    lamp.color_type *= 0.5f;
    frame(parts, {torch, lamp});
    EXPECT_EQ(texels->bakes(), 2u);
    EXPECT_EQ(compare(parts, {torch, lamp}).differ, 0);
    // A still part moves (the tree is replanted): baked again.
    parts[0].center.z += 1.0f, parts[1].center.z += 1.0f;
    frame(parts, {torch, lamp});
    EXPECT_EQ(texels->bakes(), 3u);
    EXPECT_EQ(compare(parts, {torch, lamp}).differ, 0);
    // The lamp is gone: its bake is cleared with it.
    frame(parts, {torch});
    EXPECT_EQ(texels->bakes(), 4u);
    const Compared unlit = compare(parts, {torch});
    EXPECT_EQ(unlit.differ, 0);
    EXPECT_EQ(unlit.still_baked, 0);
}

// Seed 001's improvement 2 in the game: tree crowns sway (moving parts) and the player walks.
// The atlas holds the still parts first, so what moves is one run of texels carried again by
// UV to world each frame; swaying bakes nothing, and every frame equals the reference.
TEST_F(TexelWorldTest, SwayingCrownsAreCarriedAgainEachFrameWithoutABake) {
    std::vector<TexelPart> parts(5);
    parts[0].key = 1, parts[0].model = int(TexelModel::player_body), parts[0].center = {3.5f, 0.42f, 5.0f};
    parts[0].moves = true;
    const glm::vec2 trees[2] = {{5.5f, 5.5f}, {7.5f, 3.5f}};
    for (int t = 0; t < 2; ++t) {
        TexelPart& trunk = parts[std::size_t(1 + 2 * t)];
        TexelPart& crown = parts[std::size_t(2 + 2 * t)];
        trunk.key = std::uint64_t(10 + 2 * t), trunk.model = int(TexelModel::tree_trunk);
        trunk.center = {trees[t].x, 0.45f, trees[t].y};
        crown.key = std::uint64_t(11 + 2 * t), crown.model = int(TexelModel::tree_crown), crown.moves = true;
    }
    const auto sway = [&](double time) {
        for (int t = 0; t < 2; ++t) {
            const glm::vec2 s = crown_sway(time, trees[t]);
            parts[std::size_t(2 + 2 * t)].center = {trees[t].x + s.x, 1.25f, trees[t].y + s.y};
        }
    };
    const texel::TexelLight lamp = texel::as_baked(texel::make_light({4.5f, 2.5f, 4.0f}, {1.0f, 0.8f, 0.6f}, 1.0f, 8.0f));
    const texel::TexelLight torch = texel::make_light({3.0f, 1.0f, 6.5f}, {0.4f, 0.3f, 0.1f}, 1.0f, 6.0f);
    sway(0.0);
    frame(parts, {torch, lamp});
    EXPECT_EQ(compare(parts, {torch, lamp}).differ, 0);
    // The atlas: the two trunks, then the player and the two crowns.
    const auto first_texel = [&](std::size_t k) { return texels->records()[k].texture.x; };
    EXPECT_LT(first_texel(1), first_texel(0));
    EXPECT_LT(first_texel(3), first_texel(0));
    EXPECT_LT(first_texel(0), first_texel(2));
    EXPECT_LT(first_texel(0), first_texel(4));
    for (int f = 1; f <= 3; ++f) {
        sway(0.25 * f);
        frame(parts, {torch, lamp});
        const texel::TexelPlan& plan = texels->last_plan();
        EXPECT_TRUE(plan.runs(texel::TexelPass::uv_to_world)) << f;
        EXPECT_FALSE(plan.runs(texel::TexelPass::bake)) << f;
        EXPECT_EQ(plan.moved, (std::vector<std::uint32_t>{3u, 4u})) << "the crowns, after the trunks and the player";
        EXPECT_EQ(compare(parts, {torch, lamp}).differ, 0) << f;
    }
    EXPECT_EQ(texels->bakes(), 1u);
    // The crowns did move, by less than the sway's bound.
    const glm::vec2 moved = crown_sway(0.75, trees[0]) - crown_sway(0.0, trees[0]);
    EXPECT_GT(glm::length(moved), 0.005f);
    EXPECT_LE(glm::length(moved), 2.0f * 1.42f * crown_sway_tiles);
}

} // namespace
} // namespace lantern::game
