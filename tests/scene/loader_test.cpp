#include "lantern/scene/loader.hpp"

#include "lantern/scene/color.hpp"

#include "common/test_support.hpp"
#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

using namespace lantern::scene;
using lantern::test::parse_scene_error;
using lantern::test::parse_scene_ok;
using lantern::test::scene_with;
using lantern::test::TempDir;

namespace {

// SCENES.md's example with rows instead of a map, every value away from its default.
constexpr std::string_view golden_text = R"({
  "lantern_scene": 1,
  "world": {
    "rows": ["#####", "#...#", "#.#..", "#####"],
    "origin": [-3, 7],
    "wall_height": 2.5
  },
  "view": { "center": [32.0, 40.0], "size": [30.0, 16.875] },
  "gi": {
    "resolution": 16, "padding": 1.5,
    "heat_rounds": 30, "heat_scale": "half",
    "diffusion_rate": 0.75, "diffusion_distance": 2.0,
    "emission_strength": 1.5, "range_boost": 0.25, "intensity_multiplier": 2.0,
    "per_channel": false, "segment_check": false, "light_softness": 1.5,
    "ao": { "enabled": false, "radius": 2.5, "power": 2.0, "strength": 0.5, "dither": true },
    "blur": false, "tone_map": "reinhard_white", "white_point": 3.0,
    "directional_angle_scale": 0.25,
    "max_lights": 128, "max_shadow_proxies": 32
  },
  "point_lights":       [ { "position": [30.5, 41.5], "height": 1.5, "color": [1.0, 0.5, 0.25],
                            "intensity": 2.0, "radius": 10.0 },
                          { "position": [1, 2] } ],
  "emissive_lights":    [ { "position": [20.5, 35.5], "color": [0.25, 0.5, 1.0], "intensity": 0.5,
                            "radius": 3.0 } ],
  "directional_lights": [ { "direction": [0.0, -3.0, 4.0], "color": [1.0, 0.75, 0.5], "intensity": 1.25,
                            "base_shadow_distance": 6.0, "bounce_intensity": 0.125 } ],
  "shadow_proxies":     [ { "position": [25.0, 38.0], "shape": "box", "size": [0.5, 0.25],
                            "max_length": 2.0, "end_cap_blend": 0.75,
                            "penumbra_width": 0.5, "penumbra_length": 1.5, "penumbra_power": 2.0,
                            "width_mode": "max_axis", "penumbra_mode": "inward" } ]
})";

Scene golden_scene() {
    Scene s;
    s.source = "t.json";
    s.walls.width = 5;
    s.walls.height = 4;
    s.walls.origin = {-3, 7};
    s.walls.cells = {1, 1, 1, 1, 1, //
                     1, 0, 0, 0, 1, //
                     1, 0, 1, 0, 0, //
                     1, 1, 1, 1, 1};
    s.wall_height = 2.5f;
    s.view = OrthoView{{32.0f, 40.0f}, {30.0f, 16.875f}};
    GiSettings& gi = s.gi;
    gi.resolution = 16;
    gi.padding = 1.5f;
    gi.heat_rounds = 30;
    gi.heat_scale = HeatScale::half;
    gi.diffusion_rate = 0.75f;
    gi.diffusion_distance = 2.0f;
    gi.emission_strength = 1.5f;
    gi.range_boost = 0.25f;
    gi.intensity_multiplier = 2.0f;
    gi.per_channel = false;
    gi.segment_check = false;
    gi.light_softness = 1.5f;
    gi.ao = AoSettings{false, 2.5f, 2.0f, 0.5f, true};
    gi.blur = false;
    gi.tone_map = ToneMap::reinhard_white;
    gi.white_point = 3.0f;
    gi.directional_angle_scale = 0.25f;
    gi.max_lights = 128;
    gi.max_shadow_proxies = 32;
    s.point_lights = {PointLight{{30.5f, 41.5f}, 1.5f, {1.0f, 0.5f, 0.25f}, 2.0f, 10.0f},
                      PointLight{{1.0f, 2.0f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 8.0f}};
    s.emissive_lights = {EmissiveLight{{20.5f, 35.5f}, {0.25f, 0.5f, 1.0f}, 0.5f, 3.0f}};
    s.directional_lights = {
        DirectionalLight{{0.0f, -0.6f, 0.8f}, {1.0f, 0.75f, 0.5f}, 1.25f, 6.0f, 0.125f}};
    s.shadow_proxies = {ShadowProxy{{25.0f, 38.0f},
                                    ProxyShape::box,
                                    {0.5f, 0.25f},
                                    2.0f,
                                    0.75f,
                                    0.5f,
                                    1.5f,
                                    2.0f,
                                    WidthMode::max_axis,
                                    PenumbraMode::inward}};
    return s;
}

void write_text(const std::string& path, std::string_view text) {
    std::ofstream(path, std::ios::binary) << text;
}

} // namespace

TEST(SceneLoader, GoldenSceneParsesIntoExactlyTheExpectedScene) {
    const Scene scene = parse_scene_ok(golden_text);
    const Scene expected = golden_scene();
    EXPECT_EQ(scene.source, expected.source);
    EXPECT_EQ(scene.walls, expected.walls);
    EXPECT_EQ(scene.wall_height, expected.wall_height);
    EXPECT_EQ(scene.view, expected.view);
    EXPECT_EQ(scene.gi, expected.gi);
    EXPECT_EQ(scene.point_lights, expected.point_lights);
    EXPECT_EQ(scene.emissive_lights, expected.emissive_lights);
    EXPECT_EQ(scene.directional_lights, expected.directional_lights);
    EXPECT_EQ(scene.shadow_proxies, expected.shadow_proxies);
    EXPECT_EQ(scene, expected); // and nothing else differs
}

TEST(SceneLoader, MinimalSceneTakesEveryDefault) {
    const Scene scene = parse_scene_ok(
        R"({"lantern_scene": 1, "world": {"rows": ["#."]}, "view": {"center": [4, 5]}})");
    Scene expected;
    expected.source = "t.json";
    expected.walls.width = 2;
    expected.walls.height = 1;
    expected.walls.cells = {1, 0};
    expected.view = OrthoView{{4.0f, 5.0f}, OrthoView{}.size};
    EXPECT_EQ(scene, expected);
}

TEST(SceneLoader, CameraSceneReadsThePerspectiveCamera) {
    const Scene scene = parse_scene_ok(R"({"lantern_scene": 1, "world": {"rows": ["."]},
        "camera": {"position": [32, 20, 30], "target": [32, 0, 40], "fov_deg": 60, "aspect": 2}})");
    ASSERT_TRUE(std::holds_alternative<PerspectiveCamera>(scene.view));
    const PerspectiveCamera expected{{32.0f, 20.0f, 30.0f}, {32.0f, 0.0f, 40.0f}, 60.0f, 2.0f};
    EXPECT_EQ(std::get<PerspectiveCamera>(scene.view), expected);
}

