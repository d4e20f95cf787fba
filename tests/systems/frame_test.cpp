// The frame: per-pass caching (an unchanged frame runs nothing; each change reruns exactly
// its passes), pass culling with no textures for passes a scene does not need, determinism
// over worker counts, and profiler lanes.
#include "gpu_test_support.hpp"
#include "test_scenes.hpp"

#include "lantern/gi/baked_light.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/profile/profiler.hpp"
#include "lantern/systems/scene_world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <set>

using namespace lantern;
using gi::Pass;
using gi::PassSet;

namespace {

jobs::JobSystem::Config workers(int n) {
    jobs::JobSystem::Config c;
    c.worker_threads = n;
    return c;
}

PassSet set_of(std::initializer_list<Pass> passes) {
    PassSet s;
    for (Pass p : passes) s.add(p);
    return s;
}

std::string names(PassSet s) {
    std::string out;
    for (int p = 0; p < gi::registered_pass_count(); ++p)
        if (s.has(Pass(p))) out += std::string(out.empty() ? "" : " ") + gi::pass_name(Pass(p));
    return out.empty() ? "(none)" : out;
}

// A rooms scene with a sun and a proxy: every pass has work.
scene::Scene full_scene() {
    scene::Scene s = gi_test::comparison_scenes()[1].scene;
    s.directional_lights.push_back({glm::normalize(glm::vec3(0.5f, -0.6f, 0.3f)), {1.0f, 0.9f, 0.8f}, 0.8f, 3.0f, 0.4f});
    scene::ShadowProxy tree;
    tree.position = {7.5f, 14.5f};
    s.shadow_proxies.push_back(tree);
    return s;
}

struct Harness {
    jobs::JobSystem jobs;
    ecs::World world;
    systems::SceneWorld sw;
    std::unique_ptr<gi::vk::Renderer> renderer;
    std::unique_ptr<systems::GiFrame> frame;

    Harness(const scene::Scene& s, int worker_count, gpu::Device* device, systems::GiFrameOptions options = {})
        : jobs(workers(worker_count)) {
        sw = systems::populate_world(s, world);
        std::unique_ptr<gi::Backend> backend;
        if (device) {
            renderer = std::move(gi::vk::Renderer::create(*device).value());
            backend = gi::make_vulkan_backend(*renderer);
        } else {
            backend = gi::make_reference_backend(nullptr);
        }
        frame = std::make_unique<systems::GiFrame>(world, jobs, sw.source, std::move(backend), sw.config, std::move(options));
        frame->warm_up();
    }
    ~Harness() {
        frame.reset(); // the backend waits for the GPU before the renderer goes
    }
    PassSet step() { return frame->step().ran; }
};

} // namespace

class FrameCaching : public ::testing::TestWithParam<bool> {
  protected:
    void SetUp() override {
        if (GetParam() && !test::shared_gpu_device()) LANTERN_SKIP_NO_GPU("no Vulkan device");
    }
    gpu::Device* device() { return GetParam() ? test::shared_gpu_device() : nullptr; }
};

TEST_P(FrameCaching, EachChangeRerunsExactlyItsPasses) {
    gpu::Device* d = device();
    Harness h(full_scene(), 1, d);
    ecs::World& w = h.world;
    const PassSet all = set_of({Pass::conduction, Pass::ao, Pass::direct, Pass::directional, Pass::emission, Pass::heat,
                                Pass::blur, Pass::wall_indirect, Pass::probes});
    // The live probes (rooms sets gi.probe_rays) read the wall textures: they follow every
    // pass that writes those.
    // The suns have textures of their own, which the direct pass adds: a point light's
    // change leaves the directional pass out, a sun's reruns the direct pass.
    const PassSet from_direct = set_of({Pass::direct, Pass::emission, Pass::heat, Pass::blur,
                                        Pass::wall_indirect, Pass::probes});
    const PassSet from_sun = set_of({Pass::directional, Pass::direct, Pass::emission, Pass::heat, Pass::blur,
                                     Pass::wall_indirect, Pass::probes});
    EXPECT_EQ(names(h.step()), names(all)) << "first frame";
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "unchanged frame";
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "still unchanged";

    w.patch<PointLight>(h.sw.point_lights[0]).position.x += 0.5f;
    EXPECT_EQ(names(h.step()), names(from_direct)) << "a light moved";
    w.patch<EmissiveLight>(h.sw.emissive_lights[0]).intensity *= 1.5f;
    EXPECT_EQ(names(h.step()), names(from_direct)) << "an emissive changed";
    w.patch<DirectionalLight>(h.sw.directional_lights[0]).direction.x += 0.1f;
    EXPECT_EQ(names(h.step()), names(from_sun)) << "the sun moved";
    w.patch<ShadowProxy>(h.sw.proxies[0]).shape.position.x += 1.0f;
    EXPECT_EQ(names(h.step()), names(from_sun)) << "a proxy moved (it shadows the sun too)";
    const glm::ivec2 tile(3, 3);
    h.frame->streaming().set_wall(w, tile, !h.frame->streaming().is_wall(tile));
    EXPECT_EQ(names(h.step()), names(all)) << "a wall was edited";
    h.frame->config().settings.ao.strength = 0.3f;
    EXPECT_EQ(names(h.step()), names(set_of({Pass::ao}))) << "AO settings";
    h.frame->config().settings.heat_rounds = 12;
    EXPECT_EQ(names(h.step()), names(set_of({Pass::heat, Pass::blur, Pass::wall_indirect, Pass::probes}))) << "heat settings";
    auto& view = std::get<scene::OrthoView>(w.patch<Camera>(h.sw.camera).view);
    view.center.x += 0.3f; // rooms: window origin at a whole tile; 0.3 stays within it
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "sub-tile camera motion (phase lock)";
    view.center.x += 1.0f;
    EXPECT_EQ(names(h.step()), names(all)) << "camera moved a tile";
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "unchanged again";
}

