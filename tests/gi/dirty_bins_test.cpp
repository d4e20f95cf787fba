// Dirty light bins (docs/gi.md): the direct pass records only the workgroups whose lights
// changed since it last ran, and runs those no light reaches without its light loops. Two
// renderers see the same frames, one with dirty bins and one without: every texture of
// every frame is the same bit for bit, the first records fewer workgroups where only
// lights changed, and all of them where anything else did. The frames cover a flicker, a
// light that moves, one that leaves, removed and added lights (indices shift), emissives,
// proxies, unfolded proxy shadows, a sun coming and going, and mixed lights.
#include "gi_compare.hpp"
#include "test_scenes.hpp"

#include "gpu_test_support.hpp"
#include "lantern/gi/baked_light.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/vulkan/renderer.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

using namespace lantern::gi;
using gi_test::inputs_of;
using lantern::scene::Scene;

namespace {

class DirtyBins : public lantern::test::GpuTest {
  protected:
    void SetUp() override {
        GpuTest::SetUp();
        if (IsSkipped()) return;
        auto a = vk::Renderer::create(device());
        auto b = vk::Renderer::create(device(), {.dirty_bins = false});
        ASSERT_TRUE(a.ok() && b.ok());
        dirty_ = std::move(a.value());
        full_ = std::move(b.value());
    }
    void TearDown() override {
        dirty_.reset();
        full_.reset();
        GpuTest::TearDown();
    }

    // What a pass did on the renderer with dirty bins: nothing, part of its workgroups, all
    // of them; `any`: not checked (the pass does not run).
    enum class Expect { any, none, some, all };

    // One frame on both renderers: every contract texture equal bit for bit; the direct and
    // mixed passes recorded as many workgroups as `direct` and `mixed` say, the heat pass as
    // many of its tap masks' workgroups as `heat` says, the baked pass as many of its
    // mixed lights' adds as `mixed_add` says (the renderer without dirty bins adds them all),
    // and the baked sampling and AO rows as many workgroups as `sampled` and `ao` say (they
    // scroll with the window), and the wall indirect pass as many as `faces` says (the blocks
    // holding a wall texel, while the window and the walls stay).
    void frame(const std::string& name, const FrameInputs& in, Expect direct, Expect mixed = Expect::any,
               Expect heat = Expect::any, Expect mixed_add = Expect::any, Expect sampled = Expect::any,
               Expect ao = Expect::any, Expect faces = Expect::any) {
        PassPlan plan = plan_passes(in, true);
        constexpr int n = 7;
        constexpr Pass passes[n] = {Pass::direct,       Pass::mixed, Pass::heat,         Pass::baked,
                                    Pass::baked_sample, Pass::ao,    Pass::wall_indirect};
        constexpr const char* names[n] = {": direct", ": mixed", ": heat's tap masks", ": the mixed lights' adds",
                                          ": the baked sampling", ": AO", ": the wall indirect pass"};
        vk::Renderer::PartialWork before[n], after[n];
        for (int k = 0; k < n; ++k) before[k] = dirty_->partial_work(passes[k]);
        auto a = run_vulkan_frame(*dirty_, in, plan);
        auto b = run_vulkan_frame(*full_, in, plan);
        ASSERT_TRUE(a.ok() && b.ok()) << name;
        for (int k = 0; k < n; ++k) after[k] = dirty_->partial_work(passes[k]);
        const Expect expect[n] = {direct, mixed, heat, mixed_add, sampled, ao, faces};
        for (int k = 0; k < n; ++k) {
            const std::string what = name + names[k];
            const std::uint64_t workgroups = after[k].workgroups - before[k].workgroups,
                                recorded = after[k].recorded - before[k].recorded;
            if (expect[k] != Expect::any) {
                ASSERT_GT(workgroups, 0u) << what;
            }
            switch (expect[k]) {
            case Expect::any: break;
            case Expect::none: EXPECT_EQ(recorded, 0u) << what; break;
            case Expect::some:
                EXPECT_GT(recorded, 0u) << what;
                EXPECT_LT(recorded, workgroups) << what;
                break;
            case Expect::all: EXPECT_EQ(recorded, workgroups) << what; break;
            }
        }
        int compared = 0;
        for (const auto& [tex, want] : b->textures) {
            auto it = a->textures.find(tex);
            ASSERT_NE(it, a->textures.end()) << name << ": " << tex;
            const Texture& got = it->second;
            ASSERT_EQ(got.texels.size(), want.texels.size()) << name << ": " << tex;
            std::size_t differ = 0, first = 0;
            for (std::size_t i = 0; i < got.texels.size(); ++i)
                if (std::memcmp(&got.texels[i], &want.texels[i], sizeof(float)) != 0 && differ++ == 0) first = i;
            EXPECT_EQ(differ, 0u) << name << ": " << tex << " differs in " << differ << " values, first at value " << first
                                  << " (" << got.texels[first] << " against " << want.texels[first] << ")";
            ++compared;
        }
        EXPECT_GE(compared, 6) << name;
    }

