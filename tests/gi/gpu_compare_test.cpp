// Every GI pass on Vulkan (lavapipe in CI) against the C++ reference, texel by texel, on
// the comparison scenes and two real maps (tolerances: gi_compare.hpp).
#include "gi_compare.hpp"
#include "test_scenes.hpp"

#include "gpu_test_support.hpp"
#include "shared_renderer.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/vulkan/pass_params.hpp"
#include "lantern/gi/vulkan/renderer.hpp"

#include <gtest/gtest.h>

#include <optional>

using namespace lantern::gi;
using gi_test::NamedScene;

namespace {

class GiGpuCompare : public lantern::test::GpuTest {
  protected:
    // Runs the scene's frame (through `through`) on both backends and compares every texture
    // and the lit image.
    // With `reference_by_dda`, the reference traces point lights' shadows by the DDA (the
    // specification) whatever gi.shadow_method says.
    // With `proxy_strength` below 1, every other shadow proxy fades to it (the cap's fade).
    // `renderer`: another than the shared one (other block and workgroup sizes).
    void compare_scene(const NamedScene& named, Pass through, bool lit, bool reference_by_dda = false,
                       float proxy_strength = 1.0f, vk::Renderer* renderer = nullptr) {
        const lantern::scene::Scene& s = named.scene;
        std::string why;
        auto window = compute_window(s.view, s.gi, &why);
        ASSERT_TRUE(window) << why;
        FrameInputs in = gather_frame_inputs(s, *window);
        for (std::size_t k = 0; k < in.proxies.size(); k += 2) in.proxies[k].fade.x = proxy_strength;
        PassPlan plan = plan_passes(in, lit, through);
        auto gpu = run_vulkan_frame(renderer ? *renderer : gi_test::shared_renderer(device()), in, plan);
        ASSERT_TRUE(gpu.ok()) << gpu.error().message;
        FrameInputs ref_in = in;
        if (reference_by_dda) ref_in.settings.shadow_method = lantern::scene::ShadowMethod::dda;
        FrameResult ref = run_reference_frame(ref_in, plan);
        ASSERT_EQ(gpu->textures.size(), ref.textures.size()) << named.name;
        for (const auto& [name, reference] : ref.textures) {
            auto it = gpu->textures.find(name);
            ASSERT_NE(it, gpu->textures.end()) << named.name << ": GPU did not produce " << name;
            const float ulps = (name == "indirect" || name.rfind("wall_indirect", 0) == 0) ? 4.0f : 2.0f;
            auto diff = gi_test::compare_textures(it->second, reference, ulps);
            EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe(named.name + " " + name, diff);
        }
        if (lit) {
            ASSERT_TRUE(gpu->lit && ref.lit);
            int worst = 0;
            std::size_t off = 0;
            for (std::size_t i = 0; i < ref.lit->rgb.size(); ++i) {
                int d = std::abs(int(gpu->lit->rgb[i]) - int(ref.lit->rgb[i]));
                worst = std::max(worst, d);
                off += d > 1;
            }
            EXPECT_EQ(off, 0u) << named.name << " lit image: " << off << " channels differ by more than one step (worst "
                               << worst << ")";
        }
    }
};

class GiGpuScenes : public GiGpuCompare, public ::testing::WithParamInterface<std::string> {};

// The proxies comparison scene at giRes 8 over a 20 x 20 cave with walls 2.5 high: faces for
// the proxies' shadows to climb, and room for long shadows.
NamedScene proxies_over_a_cave() {
    NamedScene named = gi_test::comparison_scene("proxies");
    named.scene.gi.resolution = 8;
    named.scene.walls = gi_test::cave(20, 20, 9, 0.3f);
    named.scene.wall_height = 2.5f;
    return named;
}

// That scene with shadows up to 5 long and four lights near the cave's corners, far from the
// proxies (so each proxy's shadow wedge from a light is narrow), reaching 18.
NamedScene proxies_lit_from_the_corners() {
    NamedScene named = proxies_over_a_cave();
    for (auto& p : named.scene.shadow_proxies) p.max_length = 5.0f;
    named.scene.point_lights.clear();
    for (glm::vec2 at : {glm::vec2(1.5f, 1.5f), glm::vec2(18.5f, 2.5f), glm::vec2(17.5f, 18.5f), glm::vec2(2.5f, 16.5f)})
        named.scene.point_lights.push_back(gi_test::point(at, {1.0f, 0.8f, 0.6f}, 1.5f, 18.0f));
    return named;
}

} // namespace