// Seed 004's pulsing emission through the frame systems: with a bake that has a pulsing part
// (systems::BakedGi::light), a new pulse (BakedGi::pulse) reruns the baked pass and what it
// adds to in place (a colour-only update: the atlas is not read again, nothing else reruns);
// the same pulse reruns nothing; a steady bake ignores the pulse.
TEST_P(FrameCaching, ANewPulseRerunsTheBakedRows) {
    Harness h(full_scene(), 1, device());
    auto window = gi::compute_window(full_scene().view, full_scene().gi);
    ASSERT_TRUE(window);
    const glm::ivec2 origin(int(std::floor(window->view.min_x)) - 1, int(std::floor(window->view.min_z)) - 1);
    const int w = int(window->view.width) + 2, hgt = int(window->view.height) + 2;
    auto bake = [&](bool pulsing, std::uint64_t key) {
        std::vector<gi::Field> layers(std::size_t(gi::baked_layers * (pulsing ? 2 : 1)), gi::Field(w, hgt));
        for (std::size_t l = 0; l < layers.size(); ++l) {
            std::fill(layers[l].air.begin(), layers[l].air.end(), std::uint8_t(1));
            std::fill(layers[l].rgb.begin(), layers[l].rgb.end(), 0.1f * float(l + 1));
        }
        return std::make_shared<const gi::BakedLight>(gi::make_baked_light(origin, 1, layers, 0.01f, key));
    };
    systems::BakedGi& baked = h.world.resource<systems::BakedGi>();
    baked.light = bake(true, 77);
    baked.pulse = 0.25f;
    const PassSet first = h.step();
    EXPECT_TRUE(first.has(Pass::baked_sample)) << names(first);
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "the same pulse";
    baked.pulse = 0.5f;
    const PassSet pulsed = h.step();
    EXPECT_TRUE(pulsed.has(Pass::baked)) << names(pulsed);
    EXPECT_FALSE(pulsed.has(Pass::baked_sample) || pulsed.has(Pass::ao) || pulsed.has(Pass::conduction)) << names(pulsed);
    baked.light = bake(false, 78);
    h.step();
    baked.pulse = 0.75f;
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "a steady bake ignores the pulse";
}

