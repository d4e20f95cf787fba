// The baked row (docs/baked.md, "At run time"): the bake's brick atlas added to the indirect
// textures. On the reference it adds the atlas's light at every open texel and exposed face
// and nothing elsewhere; on Vulkan (hardware bilinear filtering of the RGBM atlas) it equals
// the reference within the sampler's precision, for every method, resolutions that sample
// between probes, a bake covering part of the window, and frames with nothing else lit.
#include "gi_compare.hpp"
#include "test_scenes.hpp"

#include "gpu_test_support.hpp"
#include "lantern/gi/baked_light.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/reference.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/scene/day.hpp"
#include "shared_renderer.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

using namespace lantern::gi;
using gi_test::inputs_of;
using gi_test::synthetic_bake;
using lantern::scene::Scene;

namespace {

glm::vec3 load_rgb(const Texture& t, int x, int y) {
    const float* v = t.at(x, y);
    return {v[0], v[1], v[2]};
}

ReferenceStore reference_frame(const FrameInputs& in) {
    PassPlan plan = plan_passes(in, true);
    derive_keys(in, plan, input_keys_of(in), nullptr);
    ReferenceStore store;
    execute_reference(in, plan, plan.run, {}, store);
    return store;
}

// The sampler's precision. Between probes a GPU filters the RGBM texels and returns the
// result in the texture's own 8 bits (lavapipe does), so rgb and m each come back within
// half a step of 1/255 of the reference's float bilinear: the light rgb x m x 8 within
// 8 x (m + rgb) / 510, at most (texel max + 8) / 255 with m = max / 8 and rgb <= 1. On the
// probes themselves (weights 0 and 1) nothing is filtered: equal within half rounding.
float allowed_difference(float ref, float texel_max, bool filtered) {
    const float ulps = 4.0f * std::max(std::abs(ref) * std::ldexp(1.0f, -10), std::ldexp(1.0f, -24));
    return ulps + (filtered ? (texel_max + rgbm_range) / 255.0f : 0.0f);
}

} // namespace

// With the window's texels on the baked grid's texel centres (same resolution, whole tiles)
// and every brick at level 0 (eps 0), the row adds the baked field itself (up to RGBM's
// rounding) at open texels and exposed faces, and nothing at walls or hidden faces.
TEST(BakedReference, AddsTheBakedLightAtOpenTexelsAndExposedFaces) {
    Scene s = gi_test::comparison_scene("rooms").scene;
    s.gi.resolution = 4;
    FrameInputs in = inputs_of(s);
    const ReferenceStore without = reference_frame(in);
    const glm::ivec2 origin(int(std::floor(in.window.view.min_x)), int(std::floor(in.window.view.min_z)));
    in.baked = synthetic_bake(in.walls, origin, glm::ivec2(int(in.window.view.width), int(in.window.view.height)), 4, 0.0f, 1);
    const ReferenceStore with = reference_frame(in);
    ASSERT_TRUE(with.find(Tex::indirect));
    const GiWindow& w = in.window;
    int open = 0, faces = 0;
    for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            const glm::ivec2 cell(int(std::floor(p.x)), int(std::floor(p.y)));
            const bool wall = in.walls.is_wall(cell.x, cell.y);
            const glm::vec3 added = (load_rgb(with.at(Tex::indirect), x, y)) -
                                    (load_rgb(without.at(Tex::indirect), x, y));
            if (!wall) {
                const glm::vec3 want = in.baked->sample(0, p);
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(added[c], want[c], 0.004f * (1.0f + want[c])) << x << ", " << y;
                ++open;
            } else {
                EXPECT_EQ(added, glm::vec3(0.0f));
            }
            const glm::vec4 mask = wall ? wall_face_mask(in.walls, cell) : glm::vec4(0.0f);
            for (int f = 0; f < 4; ++f) {
                const Tex t = Tex(int(Tex::wall_indirect_px) + f);
                const glm::vec3 face_added = (load_rgb(with.at(t), x, y)) - (load_rgb(without.at(t), x, y));
                if (mask[f] > 0.0f) {
                    const glm::vec3 want = in.baked->sample(1 + f, p);
                    for (int c = 0; c < 3; ++c) ASSERT_NEAR(face_added[c], want[c], 0.004f * (1.0f + want[c]));
                    ++faces;
                } else {
                    EXPECT_EQ(face_added, glm::vec3(0.0f)) << "face " << f << " at " << x << ", " << y;
                }
            }
        }
    EXPECT_GT(open, 1000);
    EXPECT_GT(faces, 200);
}