    std::unique_ptr<vk::Renderer> dirty_, full_;
};

// A cave with point lights, an emissive, and proxies that cast unfolded shadows up the walls.
Scene lit_cave() {
    Scene s = gi_test::open_scene({20, 15}, {40, 30}, 4);
    s.walls = gi_test::cave(40, 30, 7, 0.42f);
    s.gi.proxy_wall_shadows = lantern::scene::ProxyWallShadows::unfold;
    s.point_lights = {gi_test::point({8.5f, 7.5f}, {1.0f, 0.6f, 0.3f}, 1.0f, 6.5f),
                      gi_test::point({30.2f, 20.7f}, {0.3f, 0.6f, 1.0f}, 1.2f, 5.0f),
                      gi_test::point({20.5f, 14.5f}, {1.0f, 1.0f, 0.8f}, 0.8f, 4.0f),
                      gi_test::point({34.5f, 5.5f}, {1.0f, 0.4f, 0.2f}, 1.0f, 6.0f)};
    s.emissive_lights = {gi_test::emissive({12.5f, 24.5f}, {0.2f, 1.0f, 0.4f}, 1.0f, 4.0f)};
    for (glm::vec2 p : {glm::vec2(10.5f, 9.0f), glm::vec2(29.0f, 18.5f)}) {
        lantern::scene::ShadowProxy proxy;
        proxy.position = p;
        proxy.size = {0.4f, 0.4f};
        s.shadow_proxies.push_back(proxy);
    }
    return s;
}

} // namespace

TEST_F(DirtyBins, OnlyTheBinsOfChangedLightsAreRecordedAndTheFrameIsTheSame) {
    Scene s = lit_cave();
    frame("the first frame", inputs_of(s), Expect::all);
    frame("nothing changed", inputs_of(s), Expect::none);
    s.point_lights[0].intensity *= 0.83f;
    frame("a torch flickers", inputs_of(s), Expect::some);
    s.point_lights[1].position += glm::vec2(0.3f, -0.2f);
    frame("a light moves", inputs_of(s), Expect::some);
    s.emissive_lights[0].intensity = 1.4f;
    frame("an emissive brightens", inputs_of(s), Expect::some);
    s.point_lights.pop_back();
    frame("the last point light is gone (the emissive's index shifts)", inputs_of(s), Expect::some);
    s.point_lights.insert(s.point_lights.begin(), gi_test::point({3.5f, 3.5f}, {1.0f, 0.9f, 0.9f}, 1.0f, 3.0f));
    frame("a point light comes first (every index shifts)", inputs_of(s), Expect::some);
    s.point_lights[1].position = {-40.0f, -40.0f};
    frame("a light leaves the window", inputs_of(s), Expect::some);
    s.shadow_proxies[0].position.x += 0.25f;
    frame("a proxy moves", inputs_of(s), Expect::all);
    s.point_lights[2].intensity *= 1.1f;
    frame("after it, a flicker again", inputs_of(s), Expect::some);
    s.walls.cells[std::size_t(15 * 40 + 20)] ^= 1;
    frame("a wall is mined", inputs_of(s), Expect::all);
    s.point_lights[2].intensity *= 0.9f;
    frame("after it, a flicker again", inputs_of(s), Expect::some);
}