TEST_P(GiGpuScenes, DirectPassesMatchReference) {
    compare_scene(gi_test::comparison_scene(GetParam()), Pass::direct, false); // through the suns, which come first
}

TEST_P(GiGpuScenes, WholePipelineMatchesReference) {
    compare_scene(gi_test::comparison_scene(GetParam()), Pass::lit, true);
}

INSTANTIATE_TEST_SUITE_P(Scenes, GiGpuScenes, ::testing::ValuesIn(gi_test::comparison_scene_names()),
                         [](const auto& p) { return p.param; });

// Shadow proxies fading near the cap (GpuShadowProxy::fade, issue 19): partial strengths on
// the GPU equal the reference through the whole pipeline, on the comparison scenes with
// proxies.
TEST_F(GiGpuCompare, FadingProxiesMatchReference) {
    int scenes = 0;
    for (const std::string& name : gi_test::comparison_scene_names()) {
        const NamedScene named = gi_test::comparison_scene(name);
        if (named.scene.shadow_proxies.size() < 2 || scenes == 2) continue;
        ++scenes;
        SCOPED_TRACE(name);
        compare_scene(named, Pass::lit, true, false, 0.35f);
    }
    EXPECT_EQ(scenes, 2) << "two comparison scenes with shadow proxies";
}

// The direct pass's lanes take every workgroup width's stride (invocation x computes texels
// x + k * width) and repack the shadow texture's rows through shared memory: the GPU's
// default shape (16 x 8 blocks of 4 x 1) and a narrow one on lavapipe equal the reference on
// the scenes with proxies and walls; a workgroup needing more shared memory than every
// device offers is refused with a message.
TEST_F(GiGpuCompare, OtherWorkgroupShapesMatchReference) {
    struct Shape { std::uint32_t block_h, gx, gy; };
    for (const Shape shape : {Shape{1, 16, 8}, Shape{2, 4, 4}}) {
        vk::RendererOptions options;
        options.block_h = shape.block_h;
        options.group_x = shape.gx;
        options.group_y = shape.gy;
        auto renderer = vk::Renderer::create(device(), options);
        ASSERT_TRUE(renderer.ok()) << renderer.error().message;
        for (const char* name : {"proxies", "sun_and_walls"}) {
            SCOPED_TRACE(std::string(name) + ", block_h " + std::to_string(shape.block_h) + ", group " +
                         std::to_string(shape.gx) + " x " + std::to_string(shape.gy));
            compare_scene(gi_test::comparison_scene(name), Pass::direct, false, false, 1.0f, renderer.value().get());
        }
    }
    vk::RendererOptions large;
    large.group_x = large.group_y = 32;
    large.block_h = 4;
    auto refused = vk::Renderer::create(device(), large);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("shared memory"), std::string::npos) << refused.error().message;
}

// gi_light_bins keeps for each (bin, point light, sub-bin: a band of its rows by a strip of
// 8 neighbouring lanes' columns) only the proxies whose shadow from that light can reach the
// sub-bin: beyond its horizon, within its reach, and inside the wedge round the proxy's
// direction from the light (half-angle asin(w / rmin)); the reference visits every proxy. The proxies scene at giRes 8
// over a cave, with lights far from the proxies (so the wedges are narrow) and long shadows,
// folded and unfolded, on the default workgroup and on a narrower one.
TEST_F(GiGpuCompare, PointLightsSkipOnlyProxiesOutsideTheirShadowWedges) {
    NamedScene named = proxies_lit_from_the_corners();
    vk::RendererOptions narrow;
    narrow.group_x = narrow.group_y = 4;
    auto renderer = vk::Renderer::create(device(), narrow);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    for (auto unfold : {lantern::scene::ProxyWallShadows::full, lantern::scene::ProxyWallShadows::unfold}) {
        named.scene.gi.proxy_wall_shadows = unfold;
        SCOPED_TRACE(unfold == lantern::scene::ProxyWallShadows::unfold ? "unfolded" : "folded");
        compare_scene(named, Pass::direct, false);
        compare_scene(named, Pass::direct, false, false, 1.0f, renderer.value().get());
    }
}