namespace {

class Baked : public lantern::test::GpuTest {
  protected:
    // One frame on both backends: every texture equal; the ones the baked row adds to within
    // the sampler's precision (`filtered`: the window samples between the bake's probes).
    void compare(const std::string& name, const FrameInputs& in, bool filtered) {
        const ReferenceStore store = reference_frame(in);
        PassPlan plan = plan_passes(in, true);
        ASSERT_TRUE(plan.run.has(Pass::baked)) << name << ": " << plan.reason[int(Pass::baked)];
        auto gpu = run_vulkan_frame(gi_test::shared_renderer(device()), in, plan);
        ASSERT_TRUE(gpu.ok()) << gpu.error().message;
        int compared = 0;
        for (int t = 0; t < registered_texture_count(); ++t) {
            const Texture* ref = store.find(Tex(t));
            if (!ref || texture_row(Tex(t)).internal) continue;
            const std::string tex = tex_name(Tex(t));
            auto it = gpu->textures.find(tex);
            ASSERT_NE(it, gpu->textures.end()) << name << ": GPU did not produce " << tex;
            const Texture& g = it->second;
            const bool sampled = tex == "indirect" || tex == "baked_view" || tex.rfind("wall_indirect", 0) == 0;
            if (!sampled) {
                if (tex == "lit") continue; // follows from the others (1/255 steps near the sampler's precision)
                auto diff = gi_test::compare_textures(g, *ref, 4.0f);
                EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe(name + " " + tex, diff);
                ++compared;
                continue;
            }
            std::size_t bad = 0;
            float worst = 0.0f;
            double err2 = 0.0, ref2 = 0.0;
            for (int y = 0; y < ref->height; ++y)
                for (int x = 0; x < ref->width; ++x) {
                    const float* r = ref->at(x, y);
                    const float m = std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2])});
                    if (tex == "baked_view" && g.at(x, y)[3] != r[3]) {
                        ADD_FAILURE() << name << " baked_view: the brick level at (" << x << ", " << y << ") is "
                                      << g.at(x, y)[3] - 1 << ", the reference's " << r[3] - 1;
                        return;
                    }
                    for (int c = 0; c < 3; ++c) {
                        const float d = g.at(x, y)[c] - r[c];
                        err2 += double(d) * double(d);
                        ref2 += double(r[c]) * double(r[c]);
                        if (!(std::abs(d) <= allowed_difference(r[c], m, filtered))) {
                            if (bad == 0)
                                ADD_FAILURE() << name << " " << tex << " first at (" << x << ", " << y << ") channel " << c
                                              << ": gpu " << g.at(x, y)[c] << " reference " << r[c];
                            ++bad;
                            worst = std::max(worst, std::abs(d) / std::max(m, 1e-6f));
                        }
                    }
                }
            EXPECT_EQ(bad, 0u) << name << " " << tex << ": worst relative difference " << worst;
            if (tex == "indirect")
                std::printf("%s: indirect, GPU against the reference: relative RMS %.3f %%\n", name.c_str(),
                            100.0 * std::sqrt(err2 / std::max(ref2, 1e-30)));
            ++compared;
        }
        EXPECT_GT(compared, 4) << name;
    }
};

} // namespace