// "temperature" multiplies a light's colour by the black body's at that temperature, at the
// same luminance; without a "color", white is multiplied.
TEST(SceneLoader, LightTemperatureTintsTheColour) {
    const Scene scene = parse_scene_ok(scene_with(
        R"("point_lights": [{"position": [0, 0], "temperature": 2856}, {"position": [0, 0], "color": [0.5, 0.5, 0.5], "temperature": 2856}],)"
        R"( "emissive_lights": [{"position": [0, 0], "temperature": 9000}],)"
        R"( "directional_lights": [{"direction": [0, -1, 0], "temperature": 5800}])"));
    const glm::vec3 tungsten = lantern::scene::blackbody_rgb(2856.0f);
    EXPECT_EQ(scene.point_lights[0].color, tungsten);
    EXPECT_EQ(scene.point_lights[1].color, 0.5f * tungsten);
    EXPECT_GT(tungsten.r, tungsten.g);
    EXPECT_GT(tungsten.g, tungsten.b);
    const glm::vec3 blue = scene.emissive_lights[0].color;
    EXPECT_GT(blue.b, blue.r);
    EXPECT_EQ(scene.directional_lights[0].color, lantern::scene::blackbody_rgb(5800.0f));
}

TEST(SceneLoader, EmptyListsMeanNoLights) {
    const Scene scene = parse_scene_ok(scene_with(R"("point_lights": [], "shadow_proxies": [])"));
    EXPECT_TRUE(scene.point_lights.empty());
    EXPECT_TRUE(scene.shadow_proxies.empty());
}

TEST(SceneLoader, IntegralNumbersAreIntegers) {
    EXPECT_EQ(parse_scene_ok(scene_with(R"("gi": {"resolution": 16.0, "heat_rounds": 1e3})"))
                  .gi.heat_rounds,
              1000);
}

TEST(SceneLoader, DirectionalDirectionsAreNormalisedInDoublePrecision) {
    const Scene scene =
        parse_scene_ok(scene_with(R"("directional_lights": [{"direction": [1e-30, 0, 0]}])"));
    ASSERT_EQ(scene.directional_lights.size(), 1u);
    EXPECT_EQ(scene.directional_lights[0].direction, glm::vec3(1.0f, 0.0f, 0.0f));
}

TEST(SceneLoader, EveryTruncationOfTheGoldenSceneFails) {
    const std::string_view text = golden_text;
    for (std::size_t length = 0; length < text.size(); ++length) {
        const std::string message = parse_scene_error(text.substr(0, length));
        EXPECT_TRUE(message.starts_with("t.json:")) << "length " << length << ": " << message;
    }
}

TEST(SceneLoader, DeletingAnyOneByteOfTheGoldenSceneNeverCrashes) {
    const std::string text(golden_text);
    for (std::size_t i = 0; i < text.size(); ++i) {
        std::string damaged = text;
        damaged.erase(i, 1);
        auto result = parse_scene(damaged, "t.json", "");
        if (!result.ok()) {
            EXPECT_TRUE(result.error().message.starts_with("t.json:")) << result.error().message;
        }
    }
}

struct SceneErrorCase {
    std::string text;
    std::string message;
};

void PrintTo(const SceneErrorCase& c, std::ostream* os) {
    *os << c.text;
}

class SceneErrors : public testing::TestWithParam<SceneErrorCase> {};

TEST_P(SceneErrors, GiveOneMessageWithFileLineColumnAndPath) {
    EXPECT_EQ(parse_scene_error(GetParam().text), GetParam().message);
}