// With a sun the direct pass adds the suns' own textures (the directional pass's) as it
// writes: when the sun rises, moves or sets, every bin is recorded; a flicker under a still
// sun records the flickering light's bins alone.
TEST_F(DirtyBins, ASunComingAndGoingRecordsEverything) {
    Scene s = lit_cave();
    frame("the first frame", inputs_of(s), Expect::all);
    lantern::scene::DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.4f, -0.8f, -0.3f));
    sun.intensity = 0.4f;
    s.directional_lights.push_back(sun);
    frame("the sun rises", inputs_of(s), Expect::all);
    s.point_lights[0].intensity *= 0.9f;
    frame("a flicker under the sun", inputs_of(s), Expect::some);
    s.directional_lights[0].direction = glm::normalize(glm::vec3(0.5f, -0.8f, -0.3f));
    frame("the sun moves", inputs_of(s), Expect::all);
    s.point_lights[0].intensity *= 0.9f;
    frame("a flicker under the moved sun", inputs_of(s), Expect::some);
    s.directional_lights.clear();
    frame("the sun sets", inputs_of(s), Expect::all);
    s.point_lights[0].intensity *= 0.9f;
    frame("a flicker at night", inputs_of(s), Expect::some);
}

// Mixed lights (a bake is used): the baked pass adds their direct light into the direct
// textures in place, after the bounce passes read them, and only in the workgroups a mixed
// light reaches (the mixed set holds zeros elsewhere), so the direct pass records those bins
// again the next frame and keeps the others. The mixed pass keeps its own bins while
// realtime lights or a mixed sun change.
TEST_F(DirtyBins, MixedLightsKeepTheirOwnBins) {
    Scene s = lit_cave();
    s.point_lights[3].mode = lantern::scene::LightMode::mixed;
    auto inputs = [&] {
        FrameInputs in = inputs_of(s);
        in.baked = gi_test::synthetic_bake(in.walls, {-2, -2}, {44, 34}, 4, 0.0f, 900);
        split_for_bake(in, s);
        return in;
    };
    {
        const FrameInputs in = inputs();
        ASSERT_EQ(in.mixed_lights.size(), 1u);
        const PassPlan plan = plan_passes(in, true);
        ASSERT_TRUE(plan.run.has(Pass::mixed) && plan.run.has(Pass::baked));
    }
    frame("the first frame", inputs(), Expect::all, Expect::all, Expect::any, Expect::some);
    s.point_lights[0].intensity *= 0.8f;
    frame("a realtime torch flickers", inputs(), Expect::some, Expect::none, Expect::any, Expect::some);
    frame("nothing changed but the mixed light's bins", inputs(), Expect::some, Expect::none, Expect::any, Expect::some);
    s.point_lights[3].position += glm::vec2(0.5f, 0.0f);
    frame("the mixed light moves", inputs(), Expect::some, Expect::some, Expect::any, Expect::some);
    s.emissive_lights[0].mode = lantern::scene::LightMode::mixed;
    frame("an emissive turns mixed", inputs(), Expect::some, Expect::any, Expect::any, Expect::some);
    s.point_lights[3].radius = 100.0f;
    frame("the mixed light reaches every texel", inputs(), Expect::some, Expect::any, Expect::any, Expect::all);
    s.point_lights[0].intensity *= 0.8f;
    frame("a flicker after the adds everywhere", inputs(), Expect::all, Expect::none, Expect::any, Expect::all);
    s.point_lights[3].radius = 6.0f;
    s.emissive_lights[0].mode = lantern::scene::LightMode::realtime;
    s.point_lights[3].position = {-50.0f, 0.0f};
    frame("the mixed light leaves (nothing is added in place)", inputs(), Expect::all, Expect::any);
    s.point_lights[0].intensity *= 1.2f;
    frame("a realtime torch flickers again", inputs(), Expect::some, Expect::any);
    // A mixed sun has textures of its own (the mixed row writes them, the baked row adds them
    // everywhere): the mixed lights keep their bins while it rises and moves, and their adds
    // stay in the bins they reach. The realtime direct pass records every bin after each add
    // everywhere.
    s.point_lights[3].position = {20.5f, 14.5f};
    frame("the mixed light is back (its set was cleared)", inputs(), Expect::any, Expect::all, Expect::any, Expect::some);
    lantern::scene::DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.4f, -0.8f, -0.3f));
    sun.intensity = 0.4f;
    sun.mode = lantern::scene::LightMode::mixed;
    s.directional_lights.push_back(sun);
    frame("a mixed sun rises", inputs(), Expect::some, Expect::none, Expect::any, Expect::some);
    s.directional_lights[0].direction = glm::normalize(glm::vec3(0.5f, -0.8f, -0.3f));
    frame("the mixed sun moves", inputs(), Expect::all, Expect::none, Expect::any, Expect::some);
    s.point_lights[3].intensity *= 0.9f;
    frame("the mixed light changes under the mixed sun", inputs(), Expect::all, Expect::some, Expect::any, Expect::some);
    s.directional_lights.clear();
    frame("the mixed sun sets", inputs(), Expect::all, Expect::none, Expect::any, Expect::some);
}