// Seed 003's radiosity in the frame: it refines for gi.radiosity.frames frames, then a still
// scene submits nothing; a light move reruns it (history kept), a wall edit reruns the
// distance field too. The CPU distance field for game code follows the walls.
TEST_P(FrameCaching, RadiosityConvergesThenStopsAndTheWallDistanceFollowsTheWalls) {
    scene::Scene s = full_scene();
    s.gi.method = scene::GiMethod::radiosity;
    s.gi.radiosity.frames = 4;
    Harness h(s, 1, device());
    ecs::World& w = h.world;
    const PassSet all = set_of({Pass::conduction, Pass::ao, Pass::direct, Pass::directional, Pass::emission,
                                Pass::distance_field, Pass::radiosity, Pass::blur, Pass::wall_indirect, Pass::probes});
    const PassSet refine = set_of({Pass::radiosity, Pass::blur, Pass::wall_indirect, Pass::probes});
    EXPECT_EQ(names(h.step()), names(all)) << "first frame";
    for (int f = 1; f < 4; ++f) EXPECT_EQ(names(h.step()), names(refine)) << "refining, frame " << f;
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "converged: a still scene submits nothing";
    const auto& distance = w.resource<systems::WallDistanceField>();
    EXPECT_EQ(distance.builds, 1u);
    const glm::vec2 open_tile(4.5f, 4.5f); // rooms: floor, the wall row at z = 10 is 5.5 away
    const float before = distance.field.distance(open_tile);
    EXPECT_GT(before, 1.0f);
    w.patch<PointLight>(h.sw.point_lights[0]).position.x += 0.5f;
    EXPECT_EQ(names(h.step()), names(set_of({Pass::direct, Pass::emission, Pass::radiosity, Pass::blur,
                                             Pass::wall_indirect, Pass::probes})))
        << "a light moved: the distance field is kept";
    EXPECT_EQ(distance.builds, 1u);
    h.frame->streaming().set_wall(w, {4, 5}, true);
    EXPECT_EQ(names(h.step()), names(all)) << "a wall was edited";
    EXPECT_EQ(distance.builds, 2u);
    EXPECT_EQ(distance.field.distance({4.5f, 5.5f}), 0.0f) << "inside the new wall";
    EXPECT_LT(distance.field.distance(open_tile), before);
    EXPECT_FLOAT_EQ(distance.field.distance(open_tile), 1.0f) << "the new wall is the next tile along +z";
    EXPECT_GT(distance.field.direction(open_tile).y, 0.99f) << "towards the new wall";
}

// The gather method (physical): its bounces refine for gi.gather.frames frames, then a still
// scene submits nothing; a light move reruns it with its history kept.
TEST_P(FrameCaching, GatherConvergesThenStops) {
    scene::Scene s = full_scene();
    s.gi.method = scene::GiMethod::gather;
    s.gi.gather.frames = 3;
    Harness h(s, 1, device());
    const PassSet all = set_of({Pass::conduction, Pass::ao, Pass::direct, Pass::directional, Pass::gather, Pass::blur,
                                Pass::probes});
    const PassSet refine = set_of({Pass::gather, Pass::blur, Pass::probes});
    EXPECT_EQ(names(h.step()), names(all)) << "first frame";
    for (int f = 1; f < 3; ++f) EXPECT_EQ(names(h.step()), names(refine)) << "refining, frame " << f;
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "converged: a still scene submits nothing";
    h.world.patch<PointLight>(h.sw.point_lights[0]).position.x += 0.5f;
    EXPECT_EQ(names(h.step()), names(set_of({Pass::direct, Pass::gather, Pass::blur, Pass::probes})))
        << "a light moved";
    EXPECT_GT(h.world.resource<systems::FramePasses>().plan.history[int(Pass::gather)], 0) << "history kept";
}

// The HUD's bounce stepper (GiConfig::converge): held, the radiosity does not refine; each
// step runs it once more with one more frame of history (one more bounce); a restart runs it
// afresh (history 0) even though nothing changed; released, it refines on to convergence.
TEST_P(FrameCaching, RadiosityBouncesStepFrameByFrame) {
    scene::Scene s = full_scene();
    s.gi.method = scene::GiMethod::radiosity;
    s.gi.radiosity.frames = 6;
    Harness h(s, 1, device());
    systems::ConvergeControl& control = h.frame->config().converge;
    control.hold = true;
    const PassSet refine = set_of({Pass::radiosity, Pass::blur, Pass::wall_indirect, Pass::probes});
    const auto history = [&] { return h.world.resource<systems::FramePasses>().plan.history[int(Pass::radiosity)]; };
    EXPECT_TRUE(h.step().has(Pass::radiosity)) << "first frame";
    EXPECT_EQ(history(), 0);
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "held: no second bounce";
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "still held";
    ++control.steps;
    EXPECT_EQ(names(h.step()), names(refine)) << "one step";
    EXPECT_EQ(history(), 1) << "the second bounce reads the first";
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "held after the step";
    control.steps += 2; // two steps: one a frame
    EXPECT_EQ(names(h.step()), names(refine));
    EXPECT_EQ(history(), 2);
    EXPECT_EQ(names(h.step()), names(refine));
    EXPECT_EQ(history(), 3);
    EXPECT_EQ(names(h.step()), names(PassSet{}));
    ++control.restarts;
    EXPECT_EQ(names(h.step()), names(refine)) << "restart: afresh although nothing changed";
    EXPECT_EQ(history(), 0);
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "held after the restart";
    control.hold = false;
    for (int f = 1; f < 6; ++f) {
        EXPECT_EQ(names(h.step()), names(refine)) << "released, frame " << f;
        EXPECT_EQ(history(), f);
    }
    EXPECT_EQ(names(h.step()), names(PassSet{})) << "converged";
}