// Cases on line 2 of scene_with(): columns count from the start of the given text.
INSTANTIATE_TEST_SUITE_P(
    Gi, SceneErrors,
    testing::Values(
        SceneErrorCase{scene_with(R"("gi": 3)"),
                       "t.json:2:7: gi: expected an object, got a number"},
        SceneErrorCase{
            scene_with(R"("gi": {"resoluton": 8})"),
            "t.json:2:8: gi.resoluton: unknown key 'resoluton' in gi (did you mean 'resolution'?)"},
        SceneErrorCase{scene_with(R"("gi": {"bloom": 8})"),
                       "t.json:2:8: gi.bloom: unknown key 'bloom' in gi"},
        SceneErrorCase{scene_with(R"("gi": {"ao.radius": 2})"),
                       "t.json:2:8: gi.ao.radius: unknown key 'ao.radius' in gi"},
        SceneErrorCase{scene_with(R"("gi": {"resolution": 0})"),
                       "t.json:2:22: gi.resolution: must be an integer in [1, 32], got 0"},
        SceneErrorCase{scene_with(R"("gi": {"resolution": 33})"),
                       "t.json:2:22: gi.resolution: must be an integer in [1, 32], got 33"},
        SceneErrorCase{scene_with(R"("gi": {"resolution": 8.5})"),
                       "t.json:2:22: gi.resolution: expected an integer, got 8.5"},
        SceneErrorCase{scene_with(R"("gi": {"resolution": "8"})"),
                       "t.json:2:22: gi.resolution: expected an integer, got a string"},
        SceneErrorCase{scene_with(R"("gi": {"padding": 0.5})"),
                       "t.json:2:19: gi.padding: must be in [1, 8], got 0.5"},
        SceneErrorCase{scene_with(R"("gi": {"padding": 9})"),
                       "t.json:2:19: gi.padding: must be in [1, 8], got 9"},
        SceneErrorCase{scene_with(R"("gi": {"heat_rounds": -1})"),
                       "t.json:2:23: gi.heat_rounds: must be an integer in [0, 100000], got -1"},
        SceneErrorCase{
            scene_with(R"("gi": {"heat_rounds": 100001})"),
            "t.json:2:23: gi.heat_rounds: must be an integer in [0, 100000], got 100001"},
        SceneErrorCase{scene_with(R"("gi": {"heat_scale": "double"})"),
                       "t.json:2:22: gi.heat_scale: expected one of \"full\", \"half\", "
                       "\"quarter\", got \"double\""},
        SceneErrorCase{scene_with(R"("gi": {"heat_scale": 2})"),
                       "t.json:2:22: gi.heat_scale: expected one of \"full\", \"half\", "
                       "\"quarter\", got a number"},
        SceneErrorCase{
            scene_with(R"("gi": {"diffusion_rate": 1.5})"),
            "t.json:2:26: gi.diffusion_rate: must be in [0, 1.25], got 1.5 (above 1.25 the heat "
            "blend exceeds 1 and the diffusion overshoots; see docs/gi.md)"},
        SceneErrorCase{
            scene_with(R"("gi": {"diffusion_rate": -0.5})"),
            "t.json:2:26: gi.diffusion_rate: must be in [0, 1.25], got -0.5 (above 1.25 the heat "
            "blend exceeds 1 and the diffusion overshoots; see docs/gi.md)"},
        SceneErrorCase{scene_with(R"("gi": {"diffusion_distance": 0})"),
                       "t.json:2:30: gi.diffusion_distance: must be in (0, 16], got 0"},
        SceneErrorCase{scene_with(R"("gi": {"diffusion_distance": 16.5})"),
                       "t.json:2:30: gi.diffusion_distance: must be in (0, 16], got 16.5"},
        SceneErrorCase{scene_with(R"("gi": {"emission_strength": -1})"),
                       "t.json:2:29: gi.emission_strength: must be >= 0, got -1"},
        SceneErrorCase{scene_with(R"("gi": {"emission_strength": 1e39})"),
                       "t.json:2:29: gi.emission_strength: 1e+39 does not fit a 32-bit float"},
        SceneErrorCase{scene_with(R"("gi": {"range_boost": -1})"),
                       "t.json:2:23: gi.range_boost: must be >= 0, got -1"},
        SceneErrorCase{scene_with(R"("gi": {"intensity_multiplier": -1})"),
                       "t.json:2:32: gi.intensity_multiplier: must be >= 0, got -1"},
        SceneErrorCase{scene_with(R"("gi": {"per_channel": 1})"),
                       "t.json:2:23: gi.per_channel: expected true or false, got a number"},
        SceneErrorCase{scene_with(R"("gi": {"segment_check": "true"})"),
                       "t.json:2:25: gi.segment_check: expected true or false, got a string"},
        SceneErrorCase{scene_with(R"("gi": {"light_softness": 0})"),
                       "t.json:2:26: gi.light_softness: must be > 0, got 0"},
        SceneErrorCase{scene_with(R"("gi": {"ao": 1})"),
                       "t.json:2:14: gi.ao: expected an object, got a number"},
        SceneErrorCase{
            scene_with(R"("gi": {"ao": {"radus": 1}})"),
            "t.json:2:15: gi.ao.radus: unknown key 'radus' in gi.ao (did you mean 'radius'?)"},
        SceneErrorCase{scene_with(R"("gi": {"ao": {"enabled": null}})"),
                       "t.json:2:26: gi.ao.enabled: expected true or false, got null"},
        SceneErrorCase{scene_with(R"("gi": {"ao": {"radius": 0}})"),
                       "t.json:2:25: gi.ao.radius: must be in (0, 8], got 0"},
        SceneErrorCase{scene_with(R"("gi": {"ao": {"radius": 8.5}})"),
                       "t.json:2:25: gi.ao.radius: must be in (0, 8], got 8.5"},
        SceneErrorCase{scene_with(R"("gi": {"ao": {"power": 0}})"),
                       "t.json:2:24: gi.ao.power: must be > 0, got 0"},
        SceneErrorCase{scene_with(R"("gi": {"ao": {"strength": 1.5}})"),
                       "t.json:2:27: gi.ao.strength: must be in [0, 1], got 1.5"},
        SceneErrorCase{scene_with(R"("gi": {"ao": {"dither": 0}})"),
                       "t.json:2:25: gi.ao.dither: expected true or false, got a number"},
        SceneErrorCase{scene_with(R"("gi": {"blur": "no"})"),
                       "t.json:2:16: gi.blur: expected true or false, got a string"},
        SceneErrorCase{
            scene_with(R"("gi": {"tone_map": "filmic"})"),
            "t.json:2:20: gi.tone_map: expected one of \"none\", \"reinhard\", \"reinhard_white\", "
            "\"aces\", got \"filmic\""},
        SceneErrorCase{scene_with(R"("gi": {"white_point": 0})"),
                       "t.json:2:23: gi.white_point: must be > 0, got 0"},
        SceneErrorCase{scene_with(R"("gi": {"directional_angle_scale": 1.5})"),
                       "t.json:2:35: gi.directional_angle_scale: must be in [0, 1], got 1.5"},
        SceneErrorCase{scene_with(R"("gi": {"max_lights": 4097})"),
                       "t.json:2:22: gi.max_lights: must be an integer in [0, 4096], got 4097"},
        SceneErrorCase{
            scene_with(R"("gi": {"max_shadow_proxies": 257})"),
            "t.json:2:30: gi.max_shadow_proxies: must be an integer in [0, 256], got 257"}));

INSTANTIATE_TEST_SUITE_P(
    Lights, SceneErrors,
    testing::Values(
        SceneErrorCase{scene_with(R"("point_lights": {})"),
                       "t.json:2:17: point_lights: expected an array, got an object"},
        SceneErrorCase{scene_with(R"("point_lights": [3])"),
                       "t.json:2:18: point_lights[0]: expected an object, got a number"},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [0, 0]}, {"radius": 2}])"),
                       "t.json:2:40: point_lights[1].position: required key is missing"},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [0, 0], "temperature": 1000}])"),
                       "t.json:2:54: point_lights[0].temperature: must be in [1667, 25000], got 1000 (the "
                       "range of the black-body colour approximation)"},
        SceneErrorCase{
            scene_with(R"("point_lights": [{"position": [0, 0, 0]}])"),
            "t.json:2:31: point_lights[0].position: expected an array of 2 numbers, got 3"},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [0, "1"]}])"),
                       "t.json:2:35: point_lights[0].position[1]: expected a number, got a string"},
        SceneErrorCase{
            scene_with(R"("point_lights": [{"position": [0, 1e39]}])"),
            "t.json:2:35: point_lights[0].position[1]: must be in [-16777216, 16777216], got 1e+39 (world coordinates "
            "stay within +-2^24)"},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [0, 0], "radius": 1e39}])"),
                       "t.json:2:49: point_lights[0].radius: 1e+39 does not fit a 32-bit float"},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [0, 0], "radius": 1e-40}])"),
                       "t.json:2:49: point_lights[0].radius: 1e-40 is too close to 0 for a 32-bit float"},
        SceneErrorCase{
            scene_with(R"("point_lights": [{"position": [0, 0], "color": [1, -0.5, 1]}])"),
            "t.json:2:52: point_lights[0].color[1]: must be >= 0, got -0.5"},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [0, 0], "intensity": -1}])"),
                       "t.json:2:52: point_lights[0].intensity: must be >= 0, got -1"},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [0, 0], "radius": -1}])"),
                       "t.json:2:49: point_lights[0].radius: must be > 0, got -1"},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [0, 0], "radius": 0}])"),
                       "t.json:2:49: point_lights[0].radius: must be > 0, got 0"},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [0, 0], "height": -1}])"),
                       "t.json:2:49: point_lights[0].height: must be >= 0, got -1"},
        SceneErrorCase{
            scene_with(R"("point_lights": [{"position": [0, 0], "radiu": 1}])"),
            "t.json:2:39: point_lights[0].radiu: unknown key 'radiu' in point_lights[0] (did you "
            "mean 'radius'?)"},
        SceneErrorCase{scene_with(R"("emissive_lights": [{"position": [0, 0], "radius": 0}])"),
                       "t.json:2:52: emissive_lights[0].radius: must be > 0, got 0"},
        SceneErrorCase{
            scene_with(R"("emissive_lights": [{"position": [0, 0], "height": 1}])"),
            "t.json:2:42: emissive_lights[0].height: unknown key 'height' in emissive_lights[0]"},
        SceneErrorCase{scene_with(R"("directional_lights": [{"color": [1, 1, 1]}])"),
                       "t.json:2:24: directional_lights[0].direction: required key is missing"},
        SceneErrorCase{scene_with(R"("directional_lights": [{"direction": [0, 0, 0]}])"),
                       "t.json:2:38: directional_lights[0].direction: must not be zero"},
        SceneErrorCase{
            scene_with(R"("directional_lights": [{"direction": [0, -1]}])"),
            "t.json:2:38: directional_lights[0].direction: expected an array of 3 numbers, got 2"},
        SceneErrorCase{
            scene_with(
                R"("directional_lights": [{"direction": [0, -1, 0], "base_shadow_distance": -1}])"),
            "t.json:2:74: directional_lights[0].base_shadow_distance: must be >= 0, got -1"},
        SceneErrorCase{
            scene_with(
                R"("directional_lights": [{"direction": [0, -1, 0], "bounce_intensity": -1}])"),
            "t.json:2:70: directional_lights[0].bounce_intensity: must be >= 0, got -1"},
        SceneErrorCase{
            scene_with(R"("directional_lights": [{"direction": [0, -1, 0], "color": [-1, 0, 0]}])"),
            "t.json:2:60: directional_lights[0].color[0]: must be >= 0, got -1"}));