// The proxy loops keep a list's two mask words in registers when the frame's proxies fit
// them and its point lights are at most 256 (PROXY_REGISTERS, pass_params.hpp); past 64
// proxies they read the masks word by word (gi_shadow.glsl proxy_next). That path against
// the reference: the proxies scene of the test above with its twelve proxies copied round
// seven rings (84 in view), its four lights and a low sun, folded and unfolded.
TEST_F(GiGpuCompare, ProxyLoopsPastTwoMaskWordsMatchReference) {
    NamedScene named = proxies_over_a_cave();
    named.scene.gi.max_shadow_proxies = 256;
    const std::vector<lantern::scene::ShadowProxy> ring = named.scene.shadow_proxies;
    named.scene.shadow_proxies.clear();
    for (int copy = 0; copy < 7; ++copy)
        for (lantern::scene::ShadowProxy p : ring) {
            const glm::vec2 from_centre = p.position - glm::vec2(10.0f);
            p.position = glm::vec2(10.0f) + from_centre * (0.5f + 0.25f * float(copy)) + glm::vec2(0.13f * float(copy));
            p.max_length = 3.0f;
            named.scene.shadow_proxies.push_back(p);
        }
    named.scene.point_lights.clear();
    for (glm::vec2 at : {glm::vec2(1.5f, 1.5f), glm::vec2(18.5f, 2.5f), glm::vec2(17.5f, 18.5f), glm::vec2(10.2f, 9.7f)})
        named.scene.point_lights.push_back(gi_test::point(at, {1.0f, 0.8f, 0.6f}, 1.5f, 14.0f));
    named.scene.directional_lights.push_back(
        {glm::normalize(glm::vec3(0.4f, -0.6f, 0.2f)), {1.0f, 0.95f, 0.8f}, 1.0f, 4.0f, 0.5f});
    auto window = compute_window(named.scene.view, named.scene.gi);
    ASSERT_TRUE(window);
    ASSERT_GT(gather_frame_inputs(named.scene, *window).proxies.size(), vk::proxy_register_count);
    for (auto unfold : {lantern::scene::ProxyWallShadows::full, lantern::scene::ProxyWallShadows::unfold}) {
        named.scene.gi.proxy_wall_shadows = unfold;
        SCOPED_TRACE(unfold == lantern::scene::ProxyWallShadows::unfold ? "unfolded" : "folded");
        compare_scene(named, Pass::direct, false);
    }
}

// The per-light proxy lists come in grains: a workgroup's rows in B bands (B dividing its
// rows) by its 4 strips, the finest whose lists fit RendererOptions::proxy_list_bytes, down
// to one list per workgroup when none fits. Every grain equals the reference: the scene of
// the test above, folded (its lists are the shortest), on an 8 x 8 workgroup of 4-row blocks,
// with the budget set to exactly what 8 bands need, then 4, 2 and 1 band and just below 1. A
// proxy left out of a list occludes nothing there; the lights whose list is empty in a
// texel's sub-bin are summed before the others (gi_direct.comp), so the grains agree with the
// reference to rounding, not bit for bit with each other.
TEST_F(GiGpuCompare, PointLightProxyListsOfEveryGrainEqualTheReference) {
    NamedScene named = proxies_lit_from_the_corners();
    named.scene.gi.proxy_wall_shadows = lantern::scene::ProxyWallShadows::full;
    auto window = compute_window(named.scene.view, named.scene.gi);
    ASSERT_TRUE(window);
    const FrameInputs in = gather_frame_inputs(named.scene, *window);
    const PassPlan plan = plan_passes(in, false, Pass::direct);
    const FrameResult reference = run_reference_frame(in, plan);
    // A band's bytes (direct_light.cpp): per (bin, strip) a proxy mask per point light and a
    // mask of the point lights whose list is not empty.
    const std::uint64_t pitch = (std::uint64_t(window->width) + 3) / 4 * 4;
    const std::uint64_t bins = (pitch / 4 + 7) / 8 * ((std::uint64_t(window->height) + 31) / 32);
    const std::uint64_t words = (in.proxies.size() + 31) / 32;
    const std::uint64_t point_words = (in.point_lights.size() + 31) / 32;
    const std::uint64_t per_band = (bins * words * 4 * in.point_lights.size() + bins * point_words * 4) * 4;
    vk::RendererOptions options;
    options.block_h = 4;
    options.group_x = options.group_y = 8;
    auto renderer = vk::Renderer::create(device(), options);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    for (std::uint64_t budget : {8 * per_band, 4 * per_band, 3 * per_band, per_band, per_band - 1}) {
        SCOPED_TRACE("proxy_list_bytes " + std::to_string(budget) + " (" + std::to_string(budget / per_band) + " bands)");
        renderer.value()->set_proxy_list_bytes(budget);
        auto gpu = run_vulkan_frame(*renderer.value(), in, plan);
        ASSERT_TRUE(gpu.ok()) << gpu.error().message;
        ASSERT_EQ(gpu->textures.size(), reference.textures.size());
        for (const auto& [name, texture] : reference.textures) {
            auto it = gpu->textures.find(name);
            ASSERT_NE(it, gpu->textures.end()) << name;
            const gi_test::TexelDiff diff = gi_test::compare_textures(it->second, texture);
            EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe(name, diff);
        }
    }
}