TEST_F(Baked, VulkanEqualsTheReference) {
    struct Case {
        const char* name;
        lantern::scene::GiMethod method;
        int resolution, bake_resolution;
        float eps;
        bool part; // the bake covers only part of the window
        void (*apply)(Scene&);
    };
    using lantern::scene::GiMethod;
    const Case cases[] = {
        {"heat, bake at the window's resolution", GiMethod::heat, 4, 4, 0.0f, false, [](Scene&) {}},
        {"gather, coarse bricks", GiMethod::gather, 4, 4, 0.05f, false, [](Scene&) {}},
        {"radiosity, resolution 3 against a bake at 4", GiMethod::radiosity, 3, 4, 0.01f, false, [](Scene&) {}},
        {"heat, resolution 8 against a bake at 2, part of the window", GiMethod::heat, 8, 2, 0.01f, true,
         [](Scene&) {}},
        {"texel snap, two faces", GiMethod::heat, 4, 4, 0.01f, true,
         [](Scene& s) {
             s.gi.window_snap = lantern::scene::WindowSnap::texel;
             s.gi.wall_faces.px = false, s.gi.wall_faces.nz = false;
         }},
        {"wall lighting off", GiMethod::heat, 4, 4, 0.01f, false, [](Scene& s) { s.gi.wall_lighting = false; }},
        {"no lights: the baked light alone", GiMethod::gather, 4, 4, 0.01f, false, [](Scene& s) {
             s.point_lights.clear();
             s.emissive_lights.clear();
             s.directional_lights.clear();
         }},
    };
    std::uint64_t key = 100; // a bake's key names its contents: the renderer uploads each once
    for (const Case& c : cases) {
        Scene s = gi_test::comparison_scene("rooms").scene;
        s.gi.method = c.method;
        s.gi.resolution = c.resolution;
        c.apply(s);
        FrameInputs in = inputs_of(s);
        glm::ivec2 origin(int(std::floor(in.window.view.min_x)) - 3, int(std::floor(in.window.view.min_z)) - 2);
        glm::ivec2 tiles(int(in.window.view.width) + 6, int(in.window.view.height) + 4);
        if (c.part) origin += glm::ivec2(7, 5), tiles /= 2;
        in.baked = synthetic_bake(in.walls, origin, tiles, c.bake_resolution, c.eps, key++);
        compare(c.name, in, c.eps > 0.0f || c.resolution != c.bake_resolution);
    }
}