INSTANTIATE_TEST_SUITE_P(
    ShadowProxies, SceneErrors,
    testing::Values(
        SceneErrorCase{scene_with(R"("shadow_proxies": [{"shape": "box"}])"),
                       "t.json:2:20: shadow_proxies[0].position: required key is missing"},
        SceneErrorCase{
            scene_with(R"("shadow_proxies": [{"position": [0, 0], "shape": "triangle"}])"),
            "t.json:2:50: shadow_proxies[0].shape: expected one of \"box\", \"circle\", got "
            "\"triangle\""},
        SceneErrorCase{scene_with(R"("shadow_proxies": [{"position": [0, 0], "size": [0, 1]}])"),
                       "t.json:2:50: shadow_proxies[0].size[0]: must be > 0, got 0"},
        SceneErrorCase{scene_with(R"("shadow_proxies": [{"position": [0, 0], "size": [1, -1]}])"),
                       "t.json:2:53: shadow_proxies[0].size[1]: must be > 0, got -1"},
        SceneErrorCase{scene_with(R"("shadow_proxies": [{"position": [0, 0], "max_length": -1}])"),
                       "t.json:2:55: shadow_proxies[0].max_length: must be >= 0, got -1"},
        SceneErrorCase{
            scene_with(R"("shadow_proxies": [{"position": [0, 0], "end_cap_blend": 1.5}])"),
            "t.json:2:58: shadow_proxies[0].end_cap_blend: must be in [0, 1], got 1.5"},
        SceneErrorCase{
            scene_with(R"("shadow_proxies": [{"position": [0, 0], "penumbra_width": -1}])"),
            "t.json:2:59: shadow_proxies[0].penumbra_width: must be >= 0, got -1"},
        SceneErrorCase{
            scene_with(R"("shadow_proxies": [{"position": [0, 0], "penumbra_length": -1}])"),
            "t.json:2:60: shadow_proxies[0].penumbra_length: must be >= 0, got -1"},
        SceneErrorCase{
            scene_with(R"("shadow_proxies": [{"position": [0, 0], "penumbra_power": 0}])"),
            "t.json:2:59: shadow_proxies[0].penumbra_power: must be > 0, got 0"},
        SceneErrorCase{
            scene_with(R"("shadow_proxies": [{"position": [0, 0], "width_mode": "widest"}])"),
            "t.json:2:55: shadow_proxies[0].width_mode: expected one of \"projected\", "
            "\"max_axis\", "
            "got \"widest\""},
        SceneErrorCase{
            scene_with(R"("shadow_proxies": [{"position": [0, 0], "penumbra_mode": "all"}])"),
            "t.json:2:58: shadow_proxies[0].penumbra_mode: expected one of \"inward\", "
            "\"outward\", "
            "\"both\", got \"all\""}));

INSTANTIATE_TEST_SUITE_P(
    TopLevel, SceneErrors,
    testing::Values(
        SceneErrorCase{"[]", "t.json:1:1: expected an object, got an array"},
        SceneErrorCase{"{\"lantern_scene\": 1,}", "t.json:1:21: expected a string key, found '}'"},
        SceneErrorCase{R"({"world": {"rows": ["."]}, "view": {"center": [0, 0]}})",
                       "t.json:1:1: lantern_scene: required key is missing"},
        SceneErrorCase{
            R"({"lantern_scene": 2})",
            "t.json:1:19: lantern_scene: version 2 is not supported; this build reads version 1"},
        SceneErrorCase{R"({"lantern_scene": "1"})",
                       "t.json:1:19: lantern_scene: expected an integer, got a string"},
        SceneErrorCase{R"({"lantern_scene": 1})", "t.json:1:1: world: required key is missing"},
        SceneErrorCase{scene_with(R"("lights": [])"),
                       "t.json:2:1: lights: unknown key 'lights' in the scene"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": ["."]}})",
                       "t.json:1:1: view: required key is missing (or give 'camera')"},
        SceneErrorCase{scene_with(R"("camera": {"position": [0, 1, 0], "target": [0, 0, 0]})"),
                       "t.json:2:11: camera: give only one of 'view' and 'camera'"}));