// The pass table times parts of a pass on their own (PassRecorder::begin_part): the direct
// pass's light culling, gi_light_bins, is a part named "light bins" of the direct row, timed
// inside the row's own region, and not counted again in the frame's total. A second frame
// of the same inputs records no bin (dirty light bins), so it has no such part.
TEST_F(GiGpuCompare, TheDirectPassTimesItsLightCullingAsAPart) {
    if (!device().capabilities().timestamps) GTEST_SKIP() << "the device has no timestamps";
    NamedScene named = gi_test::comparison_scene("proxies");
    named.scene.gi.resolution = 8;
    auto window = compute_window(named.scene.view, named.scene.gi);
    ASSERT_TRUE(window);
    const FrameInputs in = gather_frame_inputs(named.scene, *window);
    ASSERT_FALSE(in.point_lights.empty());
    auto renderer = vk::Renderer::create(device());
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    for (int frame = 0; frame < 2; ++frame) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        auto gpu = run_vulkan_frame(*renderer.value(), in, plan_passes(in, false, Pass::direct), false);
        ASSERT_TRUE(gpu.ok()) << gpu.error().message;
        double sum = 0.0;
        int direct_rows = 0;
        for (const PassReport& p : gpu->passes) {
            sum += p.gpu_ms;
            if (p.pass != Pass::direct) {
                EXPECT_TRUE(p.parts.empty()) << pass_name(p.pass);
                continue;
            }
            ++direct_rows;
            ASSERT_TRUE(p.ran);
            if (frame == 1) {
                EXPECT_TRUE(p.parts.empty()) << "a frame that recorded no bin timed its culling";
                continue;
            }
            ASSERT_EQ(p.parts.size(), 1u);
            EXPECT_EQ(p.parts[0].name, "light bins");
            EXPECT_GT(p.parts[0].gpu_ms, 0.0);
            EXPECT_LE(p.parts[0].gpu_ms, p.gpu_ms); // within the pass's region
        }
        EXPECT_EQ(direct_rows, 1);
        EXPECT_NEAR(gpu->total_ms, sum, 1e-9 * (1.0 + sum)); // the parts not counted twice
    }
}

// The sun's pass visits only the proxies whose shadow can reach each workgroup (masks built
// on the host, record_directional's sun_proxy_bins); the reference visits every proxy. The
// proxies scene (every shape, width mode, penumbra mode and end-cap blend) over a cave at
// giRes 8, so that the window spans many workgroups, under low suns whose shadows cross
// them, towards each quadrant and along an axis, with folded and unfolded proxy shadows on
// tall walls.
TEST_F(GiGpuCompare, SunsSkipOnlyProxiesWhoseShadowsCannotReachAWorkgroup) {
    NamedScene named = proxies_over_a_cave();
    for (auto& p : named.scene.shadow_proxies) p.max_length = 5.0f;
    int suns = 0;
    for (glm::vec3 dir : {glm::vec3(0.7f, -0.35f, 0.4f), glm::vec3(-0.5f, -0.3f, -0.6f), glm::vec3(0.0f, -0.4f, 1.0f)})
        named.scene.directional_lights.push_back({glm::normalize(dir), {0.9f, 0.8f, 0.6f}, 0.5f + 0.2f * float(suns++), 4.0f, 0.3f});
    for (auto unfold : {lantern::scene::ProxyWallShadows::full, lantern::scene::ProxyWallShadows::unfold}) {
        named.scene.gi.proxy_wall_shadows = unfold;
        SCOPED_TRACE(unfold == lantern::scene::ProxyWallShadows::unfold ? "unfolded" : "folded");
        compare_scene(named, Pass::direct, false);
    }
}

TEST_F(GiGpuCompare, RealMapDen312d) {
    auto s = gi_test::map_scene("den312d.map", {32.0f, 40.0f}, 1);
    if (!s) GTEST_SKIP() << "../shared is absent";
    s->scene.gi.probe_rays = 16; // the live probes among a real map's walls
    compare_scene(*s, Pass::lit, true);
}