// Seed 004's pulsing emission at run time: a bake with a pulsing part adds it scaled by the
// frame's pulse (FrameInputs::baked_pulse), on Vulkan as in the reference. The sampling row
// keeps the pulsing part in textures of its own, so a new pulse reruns the baked pass's adds
// and reads no atlas; at pulse 0 the frame is the steady part's.
TEST_F(Baked, APulsingPartIsAddedScaledByTheFramesPulse) {
    Scene s = gi_test::comparison_scene("rooms").scene;
    s.gi.method = lantern::scene::GiMethod::gather;
    FrameInputs in = inputs_of(s);
    const glm::ivec2 origin(int(std::floor(in.window.view.min_x)) - 3, int(std::floor(in.window.view.min_z)) - 2);
    const glm::ivec2 tiles(int(in.window.view.width) + 6, int(in.window.view.height) + 4);
    in.baked = synthetic_bake(in.walls, origin, tiles, 4, 0.01f, 900, true);
    ASSERT_TRUE(in.baked->pulsing);
    std::uint64_t last_key = 0;
    const std::uint64_t sample_key = lantern::gi::input_keys_of(in).baked;
    for (float pulse : {0.0f, 0.37f, 1.0f}) {
        in.baked_pulse = pulse;
        const lantern::gi::InputKeys keys = lantern::gi::input_keys_of(in);
        EXPECT_NE(keys.baked_pulse, last_key) << "a new pulse reruns the baked pass";
        EXPECT_EQ(keys.baked, sample_key) << "a new pulse reads no atlas";
        last_key = keys.baked_pulse;
        compare("pulsing part at " + std::to_string(pulse), in, true);
    }
    {
        in.baked_pulse = 0.5f;
        PassPlan plan = plan_passes(in, false);
        const auto a = lantern::gi::derive_keys(in, plan, lantern::gi::input_keys_of(in));
        in.baked_pulse = 0.6f;
        const auto b = lantern::gi::derive_keys(in, plan, lantern::gi::input_keys_of(in));
        EXPECT_EQ(a[int(Pass::baked_sample)], b[int(Pass::baked_sample)]);
        EXPECT_NE(a[int(Pass::baked)], b[int(Pass::baked)]);
    }
    // The reference: the sampling row's steady texture is the steady layers' light alone and
    // its pulsing texture the pulsing layers' (sampled from the same bricks) at any pulse; the
    // ground's indirect light at 0.37 is that at 0 plus 0.37 of the pulsing texture.
    auto reference = [&](const FrameInputs& f) {
        lantern::gi::PassPlan plan = lantern::gi::plan_passes(f, false);
        lantern::gi::ReferenceStore store;
        lantern::gi::execute_reference(f, plan, plan.run, {}, store);
        return store;
    };
    in.baked_pulse = 0.0f;
    const ReferenceStore at0 = reference(in);
    in.baked_pulse = 0.37f;
    const ReferenceStore at37 = reference(in);
    const lantern::gi::Texture& steady = at37.at(lantern::gi::Tex::baked_ground);
    const lantern::gi::Texture& pulsing = at37.at(lantern::gi::Tex::baked_pulse_ground);
    int checked = 0;
    for (int y = 0; y < in.window.height; y += 7)
        for (int x = 0; x < in.window.width; x += 7) {
            const glm::vec2 p = in.window.texel_center(x, y);
            if (in.walls.is_wall(int(std::floor(p.x)), int(std::floor(p.y)))) continue;
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(steady.at(x, y)[c], in.baked->sample(0, p)[c], 2e-3f);
                EXPECT_NEAR(pulsing.at(x, y)[c], in.baked->sample(lantern::gi::baked_layers, p)[c], 2e-3f);
                const float before = at0.at(lantern::gi::Tex::indirect).at(x, y)[c];
                const float after = at37.at(lantern::gi::Tex::indirect).at(x, y)[c];
                EXPECT_NEAR(after - before, 0.37f * pulsing.at(x, y)[c], 2e-3f * std::max(1.0f, after));
            }
            ++checked;
        }
    EXPECT_GT(checked, 20);
    // A steady bake's keys do not follow the pulse.
    in.baked = synthetic_bake(in.walls, origin, tiles, 4, 0.01f, 901);
    in.baked_pulse = 0.2f;
    const lantern::gi::InputKeys steady_keys = lantern::gi::input_keys_of(in);
    in.baked_pulse = 0.9f;
    EXPECT_EQ(lantern::gi::input_keys_of(in).baked, steady_keys.baked);
    EXPECT_EQ(lantern::gi::input_keys_of(in).baked_pulse, steady_keys.baked_pulse);
}

// An open window (no wall in it): the faces' producer is left out, so the baked row writes
// the ground's texture over the method's and its faces (zero) itself.
TEST_F(Baked, AWindowWithoutWallsMatchesTheReference) {
    Scene s = gi_test::open_scene({16, 12}, {24, 16}, 4);
    s.point_lights = {{{16.0f, 12.0f}, 1.0f, {1.0f, 0.8f, 0.6f}, 1.0f, 6.0f}};
    FrameInputs in = inputs_of(s);
    in.baked = synthetic_bake(in.walls, {0, 0}, {40, 30}, 4, 0.01f, 2);
    compare("open window", in, true);
}