INSTANTIATE_TEST_SUITE_P(
    World, SceneErrors,
    testing::Values(
        SceneErrorCase{R"({"lantern_scene": 1, "world": [], "view": {"center": [0, 0]}})",
                       "t.json:1:31: world: expected an object, got an array"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {}, "view": {"center": [0, 0]}})",
                       "t.json:1:31: world.map: required key is missing (or give 'rows')"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"map": "a.map", "rows": ["."]}})",
                       "t.json:1:56: world.rows: give only one of 'map' and 'rows'"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": "#."}})",
                       "t.json:1:40: world.rows: expected an array, got a string"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": []}})",
                       "t.json:1:40: world.rows: needs at least one row"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": [""]}})",
                       "t.json:1:41: world.rows[0]: row is empty"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": ["#.", 5]}})",
                       "t.json:1:47: world.rows[1]: expected a string, got a number"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": ["#.", "#.."]}})",
                       "t.json:1:47: world.rows[1]: row has 3 cells, row 0 has 2"},
        SceneErrorCase{"{\"lantern_scene\": 1, \"world\": {\"rows\": [\n  \"####\",\n  \"#.x#\"]}}",
                       "t.json:3:6: world.rows[1]: unknown cell character 'x' (rows use '#' for "
                       "wall, '.' for floor and the symbols of \"materials\")"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": ["#.\t"]}})",
                       "t.json:1:44: world.rows[0]: unknown cell character byte 0x09 (rows use '#' "
                       "for wall, '.' for floor and the symbols of \"materials\")"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": ["."], "origin": [0.5, 0]}})",
                       "t.json:1:58: world.origin[0]: expected an integer, got 0.5"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": ["."], "origin": [0]}})",
                       "t.json:1:57: world.origin: expected an array of 2 integers, got 1"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": ["."], "origin": [0, 16777217]}})",
                       "t.json:1:61: world.origin[1]: must be an integer in [-16777216, 16777216], "
                       "got 16777217"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": ["."], "wall_height": 0}})",
                       "t.json:1:62: world.wall_height: must be > 0, got 0"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"rows": ["."], "trees": "proxy"}})",
                       "t.json:1:56: world.trees: applies to \"map\" worlds only"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."], "extra_floor_chars": "s"}})",
            "t.json:1:68: world.extra_floor_chars: applies to \"map\" worlds only"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"map": ""}})",
                       "t.json:1:39: world.map: must name a map file"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"map": "a.map", "trees": "bush"}})",
            "t.json:1:57: world.trees: expected one of \"wall\", \"proxy\", got \"bush\""},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"map": "a.map", "extra_floor_chars": "sT"}})",
            "t.json:1:69: world.extra_floor_chars: 'T' already has a meaning in Moving AI maps "
            "(. G S W @ O T)"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"map": "a.map", "extra_floor_chars": "s t"}})",
            "t.json:1:69: world.extra_floor_chars: ' ' is not a printable ASCII character"},
        SceneErrorCase{R"({"lantern_scene": 1, "world": {"map": "a.map", "wals": 1}})",
                       "t.json:1:48: world.wals: unknown key 'wals' in world"}));

INSTANTIATE_TEST_SUITE_P(
    View, SceneErrors,
    testing::Values(
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "view": {"size": [1, 1]}})",
            "t.json:1:56: view.center: required key is missing"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "view": {"center": [0, 0], "size": [0, 1]}})",
            "t.json:1:84: view.size[0]: must be > 0, got 0"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "view": {"center": [0, 0], "zoom": 2}})",
            "t.json:1:75: view.zoom: unknown key 'zoom' in view"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "camera": {"position": [0, 1, 0]}})",
            "t.json:1:58: camera.target: required key is missing"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "camera": {"position": [0, 1, 0], "target": [0, 1, 0]}})",
            "t.json:1:92: camera.target: must differ from camera.position"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "camera": {"position": [0, 1, 0], "target": [0, 0, 0], "fov_deg": 180}})",
            "t.json:1:114: camera.fov_deg: must be in (0, 180), got 180"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "camera": {"position": [0, 1, 0], "target": [0, 0, 0], "aspect": 0}})",
            "t.json:1:113: camera.aspect: must be > 0, got 0"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "view": {"center": [0, 0], "size": [10000, 10]}})",
            "t.json:1:83: view.size: the GI texture would be 112000 x 112 texels (view.size x "
            "gi.padding "
            "x gi.resolution), above the limit of 65536 per side"},
        // A camera the renderer cannot use is refused at load, at its position.
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "camera": {"position": [0, 5, 0], "target": [0, 10, 1]}})",
            "t.json:1:92: camera.target: the camera sees no ground: a viewport corner ray does not hit the ground in "
            "front of the camera"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "camera": {"position": [0, 5, 0], "target": [1, 4.99, 0]}})",
            "t.json:1:92: camera.target: the camera sees no ground: a viewport corner ray does not hit the ground in "
            "front of the camera"},
        SceneErrorCase{
            R"({"lantern_scene": 1, "world": {"rows": ["."]}, "camera": {"position": [0, 20000, 0], "target": [0, 0, 1]}})",
            "t.json:1:58: camera: the GI texture would be 289888 x 163059 texels (the ground the camera sees x "
            "gi.padding x gi.resolution), above the limit of 65536 per side"}));

TEST(SceneLoader, GiWindowLimitCountsPaddingAndResolution) {
    // 2048 * 1 * 32 = 65536 texels fits exactly; the same window at padding 1.01 does not.
    const std::string fits = scene_with(R"("gi": {"padding": 1, "resolution": 32})");
    const std::string with_size =
        std::string(fits).replace(fits.find("[0, 0]}"), 7, "[0, 0], \"size\": [2048, 1]}");
    EXPECT_TRUE(parse_scene(with_size, "t.json", "").ok());
    std::string too_big = with_size;
    too_big.replace(too_big.find("\"padding\": 1"), 12, "\"padding\": 1.01");
    EXPECT_TRUE(parse_scene_error(too_big).find("above the limit of 65536 per side") !=
                std::string::npos);
}

TEST(SceneLoader, RowGridsAboveTheSizeLimitsAreRejectedBeforeAllocating) {
    std::string wide =
        R"({"lantern_scene": 1, "world": {"rows": [")" + std::string(65537, '.') + R"("]}})";
    EXPECT_EQ(parse_scene_error(wide),
              "t.json:1:41: world.rows[0]: row has 65537 cells, above the limit of 65536");
    std::string tall = R"({"lantern_scene": 1, "world": {"rows": [".")";
    for (int i = 0; i < 65536; ++i) tall += ",\"\"";
    tall += "]}}";
    EXPECT_EQ(parse_scene_error(tall),
              "t.json:1:40: world.rows: a grid of 1 x 65537 cells is above the limits "
              "(65536 per side, 268435456 in all)");
    // 65536 x 4097 cells: the first row and the row count decide, the other rows are never read.
    std::string many =
        R"({"lantern_scene": 1, "world": {"rows": [")" + std::string(65536, '.') + "\"";
    for (int i = 1; i < 4097; ++i) many += ",\"\"";
    many += "]}}";
    EXPECT_EQ(parse_scene_error(many),
              "t.json:1:40: world.rows: a grid of 65536 x 4097 cells is above the limits "
              "(65536 per side, 268435456 in all)");
}

TEST(SceneLoader, QuotedInputIsCutShortOnACharacterBoundary) {
    const std::string key =
        std::string(39, 'a') + "\xC3\xA9" + std::string(60, 'b'); // é at bytes 39-40
    EXPECT_EQ(parse_scene_error(scene_with("\"gi\": {\"" + key + "\": 1}")),
              "t.json:2:8: gi." + std::string(39, 'a') + "...: unknown key '" +
                  std::string(39, 'a') + "...' in gi");
    EXPECT_EQ(
        parse_scene_error(scene_with("\"gi\": {\"tone_map\": \"" + std::string(50, 'x') + "\"}")),
        "t.json:2:20: gi.tone_map: expected one of \"none\", \"reinhard\", \"reinhard_white\", "
        "\"aces\", got \"" +
            std::string(40, 'x') + "...\"");
}