TEST_P(FrameCaching, ScenesLeaveOutWhatTheyDoNotNeed) {
    gpu::Device* d = device();
    scene::Scene s = gi_test::comparison_scenes()[1].scene; // no proxies
    // A sun that has set (black): it adds nothing, so it is left out like no sun at all.
    s.directional_lights.push_back({glm::normalize(glm::vec3(0.5f, -0.6f, 0.3f)), {1.0f, 0.9f, 0.8f}, 0.0f, 3.0f, 0.4f});
    s.gi.ao.enabled = false;
    s.gi.blur = false;
    Harness h(s, 1, d);
    const systems::FrameReport first = h.frame->step();
    for (Pass p : {Pass::directional, Pass::ao, Pass::blur}) {
        EXPECT_FALSE(first.ran.has(p)) << gi::pass_name(p);
        EXPECT_EQ(first.reason[std::size_t(p)].rfind("not needed", 0), 0u) << first.reason[std::size_t(p)];
    }
    const auto names_allocated = h.frame->backend().texture_names();
    EXPECT_EQ(std::count(names_allocated.begin(), names_allocated.end(), "ao"), 0);
    if (h.renderer) {
        using gi::vk::Tex;
        for (Tex t : {Tex::ao, Tex::blur_temp, Tex::direct_sun, Tex::shadow_sun, Tex::wall_direct_sun_px})
            EXPECT_FALSE(h.renderer->has(t)) << gi::vk::tex_name(t);
        EXPECT_TRUE(h.renderer->has(Tex::indirect));
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, FrameCaching, ::testing::Values(false, true),
                         [](const auto& p) { return p.param ? "vulkan" : "reference"; });

namespace {

// Runs scripted frames and returns every texture of the last one.
// With `warm_up_shaders`, the shader warm-up's frames run before the first
// (systems::GiFrameOptions); `direct_workgroups` gets the direct pass's recorded workgroups.
std::map<std::string, std::vector<float>> run_scripted(int worker_count, gpu::Device* device, bool warm_up_shaders = false,
                                                       std::uint64_t* direct_workgroups = nullptr,
                                                       const scene::Scene& scene = full_scene()) {
    systems::GiFrameOptions options;
    options.warm_up_shaders = warm_up_shaders;
    Harness h(scene, worker_count, device, std::move(options));
    ecs::World& w = h.world;
    for (int k = 0; k < 6; ++k) {
        if (k == 1) w.patch<PointLight>(h.sw.point_lights[0]).position += glm::vec2(0.7f, -0.3f);
        if (k == 2) h.frame->streaming().set_wall(w, {5, 5}, true);
        if (k == 4 && !h.sw.directional_lights.empty()) w.patch<DirectionalLight>(h.sw.directional_lights[0]).direction.z -= 0.2f;
        h.step();
    }
    std::map<std::string, std::vector<float>> out;
    for (const std::string& name : h.frame->backend().texture_names()) out[name] = h.frame->backend().read(name)->texels;
    if (direct_workgroups && h.renderer) *direct_workgroups = h.renderer->partial_work(Pass::direct).recorded;
    return out;
}

} // namespace

TEST(FrameDeterminism, SameTexturesForZeroOneAndTwoWorkers) {
    auto reference = run_scripted(0, nullptr);
    EXPECT_EQ(run_scripted(1, nullptr), reference);
    EXPECT_EQ(run_scripted(2, nullptr), reference);
    gpu::Device* d = test::shared_gpu_device();
    if (!d) LANTERN_SKIP_NO_GPU("no Vulkan device: reference backend checked only");
    auto vk0 = run_scripted(0, d);
    EXPECT_EQ(run_scripted(1, d), vk0);
    EXPECT_EQ(run_scripted(2, d), vk0);
}

// The shader warm-up (GiFrameOptions::warm_up_shaders: a frame with what the scene lacks of
// a sun, a light and a proxy added, recorded before the first) leaves no trace: the scripted
// frames (a light moved, a wall set, the sun turned) end with the same textures, bit for bit,
// where the scene has all three (the first frame may keep the warm-up's light bins) and where
// it has no sun and no proxy (the warm-up's frame differs from the first).
TEST(FrameDeterminism, TheShaderWarmUpLeavesNoTrace) {
    scene::Scene bare = full_scene();
    bare.directional_lights.clear();
    bare.shadow_proxies.clear();
    for (const scene::Scene& s : {full_scene(), bare})
        EXPECT_EQ(run_scripted(1, nullptr, true, nullptr, s), run_scripted(1, nullptr, false, nullptr, s));
    gpu::Device* d = test::shared_gpu_device();
    if (!d) LANTERN_SKIP_NO_GPU("no Vulkan device: reference backend checked only");
    EXPECT_EQ(run_scripted(1, d, true, nullptr, full_scene()), run_scripted(1, d, false, nullptr, full_scene()));
    std::uint64_t plain = 0, warmed = 0;
    const auto without = run_scripted(1, d, false, &plain, bare);
    EXPECT_EQ(run_scripted(1, d, true, &warmed, bare), without);
    EXPECT_GT(warmed, plain) << "the warm-up recorded no frame";
}

TEST(FrameProfiling, SystemsOnWorkerLanesAndPassesOnTheGpuLane) {
    gpu::Device* d = test::shared_gpu_device();
    if (!d) LANTERN_SKIP_NO_GPU("no Vulkan device");
    profile::reset();
    profile::set_enabled(true);
    {
        Harness h(full_scene(), 1, d);
        for (int k = 0; k < 4; ++k) {
            h.world.patch<PointLight>(h.sw.point_lights[0]).position.x += 0.25f;
            profile::begin_frame();
            h.step();
            profile::end_frame();
        }
        h.frame->backend().wait_idle();
        profile::begin_frame();
        h.step(); // collects the remaining GPU timestamps
        profile::end_frame();
    }
    profile::set_enabled(false);
    std::set<std::string> systems_seen, passes_seen;
    for (const profile::Frame* f : profile::history())
        for (const profile::Event& e : f->events) {
            if (e.kind == profile::EventKind::gpu) passes_seen.insert(e.name);
            else systems_seen.insert(e.name);
        }
    for (const char* s : {"camera_view", "streaming", "light_gather", "proxy_gather", "cache_keys", "gpu_submit"})
        EXPECT_TRUE(systems_seen.count(s)) << s;
    for (const char* p : {"conduction", "direct", "directional", "heat"}) EXPECT_TRUE(passes_seen.count(p)) << p;
    profile::reset();
}

// One road from lights to the GPU: a scene loaded into the world and gathered by the game's
// systems gives the frame exactly the lights, suns and proxies gi::gather_frame_inputs (the
// tools' and tests' path) gives it, on every comparison scene, with caps that bite and a
// dark sun that both leave out.
TEST(OneInputPath, GameSystemsGatherWhatTheScenePathGathers) {
    std::vector<gi_test::NamedScene> scenes = gi_test::comparison_scenes();
    scene::Scene capped = full_scene();
    capped.gi.max_lights = 1;
    capped.gi.max_shadow_proxies = 0;
    capped.directional_lights.push_back({glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(1.0f), 0.0f, 3.0f, 0.5f}); // dark
    scenes.push_back({"full, capped, dark sun", capped});
    for (const gi_test::NamedScene& named : scenes) {
        Harness h(named.scene, 0, nullptr);
        h.step();
        const systems::FramePasses& f = h.world.resource<systems::FramePasses>();
        auto window = gi::compute_window(named.scene.view, named.scene.gi);
        ASSERT_TRUE(window) << named.name;
        const gi::FrameInputs expected = gi::gather_frame_inputs(named.scene, *window);
        auto bytes = [](const auto& v) {
            return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0]));
        };
        EXPECT_EQ(f.inputs.window, expected.window) << named.name;
        EXPECT_EQ(bytes(f.inputs.point_lights), bytes(expected.point_lights)) << named.name;
        EXPECT_EQ(bytes(f.inputs.emissive_lights), bytes(expected.emissive_lights)) << named.name;
        EXPECT_EQ(bytes(f.inputs.directional_lights), bytes(expected.directional_lights)) << named.name;
        EXPECT_EQ(bytes(f.inputs.proxies), bytes(expected.proxies)) << named.name;
        EXPECT_EQ(f.plan.run, gi::plan_passes(expected, h.world.resource<systems::GiConfig>().lit_image).run) << named.name;
    }
    // The capped scene really was capped, and its dark sun left out.
    const auto window = gi::compute_window(capped.view, capped.gi);
    const gi::FrameInputs in = gi::gather_frame_inputs(capped, *window);
    EXPECT_EQ(in.point_lights.size(), 1u);
    EXPECT_TRUE(in.proxies.empty());
    EXPECT_EQ(in.directional_lights.size(), 1u);
}