namespace {

// The rooms with a shadow proxy whose shadows are unfolded on the faces, lit by `method`.
Scene rooms_with_unfolded_proxy(lantern::scene::GiMethod method) {
    Scene s = gi_test::comparison_scene("rooms").scene;
    s.gi.method = method;
    s.gi.proxy_wall_shadows = lantern::scene::ProxyWallShadows::unfold;
    lantern::scene::ShadowProxy proxy;
    proxy.position = {6.5f, 6.5f};
    proxy.size = {0.4f, 0.4f};
    s.shadow_proxies.push_back(proxy);
    return s;
}

// An empty bake (it holds the mixed lights' bounce, here nothing): the frame's own passes alone.
std::shared_ptr<const BakedLight> empty_bake() {
    std::array<Field, baked_layers> empty;
    for (Field& f : empty) f = Field(8, 8);
    return std::make_shared<const BakedLight>(make_baked_light(glm::ivec2(-100), 1, empty, 0.01f, 7));
}

// The frame with a mixed light (`mixed`, split for a bake) against the same scene all
// realtime and against the scene without that light: the same direct light (ground, every
// face, the upper faces: the same light summed in another order, within a few half ulps), and
// the live bounce of the frame without it, bit for bit.
void expect_lit_directly_and_left_out_of_the_bounce(const Scene& all_realtime, const FrameInputs& mixed,
                                                     const Scene& without, const std::string& what) {
    const ReferenceStore a = reference_frame(inputs_of(all_realtime)), b = reference_frame(mixed),
                         c = reference_frame(inputs_of(without));
    ASSERT_TRUE(b.find(Tex::direct));
    std::vector<Tex> direct = {Tex::direct};
    for (int f = 0; f < 4; ++f) {
        direct.push_back(Tex(int(Tex::wall_direct_px) + f));
        direct.push_back(Tex(int(Tex::wall_upper_px) + f));
    }
    for (Tex t : direct) {
        ASSERT_TRUE(a.find(t) && b.find(t)) << tex_name(t);
        auto diff = gi_test::compare_textures(b.at(t), a.at(t), 4.0f);
        EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe(std::string(tex_name(t)) + " " + what + " against realtime", diff);
    }
    for (Tex t : {Tex::indirect, Tex::wall_indirect_px, Tex::wall_indirect_nz}) {
        auto diff = gi_test::compare_textures(b.at(t), c.at(t), 0.0f);
        EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe(std::string(tex_name(t)) + " live bounce without the " + what, diff);
    }
}

} // namespace

// Seed 004's light modes at run time: a mixed light gives the same direct light as the same
// light realtime (ground, every face, the unfolded proxy shadows' upper faces) and no live
// bounce light (the bake holds it): the live indirect passes see only the realtime lights.
TEST(BakedReference, AMixedLightIsLitDirectlyAndLeftOutOfTheLiveBounce) {
    for (auto method : {lantern::scene::GiMethod::heat, lantern::scene::GiMethod::gather}) {
        Scene s = rooms_with_unfolded_proxy(method);
        ASSERT_GE(s.point_lights.size(), 2u);
        const Scene all_realtime = s;
        s.point_lights[1].mode = lantern::scene::LightMode::mixed;
        Scene realtime_only = s;
        realtime_only.point_lights.erase(realtime_only.point_lights.begin() + 1);
        FrameInputs mixed = inputs_of(s);
        mixed.baked = empty_bake();
        split_for_bake(mixed, s);
        ASSERT_EQ(mixed.point_lights.size() + 1, inputs_of(all_realtime).point_lights.size());
        ASSERT_EQ(mixed.mixed_lights.size(), 1u);
        expect_lit_directly_and_left_out_of_the_bounce(all_realtime, mixed, realtime_only, "mixed light");
    }
}

// A mixed sun likewise (seed 004's mixed mode for suns): its direct light equals the same sun
// realtime, and the live bounce is that of the frame without it. A second sun stays realtime,
// so both suns' passes run.
TEST(BakedReference, AMixedSunIsLitDirectlyAndLeftOutOfTheLiveBounce) {
    for (auto method : {lantern::scene::GiMethod::heat, lantern::scene::GiMethod::gather}) {
        Scene s = rooms_with_unfolded_proxy(method);
        lantern::scene::DirectionalLight sun, moon;
        sun.direction = glm::normalize(glm::vec3(0.4f, -0.8f, -0.3f));
        sun.intensity = 0.4f;
        moon.direction = glm::normalize(glm::vec3(-0.6f, -0.5f, 0.2f));
        moon.intensity = 0.15f;
        s.directional_lights = {sun, moon};
        const Scene all_realtime = s;
        s.directional_lights[0].mode = lantern::scene::LightMode::mixed;
        Scene realtime_only = s;
        realtime_only.directional_lights.erase(realtime_only.directional_lights.begin());
        FrameInputs mixed = inputs_of(s);
        mixed.baked = empty_bake();
        split_for_bake(mixed, s);
        ASSERT_EQ(mixed.directional_lights.size(), 2u) << "a mixed sun stays in the frame's sun list";
        EXPECT_TRUE(is_mixed_sun(mixed.directional_lights[0]));
        EXPECT_FALSE(is_mixed_sun(mixed.directional_lights[1]));
        EXPECT_EQ(mixed.directional_lights[0].bounce.x, 0.0f) << "no bounce fill: the bake holds its bounce";
        expect_lit_directly_and_left_out_of_the_bounce(all_realtime, mixed, realtime_only, "mixed sun");
    }
}