TEST(SceneLoader, JsonSyntaxErrorsNameTheSceneFile) {
    EXPECT_EQ(parse_scene_error("{\"lantern_scene\": 1,\n  \"gi\": {\"blur\": tru}}"),
              "t.json:2:18: invalid literal, expected 'true'");
}

TEST(SceneLoader, LoadSceneImportsTheMapRelativeToTheSceneFolder) {
    TempDir dir;
    std::filesystem::create_directories(dir.path() / "maps");
    write_text(dir.file("maps/small.map"), "type octile\nheight 2\nwidth 3\nmap\n@T.\n.G@\n");
    write_text(dir.file("level.json"), R"({"lantern_scene": 1,
        "world": {"map": "maps/small.map", "origin": [10, -4], "trees": "proxy"},
        "view": {"center": [0, 0]},
        "shadow_proxies": [{"position": [1, 1]}]})");
    auto scene = load_scene(dir.file("level.json"));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->source, dir.file("level.json"));
    EXPECT_EQ(scene->inputs, std::vector<std::string>{dir.file("maps/small.map")}); // what --watch looks at too
    WallGrid expected_walls;
    expected_walls.width = 3;
    expected_walls.height = 2;
    expected_walls.origin = {10, -4};
    expected_walls.cells = {1, 0, 0, 0, 0, 1};
    EXPECT_EQ(scene->walls, expected_walls);
    EXPECT_TRUE(scene->walls.is_wall_tile(10, -4));
    EXPECT_TRUE(scene->walls.is_wall_tile(12, -3));
    // The scene's own proxy first, then one circle of radius 0.4 at the centre of each tree.
    ShadowProxy tree;
    tree.position = {11.5f, -3.5f};
    tree.shape = ProxyShape::circle;
    tree.size = {0.4f, 0.4f};
    tree.max_length = 3.0f;
    ShadowProxy own;
    own.position = {1.0f, 1.0f};
    EXPECT_EQ(scene->shadow_proxies, (std::vector<ShadowProxy>{own, tree}));
}

TEST(SceneLoader, TreesAreWallsByDefault) {
    TempDir dir;
    write_text(dir.file("small.map"), "type octile\nheight 1\nwidth 2\nmap\nT.\n");
    auto scene = parse_scene(
        R"({"lantern_scene": 1, "world": {"map": "small.map"}, "view": {"center": [0, 0]}})",
        "t.json", dir.path().string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->walls.cells, (std::vector<std::uint8_t>{1, 0}));
    EXPECT_TRUE(scene->shadow_proxies.empty());
}

TEST(SceneLoader, RowsSceneReadsNoOtherFile) {
    auto scene = parse_scene(R"({"lantern_scene": 1, "world": {"rows": ["#."]}, "view": {"center": [0, 0]}})", "t.json",
                             ".");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->inputs.empty());
}

TEST(SceneLoader, MissingMapFileNamesTheMapValueAndTheOsError) {
    TempDir dir;
    const std::string text =
        R"({"lantern_scene": 1, "world": {"map": "nope.map"}, "view": {"center": [0, 0]}})";
    EXPECT_EQ(parse_scene_error(text, dir.path().string()),
              "t.json:1:39: world.map: " + dir.file("nope.map") +
                  ": cannot open: No such file or directory");
}

TEST(SceneLoader, MapFileErrorsNameTheMapFile) {
    TempDir dir;
    write_text(dir.file("bad.map"), "type octile\nheight 1\nwidth 2\nmap\n.s\n");
    const std::string text =
        R"({"lantern_scene": 1, "world": {"map": "bad.map"}, "view": {"center": [0, 0]}})";
    const std::string message = parse_scene_error(text, dir.path().string());
    EXPECT_TRUE(message.starts_with(dir.file("bad.map") + ":5:2: unknown map character 's'"))
        << message;
    const std::string with_option =
        R"({"lantern_scene": 1, "world": {"map": "bad.map", "extra_floor_chars": "s"}, "view": {"center": [0, 0]}})";
    auto scene = parse_scene(with_option, "t.json", dir.path().string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->walls.cells, (std::vector<std::uint8_t>{0, 0}));
}

TEST(SceneLoader, MissingSceneFileIsBadInput) {
    TempDir dir;
    auto scene = load_scene(dir.file("none.json"));
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.error().message,
              dir.file("none.json") + ": cannot open: No such file or directory");
    EXPECT_EQ(scene.error().exit_code, 2);
}

TEST(SceneLoader, LoadsARealMapScene) {
    const auto shared = lantern::test::shared_dir();
    if (shared.empty()) GTEST_SKIP() << "../shared is absent";
    TempDir dir;
    const std::string map = (shared / "maps/dao/den312d.map").string();
    write_text(dir.file("den.json"), R"({"lantern_scene": 1, "world": {"map": ")" + map +
                                         R"(", "trees": "proxy"}, "view": {"center": [32, 40]},
        "point_lights": [{"position": [30.5, 41.5], "color": [1.0, 0.6, 0.3], "intensity": 2.0, "radius": 10.0}]})");
    auto scene = load_scene(dir.file("den.json"));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->walls.width, 65);
    EXPECT_EQ(scene->walls.height, 81);
    EXPECT_EQ(scene->shadow_proxies.size(), 2565u); // one per 'T' of den312d.map
    EXPECT_EQ(scene->point_lights.size(), 1u);
}

TEST(SceneLoader, TheExampleInTheDocsLoads) {
    const std::string docs =
        lantern::test::read_file(lantern::test::source_dir() / "docs/scenes.md");
    const std::size_t begin = docs.find("```json\n");
    ASSERT_NE(begin, std::string::npos);
    const std::size_t end = docs.find("```", begin + 8);
    ASSERT_NE(end, std::string::npos);
    // Its map is one of the example maps every clone has (game/maps/keep.map).
    auto scene = parse_scene(docs.substr(begin + 8, end - begin - 8), "scenes.md", lantern::test::source_dir().string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->walls.width, 64);
    EXPECT_EQ(scene->shadow_proxies.size(), 1u + 42u); // its own proxy, then the trees
    EXPECT_EQ(scene->gi, GiSettings{});                  // the example spells out the defaults
}

// ---- materials (seed 004's meta pass; docs/scenes.md, "Materials") ----------------------