// The heat pass reruns whenever the direct light changes (every frame a torch flickers), but
// its tap masks depend on the window, the walls and the heat settings alone: they are kept
// through flickers and proxy moves and recomputed when a wall is mined or the window steps,
// and the frames stay the same bit for bit as with everything recomputed.
TEST_F(DirtyBins, TheHeatPassKeepsItsTapMasksWhileTheWallsAndWindowStay) {
    Scene s = lit_cave();
    s.gi.resolution = 8;
    s.gi.heat_scale = lantern::scene::HeatScale::half; // four heat texels a tile: far taps, segment checks
    s.gi.heat_rounds = 6;
    ASSERT_TRUE(plan_passes(inputs_of(s), true).run.has(Pass::heat));
    frame("the first frame", inputs_of(s), Expect::all, Expect::any, Expect::all);
    s.point_lights[0].intensity *= 0.83f;
    frame("a torch flickers", inputs_of(s), Expect::some, Expect::any, Expect::none);
    s.shadow_proxies[0].position.x += 0.25f;
    frame("a proxy moves", inputs_of(s), Expect::all, Expect::any, Expect::none);
    s.walls.cells[std::size_t(15 * 40 + 20)] ^= 1;
    frame("a wall is mined", inputs_of(s), Expect::all, Expect::any, Expect::all);
    s.point_lights[1].intensity *= 1.1f;
    frame("after it, a flicker", inputs_of(s), Expect::some, Expect::any, Expect::none);
    std::get<lantern::scene::OrthoView>(s.view).center += glm::vec2(1.0f, 0.0f);
    frame("the window steps", inputs_of(s), Expect::all, Expect::any, Expect::all);
    s.gi.segment_check = !s.gi.segment_check;
    frame("the segment check is switched (the direct pass does not read it)", inputs_of(s), Expect::none, Expect::any,
          Expect::all);
}