TEST_F(Baked, MixedLightsOnVulkanEqualTheReference) {
    using lantern::scene::GiMethod;
    std::uint64_t key = 200;
    // 0: a mixed light; 1: mixed lights only, a realtime sun and unfolded proxy shadows; 2: as
    // 1 with a mixed sun beside the realtime one (the mixed row adds it in place).
    for (auto method : {GiMethod::heat, GiMethod::radiosity, GiMethod::gather})
        for (int variant : {0, 1, 2}) {
            Scene s = gi_test::comparison_scene("rooms").scene;
            s.gi.method = method;
            s.point_lights[1].mode = lantern::scene::LightMode::mixed;
            if (variant > 0) {
                s.gi.proxy_wall_shadows = lantern::scene::ProxyWallShadows::unfold;
                lantern::scene::ShadowProxy proxy;
                proxy.position = {6.5f, 6.5f};
                proxy.size = {0.4f, 0.4f};
                s.shadow_proxies.push_back(proxy);
                lantern::scene::DirectionalLight sun;
                sun.direction = glm::normalize(glm::vec3(0.4f, -0.8f, -0.3f));
                sun.intensity = 0.4f;
                s.directional_lights.push_back(sun);
                s.point_lights[0].mode = lantern::scene::LightMode::mixed; // no realtime point light left
            }
            if (variant == 2) {
                lantern::scene::DirectionalLight sun;
                sun.direction = glm::normalize(glm::vec3(-0.6f, -0.5f, 0.2f));
                sun.intensity = 0.3f;
                sun.mode = lantern::scene::LightMode::mixed;
                s.directional_lights.insert(s.directional_lights.begin(), sun);
            }
            FrameInputs in = inputs_of(s);
            in.baked = synthetic_bake(in.walls, {-4, -4}, {40, 32}, 4, 0.0f, key++);
            split_for_bake(in, s);
            const char* what[] = {", a mixed light", ", mixed lights only, a sun and unfolded proxy shadows",
                                  ", mixed lights only, a realtime and a mixed sun, unfolded proxy shadows"};
            const std::string name =
                std::string(method == GiMethod::heat ? "heat" : method == GiMethod::gather ? "gather" : "radiosity") + what[variant];
            compare(name, in, false);
        }
}