TEST(SceneLoader, TheWorldKeepsItsBakeSettings) {
    const Scene s = parse_scene_ok(R"({"lantern_scene": 1, "world": {"rows": ["#."]}, "view": {"center": [1, 0]},
        "bake": {"resolution": 2, "margin": 8, "rays": 64, "face_rays": 32, "solver": "seed002", "falloff": 6,
                 "ambient": 0.05, "directional": false, "sun_keys": 9, "eps": 0.05, "max_level": 2}})");
    BakeSettings want;
    want.resolution = 2;
    want.margin = 8;
    want.rays = 64;
    want.face_rays = 32;
    want.solver = BakeSolver::seed002;
    want.falloff = 6.0f;
    want.ambient = 0.05f;
    want.directional = false;
    want.sun_keys = 9;
    want.eps = 0.05f;
    want.max_level = 2;
    EXPECT_EQ(s.bake, want);
    // Seed 004's texel density per chunk: regions of chunks at their own resolution.
    const Scene d = parse_scene_ok(R"({"lantern_scene": 1, "world": {"rows": ["#."]}, "view": {"center": [1, 0]},
        "bake": {"resolution": 2, "density": [{"min": [0, 0], "max": [3, 1], "resolution": 1},
                                              {"min": [2, -1], "max": [2, 0], "resolution": 8}]}})");
    ASSERT_EQ(d.bake.density.size(), 2u);
    EXPECT_EQ(d.bake.density[0], (BakeDensity{{0, 0}, {3, 1}, 1}));
    EXPECT_EQ(d.bake.resolution_at(1, 1), 1);
    EXPECT_EQ(d.bake.resolution_at(2, 0), 8); // the last region holding a chunk wins
    EXPECT_EQ(d.bake.resolution_at(2, -1), 8);
    EXPECT_EQ(d.bake.resolution_at(4, 0), 2); // in no region: the world's
    EXPECT_EQ(d.bake.resolution_at(0, -1), 2);
    // Seed 004's pulsing emission.
    const Scene p = parse_scene_ok(R"({"lantern_scene": 1, "world": {"rows": ["#L."]}, "view": {"center": [1, 0]},
        "materials": [{"name": "lava", "emission": [1, 0.3, 0], "pulse": 0.25, "symbol": "L"}]})");
    EXPECT_EQ(p.materials[0].pulse, 0.25f);
    EXPECT_EQ(pulse_frequency(p.materials), 0.25f);
    EXPECT_FLOAT_EQ(pulse_factor(0.25f, 0.0), 1.0f);
    EXPECT_NEAR(pulse_factor(0.25f, 2.0), 0.0f, 1e-6f);
    EXPECT_NEAR(pulse_factor(0.25f, 1.0), 0.5f, 1e-6f);
    EXPECT_EQ(pulse_factor(0.0f, 1.0), 1.0f);
    EXPECT_EQ(parse_scene_ok(R"({"lantern_scene": 1, "world": {"rows": ["#."]}, "view": {"center": [1, 0]}})").bake,
              BakeSettings{});
}

TEST(SceneLoader, MaterialsColourRowsByTheirSymbolsAndRegions) {
    const Scene s = parse_scene_ok(R"({"lantern_scene": 1,
        "materials": [{"name": "red_rock", "albedo": [0.8, 0.1, 0.1], "symbol": "R"},
                      {"name": "lava", "albedo": [0.2, 0.05, 0.0], "emission": [4, 1, 0.2], "gi": "realtime",
                       "opacity": 0.25}],
        "material_regions": [{"material": "lava", "min": [11, 20], "max": [11, 21]},
                             {"material": "red_rock", "min": [-1000000, 21], "max": [1000000, 21]}],
        "world": {"rows": ["#R.#", "##.R", "#..#"], "origin": [10, 20]},
        "view": {"center": [12, 21]}})");
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].name, "red_rock");
    EXPECT_EQ(s.materials[0].albedo, glm::vec3(0.8f, 0.1f, 0.1f));
    EXPECT_EQ(s.materials[0].emission, glm::vec3(0.0f));
    EXPECT_EQ(s.materials[1].emission, glm::vec3(4.0f, 1.0f, 0.2f));
    EXPECT_EQ(s.materials[0].emission_gi, EmissionGi::baked);
    EXPECT_EQ(s.materials[0].opacity, 1.0f);
    EXPECT_EQ(s.materials[1].emission_gi, EmissionGi::realtime);
    EXPECT_EQ(s.materials[1].opacity, 0.25f);
    const std::uint8_t d = default_wall_cell, red = material_cell(0), lava = material_cell(1);
    // Row 0: the region made (11, 20) lava; row 1: the second region made every wall red,
    // after the first made (11, 21) lava; floor stays floor.
    const std::vector<std::uint8_t> expected{d, lava, 0, d, red, red, 0, red, d, 0, 0, d};
    EXPECT_EQ(s.walls.cells, expected);
    EXPECT_TRUE(s.walls.is_wall_tile(11, 20));
}

TEST(SceneLoader, MaterialRegionsColourMapWalls) {
    TempDir dir;
    write_text(dir.file("a.map"), "type octile\nheight 2\nwidth 3\nmap\n@.@\n@@.\n");
    write_text(dir.file("s.json"), R"({"lantern_scene": 1, "world": {"map": "a.map"},
        "materials": [{"name": "moss", "albedo": [0.2, 0.6, 0.2]}],
        "material_regions": [{"material": "moss", "min": [1, 0], "max": [2, 1]}],
        "view": {"center": [1, 1]}})");
    auto scene = load_scene(dir.file("s.json"));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const std::uint8_t moss = material_cell(0);
    EXPECT_EQ(scene->walls.cells, (std::vector<std::uint8_t>{1, 0, moss, 1, moss, 0}));
}