// The baked sampling and AO rows rerun when the window steps, but a texel's baked light and
// AO depend on its world point and the walls around its tile alone: at a step by whole texels
// each row shifts what both windows hold and computes only the new strips, and every texture
// stays the same bit for bit as with everything computed. A mined wall, a jump past the
// window, a new bake and a resolution whose texel centres round (3) compute everything again;
// with AO's dither (a pattern of the window's texels modulo 4) AO scrolls by multiples of 4
// texels alone.
TEST_F(DirtyBins, TheBakedSamplingAndAoScrollWithTheWindow) {
    Scene s = lit_cave();
    s.point_lights[3].mode = lantern::scene::LightMode::mixed;
    s.gi.ao.enabled = true;
    s.gi.ao.dither = false;
    std::uint64_t bake_seed = 900;
    bool pulsing = false;
    auto inputs = [&] {
        FrameInputs in = inputs_of(s);
        in.baked = gi_test::synthetic_bake(in.walls, {-2, -2}, {44, 34}, 4, 0.0f, bake_seed, pulsing);
        in.baked_pulse = 0.37f;
        split_for_bake(in, s);
        return in;
    };
    {
        const PassPlan plan = plan_passes(inputs(), true);
        ASSERT_TRUE(plan.run.has(Pass::baked_sample) && plan.run.has(Pass::ao));
    }
    constexpr Expect any = Expect::any, some = Expect::some, all = Expect::all;
    auto step = [&](const std::string& name, glm::vec2 by, Expect sampled, Expect ao = Expect::any) {
        std::get<lantern::scene::OrthoView>(s.view).center += by;
        frame(name, inputs(), any, any, any, any, sampled, ao == any ? sampled : ao);
    };
    frame("the first frame", inputs(), any, any, any, any, all, all);
    step("a step in +x", {1.0f, 0.0f}, some);
    step("a step in -z", {0.0f, -1.0f}, some);
    step("a diagonal step of several tiles", {-2.0f, 3.0f}, some);
    step("a step in -x", {-1.0f, 0.0f}, some);
    s.walls.cells[std::size_t(15 * 40 + 20)] ^= 1;
    step("a wall mined where both windows are", {1.0f, 0.0f}, all);
    step("a step after it", {0.0f, 1.0f}, some);
    step("a jump past the bake (the baked sampling does not run)", {200.0f, 0.0f}, any);
    step("back into the cave", {-199.0f, 0.0f}, any);
    step("a step back", {1.0f, 1.0f}, some);
    bake_seed = 901;
    pulsing = true;
    s.gi.ao.dither = true;
    step("another bake, with a pulsing part; AO dithered", {1.0f, 0.0f}, all);
    step("a step with the pulsing part and the dither", {0.0f, -2.0f}, some);
    s.gi.window_snap = lantern::scene::WindowSnap::texel;
    step("the window snapped to texels (it stays: nothing to compute)", {0.0f, 0.0f}, Expect::none);
    step("a step of one texel (AO's dither would move)", {0.25f, 0.0f}, some, all);
    s.gi.ao.dither = false;
    step("the dither switched off", {0.0f, 0.0f}, any, all);
    step("a step of one texel without the dither", {0.0f, 0.25f}, some, some);
    s.gi.resolution = 3;
    step("resolution 3", {0.0f, 0.0f}, all);
    step("a step at resolution 3 (texel centres round)", {1.0f, 0.0f}, all);
}

// The wall indirect pass writes zeros off wall texels: once it has written the whole window,
// it computes only the blocks holding a wall texel while the window and the walls stay and
// it stays in every frame's plan. A mined wall, a window step, and a frame of another method
// (the gather writes the same face textures, with alpha 1 off walls) make it write the whole
// window again; every texture stays the same bit for bit as with everything computed.
TEST_F(DirtyBins, TheWallIndirectPassComputesTheWallBlocksAlone) {
    Scene s = lit_cave();
    const auto faces = [&](const std::string& name, Expect expect) {
        frame(name, inputs_of(s), Expect::any, Expect::any, Expect::any, Expect::any, Expect::any, Expect::any, expect);
    };
    ASSERT_TRUE(plan_passes(inputs_of(s), true).run.has(Pass::wall_indirect));
    faces("the first frame", Expect::all);
    s.point_lights[0].intensity *= 0.8f;
    faces("a torch flickers", Expect::some);
    s.walls.cells[std::size_t(15 * 40 + 20)] ^= 1;
    faces("a wall is mined", Expect::all);
    s.point_lights[1].intensity *= 1.1f;
    faces("after it, a flicker", Expect::some);
    std::get<lantern::scene::OrthoView>(s.view).center += glm::vec2(1.0f, 0.0f);
    faces("the window steps", Expect::all);
    faces("nothing changed", Expect::some);
    s.gi.method = lantern::scene::GiMethod::gather;
    ASSERT_FALSE(plan_passes(inputs_of(s), true).run.has(Pass::wall_indirect));
    faces("a frame of the gather", Expect::any);
    s.gi.method = lantern::scene::GiMethod::heat;
    faces("the heat method again", Expect::all);
    faces("and again", Expect::some);
}