// Seed 004's moving sun: a bake with sun keys and a mixed sun between two of them. The baked
// pass adds the sun's colour x the two keys blended (baked_sun_of), on Vulkan as on the
// reference; the blend and colour are in the baked rows' key, so a sun that moves reruns them.
TEST_F(Baked, SunKeysOnVulkanEqualTheReference) {
    for (bool pulsing : {false, true}) {
        Scene s = gi_test::comparison_scene("rooms").scene;
        lantern::scene::DirectionalLight sun;
        sun.direction = lantern::scene::day_sun_direction(0.41f);
        sun.color = {1.0f, 0.8f, 0.6f};
        sun.intensity = 0.7f;
        sun.mode = lantern::scene::LightMode::mixed;
        s.directional_lights.push_back(sun);
        FrameInputs in = inputs_of(s);
        in.baked = synthetic_bake(in.walls, {-4, -4}, {40, 32}, 4, 0.0f, 500 + int(pulsing), pulsing, 5);
        in.baked_pulse = 0.37f;
        split_for_bake(in, s);
        const BakedSun blend = baked_sun_of(in);
        ASSERT_EQ(blend.key, 1) << "t = 0.41 lies between keys 1 (0.375) and 2 (0.5) of five";
        EXPECT_NEAR(blend.blend, (0.41f - 0.375f) / 0.125f, 1e-3f);
        EXPECT_NEAR(blend.color.g, 0.8f * 0.7f, 1e-6f);
        // The keys' light is really added: the sampled light differs from the steady part's.
        const glm::vec2 p(3.3f, 5.6f);
        EXPECT_GT(glm::length(in.baked->light(0, p, in.baked_pulse, blend) - in.baked->light(0, p, in.baked_pulse)), 0.1f);
        compare(pulsing ? "sun keys and a pulsing part" : "sun keys", in, false);
        // Another time of day: another key in the baked rows' input key.
        FrameInputs later = in;
        later.directional_lights[0].direction_base = glm::vec4(lantern::scene::day_sun_direction(0.6f), later.directional_lights[0].direction_base.w);
        EXPECT_NE(baked_input_key(later), baked_input_key(in));
    }
}

// The mixed lights' pass is cached while they stay put: a realtime light that moves (a
// torch's flicker) reruns the direct pass, the indirect passes and the baked pass, which adds
// the kept mixed light again, but not the mixed pass; what the frame holds then equals a
// frame computed afresh. And a mixed light that moves reruns the passes it is added to.
TEST(BakedReference, AStillMixedLightIsKeptWhileRealtimeLightsChange) {
    Scene s = gi_test::comparison_scene("rooms").scene;
    s.point_lights[1].mode = lantern::scene::LightMode::mixed;
    auto frame = [&](const Scene& scene) {
        FrameInputs in = inputs_of(scene);
        in.baked = synthetic_bake(in.walls, {-4, -4}, {40, 32}, 4, 0.01f, 300);
        split_for_bake(in, scene);
        return in;
    };
    // Frames as the frame systems run them: only the passes whose keys changed, on one store.
    ReferenceStore kept;
    std::array<std::uint64_t, pass_count> last{};
    auto step = [&](const FrameInputs& in) {
        PassPlan plan = plan_passes(in, true);
        const auto keys = derive_keys(in, plan, input_keys_of(in));
        PassSet run;
        for (int p = 0; p < registered_pass_count(); ++p)
            if (plan.run.has(Pass(p)) && keys[std::size_t(p)] != last[std::size_t(p)]) run.add(Pass(p));
        execute_reference(in, plan, run, {}, kept);
        last = keys;
        return run;
    };
    step(frame(s));
    Scene moved = s;
    moved.point_lights[0].position.x += 0.5f; // the realtime light
    const PassSet second = step(frame(moved));
    EXPECT_TRUE(second.has(Pass::direct));
    EXPECT_TRUE(second.has(Pass::baked));
    EXPECT_FALSE(second.has(Pass::mixed)) << "the still mixed light is not computed again";
    const ReferenceStore fresh = reference_frame(frame(moved));
    for (Tex t : {Tex::direct, Tex::wall_direct_px, Tex::wall_direct_nz, Tex::indirect, Tex::wall_indirect_pz}) {
        auto diff = gi_test::compare_textures(kept.at(t), fresh.at(t), 0.0f);
        EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe(std::string(tex_name(t)) + " kept against afresh", diff);
    }
    Scene mixed_moved = moved;
    mixed_moved.point_lights[1].position.x += 0.5f;
    const PassSet third = step(frame(mixed_moved));
    EXPECT_TRUE(third.has(Pass::mixed));
    EXPECT_TRUE(third.has(Pass::direct)) << "the pass the baked pass adds to in place reruns first";
    const ReferenceStore fresh3 = reference_frame(frame(mixed_moved));
    for (Tex t : {Tex::direct, Tex::wall_direct_px, Tex::indirect}) {
        auto diff = gi_test::compare_textures(kept.at(t), fresh3.at(t), 0.0f);
        EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe(std::string(tex_name(t)) + " after the mixed light moved", diff);
    }
}