INSTANTIATE_TEST_SUITE_P(
    Materials, SceneErrors,
    testing::Values(
        SceneErrorCase{scene_with(R"("materials": [{"albedo": [1, 1, 1]}])"),
                       "t.json:2:15: materials[0].name: required key is missing"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "red rock"}])"),
                       "t.json:2:24: materials[0].name: must be 1 to 64 letters, digits or '_', got \"red rock\""},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a"}, {"name": "a"}])"),
                       "t.json:2:39: materials[1].name: material \"a\" is defined twice"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "albedo": [1.5, 0, 0]}])"),
                       "t.json:2:40: materials[0].albedo[0]: must be in [0, 1], got 1.5"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "emission": [0, -1, 0]}])"),
                       "t.json:2:45: materials[0].emission[1]: must be >= 0, got -1"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "symbol": "#"}])"),
                       "t.json:2:39: materials[0].symbol: must be one printable ASCII character other than '#', "
                       "'.' and space, got \"#\""},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "symbol": "ab"}])"),
                       "t.json:2:39: materials[0].symbol: must be one printable ASCII character other than '#', "
                       "'.' and space, got \"ab\""},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "symbol": "x"}, {"name": "b", "symbol": "x"}])"),
                       "t.json:2:69: materials[1].symbol: symbol 'x' is taken by material \"a\""},
        SceneErrorCase{scene_with(R"("point_lights": [{"position": [1, 1], "indirect": 0}])"),
                       "t.json:2:51: point_lights[0].indirect: only a light whose bounce is baked takes an indirect "
                       "multiplier (\"mode\": \"mixed\" or \"baked\"): the live methods' bounce is not per light"},
        SceneErrorCase{scene_with(R"("directional_lights": [{"direction": [0, -1, 0], "indirect": 2}])"),
                       "t.json:2:62: directional_lights[0].indirect: only a light whose bounce is baked takes an indirect "
                       "multiplier (\"mode\": \"mixed\" or \"baked\"): the live methods' bounce is not per light"},
        SceneErrorCase{scene_with(R"("emissive_lights": [{"position": [1, 1], "mode": "baked", "indirect": -1}])"),
                       "t.json:2:71: emissive_lights[0].indirect: must be in [0, 1000], got -1"},
        SceneErrorCase{scene_with(R"("shadow_proxies": [{"position": [1, 1], "static": 1}])"),
                       "t.json:2:51: shadow_proxies[0].static: expected true or false, got a number"},
        SceneErrorCase{scene_with(R"("bake": {"resolution": 17})"), "t.json:2:24: bake.resolution: must be an integer in [1, 16], got 17"},
        SceneErrorCase{scene_with(R"("bake": {"sun_keys": 33})"), "t.json:2:22: bake.sun_keys: must be an integer in [0, 32], got 33"},
        SceneErrorCase{scene_with(R"("bake": {"sun_keys": 1})"),
                       "t.json:2:22: bake.sun_keys: must be 0 or an integer in [2, 32] (one key cannot blend), got 1"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "emission": [1, 0, 0], "gi": "realtime", "pulse": 1}])"),
                       "t.json:2:79: materials[0].pulse: only a baked glow pulses (\"gi\": \"baked\"): its light is baked apart and scaled at run time"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "pulse": 1}, {"name": "b", "pulse": 2}])"),
                       "t.json:2:65: materials[1].pulse: every pulsing material pulses at one frequency (the bake keeps one pulsing part); \"a\" pulses at 1 Hz"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "pulse": 61}])"),
                       "t.json:2:38: materials[0].pulse: must be in [0, 60], got 61"},
        SceneErrorCase{scene_with(R"("bake": {"density": [{"min": [0, 0], "max": [1, 1], "resolution": 0}]})"),
                       "t.json:2:67: bake.density[0].resolution: must be an integer in [1, 16], got 0"},
        SceneErrorCase{scene_with(R"("bake": {"density": [{"min": [2, 0], "max": [1, 1], "resolution": 2}]})"),
                       "t.json:2:45: bake.density[0].max: must not be below min in x or z"},
        SceneErrorCase{scene_with(R"("bake": {"density": [{"min": [0, 0], "resolution": 2}]})"),
                       "t.json:2:22: bake.density[0].max: required key is missing"},
        SceneErrorCase{scene_with(R"("bake": {"density": {"min": [0, 0]}})"),
                       "t.json:2:21: bake.density: expected an array, got an object"},
        SceneErrorCase{scene_with(R"("bake": {"solver": "radiosity"})"),
                       "t.json:2:20: bake.solver: expected one of \"gather\", \"seed002\", got \"radiosity\""},
        SceneErrorCase{scene_with(R"("bake": {"max_level": 4})"), "t.json:2:23: bake.max_level: must be an integer in [0, 3], got 4"},
        SceneErrorCase{scene_with(R"("bake": {"falloff": 0})"), "t.json:2:21: bake.falloff: must be in [0.015625, 4096], got 0"},
        SceneErrorCase{scene_with(R"("bake": {"spacing": 1})"), "t.json:2:10: bake.spacing: unknown key 'spacing' in bake"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "gi": "live"}])"),
                       "t.json:2:35: materials[0].gi: expected one of \"baked\", \"realtime\", \"none\", got \"live\""},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "opacity": 1.5}])"),
                       "t.json:2:40: materials[0].opacity: must be in [0, 1], got 1.5"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a", "glow": 1}])"),
                       "t.json:2:29: materials[0].glow: unknown key 'glow' in materials[0]"},
        SceneErrorCase{scene_with(R"("materials": {"name": "a"})"),
                       "t.json:2:14: materials: expected an array, got an object"},
        SceneErrorCase{scene_with(R"("material_regions": [{"material": "b", "min": [0, 0], "max": [1, 1]}])"),
                       "t.json:2:35: material_regions[0].material: unknown material \"b\" (not in \"materials\")"},
        SceneErrorCase{scene_with(R"("materials": [{"name": "a"}], "material_regions": [{"material": "a", "min": [0, 0], "max": [1, -1]}])"),
                       "t.json:2:92: material_regions[0].max: must not be below min in x or z"},
        SceneErrorCase{scene_with(R"("material_regions": [{"material": "a", "min": [0.5, 0], "max": [1, 1]}])"),
                       "t.json:2:48: material_regions[0].min[0]: expected an integer, got 0.5"},
        SceneErrorCase{"{\"lantern_scene\": 1, \"materials\": [{\"name\": \"r\", \"symbol\": \"R\"}],\n"
                       "\"world\": {\"rows\": [\"#RG\"]}, \"view\": {\"center\": [0, 0]}}",
                       "t.json:2:23: world.rows[0]: unknown cell character 'G' (rows use '#' for wall, '.' for "
                       "floor and the symbols of \"materials\")"}));

TEST(SceneLoader, MoreMaterialsThanCellValuesAreRefused) {
    std::string list;
    for (int i = 0; i <= max_materials; ++i) list += (i ? ", " : "") + std::string("{\"name\": \"m") + std::to_string(i) + "\"}";
    EXPECT_EQ(parse_scene_error(scene_with("\"materials\": [" + list + "]")),
              "t.json:2:14: materials: has 255 materials, above the limit of 254");
}

TEST(SceneLoader, LightModesAreRealtimeUnlessSaid) {
    const Scene s = parse_scene_ok(scene_with(R"("point_lights": [{"position": [0, 0]}, {"position": [1, 0], "mode": "mixed"}],
        "emissive_lights": [{"position": [0, 0], "mode": "baked"}],
        "directional_lights": [{"direction": [0, -1, 0], "mode": "mixed"}])"));
    ASSERT_EQ(s.point_lights.size(), 2u);
    EXPECT_EQ(s.point_lights[0].mode, LightMode::realtime);
    EXPECT_EQ(s.point_lights[1].mode, LightMode::mixed);
    EXPECT_EQ(s.emissive_lights[0].mode, LightMode::baked);
    EXPECT_EQ(s.directional_lights[0].mode, LightMode::mixed);
    EXPECT_EQ(parse_scene_error(scene_with(R"("point_lights": [{"position": [0, 0], "mode": "static"}])")),
              "t.json:2:47: point_lights[0].mode: expected one of \"realtime\", \"mixed\", \"baked\", got \"static\"");
}