TEST_F(GiGpuCompare, RealMapLak303d) {
    auto s = gi_test::map_scene("lak303d.map", {100.0f, 100.0f}, 2);
    if (!s) GTEST_SKIP() << "../shared is absent";
    s->scene.gi.probe_rays = 24;
    compare_scene(*s, Pass::lit, true);
}

// The suns' shadow map (gi.sun_shadow_method) on the GPU against the reference's: real maps
// and a checkerboard (rays through tile corners: the close calls the map hands to the DDA),
// a low sun on an exact diagonal and a high one off the axes, both wall heights.
TEST_F(GiGpuCompare, SunShadowMapOnRealMapsAndACheckerboard) {
    std::vector<NamedScene> scenes;
    for (auto [file, center] : {std::pair{"den312d.map", glm::vec2(32.0f, 40.0f)}, std::pair{"lak303d.map", glm::vec2(100.0f, 100.0f)}})
        if (auto s = gi_test::map_scene(file, center, 3)) scenes.push_back(*s);
    {
        std::vector<std::string> rows(16, std::string(16, '.'));
        for (int z = 0; z < 16; ++z)
            for (int x = 0; x < 16; ++x) rows[std::size_t(z)][std::size_t(x)] = (x + z) % 2 ? '#' : '.';
        lantern::scene::Scene s = gi_test::open_scene({8, 8}, {16, 16}, 4);
        s.walls = gi_test::grid_from_rows(rows);
        scenes.push_back({"checkerboard", s});
    }
    for (NamedScene& named : scenes)
        for (float wall_height : {1.0f, 3.0f}) {
            NamedScene s = named;
            s.scene.wall_height = wall_height;
            s.scene.gi.sun_shadow_method = lantern::scene::SunShadowMethod::shadow_map;
            s.scene.directional_lights = {
                {glm::normalize(glm::vec3(-1.0f, -0.3f, -1.0f)), {1.0f, 0.8f, 0.6f}, 0.8f, 4.0f, 0.3f},
                {glm::normalize(glm::vec3(0.35f, -0.9f, -0.2f)), {0.5f, 0.6f, 1.0f}, 0.5f, 4.0f, 0.2f}};
            s.name += " sun map, wall height " + std::to_string(wall_height);
            compare_scene(s, Pass::direct, false);
        }
}

// The point lights' shadow maps (gi.shadow_method = shadow_map) on the GPU against the
// reference tracing every shadow by the DDA: real maps, a checkerboard (rays through tile
// corners) and a cave with a lattice of lights on tile centres, edges and corners, with
// proxies and both proxy-wall modes (every face path of the direct shader).
TEST_F(GiGpuCompare, PointShadowMapsEqualTheDda) {
    std::vector<NamedScene> scenes;
    for (auto [file, center] : {std::pair{"den312d.map", glm::vec2(32.0f, 40.0f)}, std::pair{"lak303d.map", glm::vec2(100.0f, 100.0f)}})
        if (auto s = gi_test::map_scene(file, center, 5)) scenes.push_back(*s);
    {
        std::vector<std::string> rows(16, std::string(16, '.'));
        for (int z = 0; z < 16; ++z)
            for (int x = 0; x < 16; ++x) rows[std::size_t(z)][std::size_t(x)] = (x + z) % 2 ? '#' : '.';
        lantern::scene::Scene s = gi_test::open_scene({8, 8}, {16, 16}, 4);
        s.walls = gi_test::grid_from_rows(rows);
        for (glm::vec2 p : {glm::vec2(4.0f, 4.0f), glm::vec2(7.5f, 8.5f), glm::vec2(11.0f, 6.5f), glm::vec2(9.0001f, 12.0f)})
            s.point_lights.push_back(gi_test::point(p, {1.0f, 0.9f, 0.7f}, 1.0f, 6.0f));
        scenes.push_back({"checkerboard", s});
    }
    {
        lantern::scene::Scene s = gi_test::open_scene({12, 12}, {24, 24}, 8);
        s.walls = gi_test::cave(24, 24, 11u);
        for (float z = 1.0f; z < 24.0f; z += 3.5f)
            for (float x = 1.0f; x < 24.0f; x += 4.25f)
                s.point_lights.push_back(gi_test::point({x, z}, {0.6f, 0.5f, 0.4f}, 0.5f, 5.0f));
        for (glm::vec2 p : {glm::vec2(6.3f, 7.1f), glm::vec2(15.2f, 12.6f)}) {
            lantern::scene::ShadowProxy proxy;
            proxy.position = p;
            s.shadow_proxies.push_back(proxy);
        }
        scenes.push_back({"lattice cave", s});
    }
    for (NamedScene& named : scenes)
        for (auto walls : {lantern::scene::ProxyWallShadows::full, lantern::scene::ProxyWallShadows::unfold}) {
            NamedScene s = named;
            s.scene.gi.shadow_method = lantern::scene::ShadowMethod::shadow_map;
            s.scene.gi.proxy_wall_shadows = walls;
            s.name += walls == lantern::scene::ProxyWallShadows::full ? " point maps" : " point maps, unfolded";
            compare_scene(s, Pass::direct, false, true);
        }
}

TEST_F(GiGpuCompare, HeatScalesAndModes) {
    NamedScene base = gi_test::comparison_scene("rooms");
    for (auto scale : {lantern::scene::HeatScale::full, lantern::scene::HeatScale::half, lantern::scene::HeatScale::quarter})
        for (bool per_channel : {true, false})
            for (float distance : {1.0f, 2.5f}) {
                NamedScene s = base;
                s.scene.gi.heat_scale = scale;
                s.scene.gi.per_channel = per_channel;
                s.scene.gi.diffusion_distance = distance;
                s.scene.gi.range_boost = 0.5f;
                s.name = "rooms scale " + std::to_string(int(scale)) + (per_channel ? " per-channel" : " physical") +
                         " distance " + std::to_string(distance);
                compare_scene(s, Pass::wall_indirect, false);
            }
}

TEST_F(GiGpuCompare, WallIndirectWithBlocksInOneTileAndAcross) {
    // gi_wall_indirect looks a block's tile up once when every block lies in one tile
    // (blocks_in_one_tile). A window snapped to texels at giRes 8 is on that alignment at some
    // origins and off it at others: one of each, against the reference.
    NamedScene base = gi_test::comparison_scene("rooms");
    base.scene.gi.resolution = 8;
    base.scene.gi.window_snap = lantern::scene::WindowSnap::texel;
    base.scene.gi.heat_scale = lantern::scene::HeatScale::full;
    const std::uint32_t block_h = gi_test::shared_renderer(device()).block_h();
    std::optional<NamedScene> on, off;
    for (int sx = 0; sx < 4; ++sx)
        for (int sz = 0; sz < 4; ++sz) {
            NamedScene s = base;
            std::get<lantern::scene::OrthoView>(s.scene.view).center += glm::vec2(0.125f * float(sx), 0.125f * float(sz));
            auto w = compute_window(s.scene.view, s.scene.gi);
            ASSERT_TRUE(w);
            const bool aligned = lantern::gi::blocks_in_one_tile(*w, block_h);
            s.name += aligned ? " blocks in one tile" : " blocks across tiles";
            (aligned ? on : off) = s;
        }
    ASSERT_TRUE(on && off);
    compare_scene(*on, Pass::wall_indirect, false);
    compare_scene(*off, Pass::wall_indirect, false);
}

TEST_F(GiGpuCompare, PhaseLockSubTileMotionIsBitIdentical) {
    // The camera moves by less than a tile without crossing a tile boundary of the window
    // origin: window and every texture stay bit-identical.
    NamedScene a = gi_test::comparison_scene("rooms");
    auto* view = std::get_if<lantern::scene::OrthoView>(&a.scene.view);
    ASSERT_NE(view, nullptr);
    view->center = {12.05f, 10.1f};
    NamedScene b = a;
    std::get<lantern::scene::OrthoView>(b.scene.view).center = {12.85f, 10.7f};
    auto frame = [&](const NamedScene& s) {
        auto w = compute_window(s.scene.view, s.scene.gi);
        EXPECT_TRUE(w);
        FrameInputs in = gather_frame_inputs(s.scene, *w);
        auto r = run_vulkan_frame(gi_test::shared_renderer(device()), in, plan_passes(in, true));
        EXPECT_TRUE(r.ok());
        return std::make_pair(*w, std::move(r.value()));
    };
    auto [wa, ra] = frame(a);
    auto [wb, rb] = frame(b);
    EXPECT_EQ(wa, wb);
    ASSERT_EQ(ra.textures.size(), rb.textures.size());
    for (const auto& [name, t] : ra.textures) EXPECT_EQ(t.texels, rb.textures.at(name).texels) << name;
    EXPECT_EQ(ra.lit->rgb, rb.lit->rgb);
}
