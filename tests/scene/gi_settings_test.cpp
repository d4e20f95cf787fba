#include "lantern/scene/loader.hpp"

#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace lantern::scene;

namespace {

Scene view_scene() {
    return lantern::test::parse_scene_ok(lantern::test::scene_with(R"("gi": {})"));
}

std::string override_error(Scene& scene, std::string_view assignment) {
    const Scene before = scene;
    auto result = apply_override(scene, assignment);
    if (result.ok()) return "(applied)";
    EXPECT_EQ(result.error().exit_code, 2);
    EXPECT_EQ(scene, before) << "a failed override changed the scene";
    return result.error().message;
}

} // namespace

TEST(GiOverride, SetsEachKindOfValue) {
    Scene scene = view_scene();
    GiSettings expected = scene.gi;
    ASSERT_TRUE(apply_override(scene, "gi.resolution=16").ok());
    expected.resolution = 16;
    EXPECT_EQ(scene.gi, expected);
    ASSERT_TRUE(apply_override(scene, "gi.padding=2.5").ok());
    expected.padding = 2.5f;
    EXPECT_EQ(scene.gi, expected);
    ASSERT_TRUE(apply_override(scene, "gi.blur=false").ok());
    expected.blur = false;
    EXPECT_EQ(scene.gi, expected);
    ASSERT_TRUE(apply_override(scene, "gi.tone_map=reinhard").ok());
    expected.tone_map = ToneMap::reinhard;
    EXPECT_EQ(scene.gi, expected);
    ASSERT_TRUE(apply_override(scene, "gi.tone_map=\"reinhard_white\"").ok());
    expected.tone_map = ToneMap::reinhard_white;
    EXPECT_EQ(scene.gi, expected);
    ASSERT_TRUE(apply_override(scene, "gi.heat_scale=quarter").ok());
    expected.heat_scale = HeatScale::quarter;
    EXPECT_EQ(scene.gi, expected);
    ASSERT_TRUE(apply_override(scene, "gi.ao.radius=2").ok());
    expected.ao.radius = 2.0f;
    EXPECT_EQ(scene.gi, expected);
    ASSERT_TRUE(apply_override(scene, "gi.ao.enabled=false").ok());
    expected.ao.enabled = false;
    EXPECT_EQ(scene.gi, expected);
}

TEST(GiOverride, ChangesNothingButGi) {
    Scene scene = view_scene();
    Scene expected = scene;
    ASSERT_TRUE(apply_override(scene, "gi.max_lights=7").ok());
    expected.gi.max_lights = 7;
    EXPECT_EQ(scene, expected);
}

struct OverrideCase {
    const char* assignment;
    const char* message;
};

class GiOverrideErrors : public testing::TestWithParam<OverrideCase> {};

TEST_P(GiOverrideErrors, NameTheKeyAndLeaveTheSceneUnchanged) {
    Scene scene = view_scene();
    EXPECT_EQ(override_error(scene, GetParam().assignment), GetParam().message);
}

INSTANTIATE_TEST_SUITE_P(
    GiOverride, GiOverrideErrors,
    testing::Values(
        OverrideCase{"gi.padding=1e3", "--set gi.padding: must be in [1, 8], got 1000"},
        OverrideCase{"gi.resolution=8.5", "--set gi.resolution: expected an integer, got 8.5"},
        OverrideCase{"gi.resolution=0",
                     "--set gi.resolution: must be an integer in [1, 32], got 0"},
        OverrideCase{"gi.diffusion_rate=2", "--set gi.diffusion_rate: must be in [0, 1.25], got 2 "
                                            "(above 1.25 the heat blend exceeds 1 "
                                            "and the diffusion overshoots; see docs/gi.md)"},
        OverrideCase{"gi.blur=yes", "--set gi.blur: expected true or false, got a string"},
        OverrideCase{"gi.tone_map=filmic", "--set gi.tone_map: expected one of \"none\", "
                                           "\"reinhard\", \"reinhard_white\", \"aces\", got "
                                           "\"filmic\""},
        OverrideCase{"gi.ao.radius=9", "--set gi.ao.radius: must be in (0, 8], got 9"},
        OverrideCase{"gi.method=cascades",
                     "--set gi.method: expected one of \"heat\", \"radiosity\", \"gather\", got \"cascades\""},
        OverrideCase{"gi.wall_albedo=1.5", "--set gi.wall_albedo: must be in [0, 1], got 1.5"},
        OverrideCase{"gi.gather.bounces=0", "--set gi.gather.bounces: must be an integer in [1, 64], got 0"},
        OverrideCase{"gi.radiosity.feedback=1", "--set gi.radiosity.feedback: must be in [0, 1), got 1 (at 1 a "
                                                "closed room's light grows without bound; see docs/gi.md)"},
        OverrideCase{"gi.radiosity.rays=0", "--set gi.radiosity.rays: must be an integer in [1, 256], got 0"},
        OverrideCase{"gi.radiosity.noise=white", "--set gi.radiosity.noise: expected one of \"rotate\", \"golden\", "
                                                 "\"off\", got \"white\""},
        OverrideCase{
            "gi.resoluton=8",
            "--set gi.resoluton: unknown key 'resoluton' in gi (did you mean 'resolution'?)"},
        OverrideCase{"gi.ao.radus=1",
                     "--set gi.ao.radus: unknown key 'ao.radus' in gi (did you mean 'ao.radius'?)"},
        OverrideCase{
            "gi.ao=1",
            "--set gi.ao: is an object; set its keys one at a time: gi.ao.enabled gi.ao.radius "
            "gi.ao.power gi.ao.strength gi.ao.dither gi.ao.walls"},
        OverrideCase{"gi.resolution", "--set gi.resolution: expected gi.KEY=VALUE"},
        OverrideCase{"gi.padding=",
                     "--set gi.padding: '' is neither a JSON value nor a bare word (such as aces)"},
        OverrideCase{
            "gi.padding=1.2.3",
            "--set gi.padding: '1.2.3' is neither a JSON value nor a bare word (such as aces)"},
        OverrideCase{"gi.padding=[1]", "--set gi.padding: expected a number, got an array"},
        OverrideCase{"view.size=3",
                     "--set view.size: only gi keys can be set (--set gi.KEY=VALUE)"},
        OverrideCase{"resolution=3",
                     "--set resolution: only gi keys can be set (--set gi.KEY=VALUE)"},
        OverrideCase{"gi.=3", "--set gi.: unknown key '' in gi"}));

TEST(GiOverride, ChecksTheGiWindowOfATopDownView) {
    Scene scene = view_scene(); // 30 x 16.875 world units at padding 1.4
    ASSERT_TRUE(apply_override(scene, "gi.resolution=32").ok());
    EXPECT_EQ(override_error(scene, "gi.padding=8"), "(applied)");
    std::get<OrthoView>(scene.view).size = {300.0f, 10.0f};
    EXPECT_EQ(override_error(scene, "gi.resolution=31"),
              "--set gi.resolution: the GI texture would be 74400 x 2480 texels (view.size x "
              "gi.padding x "
              "gi.resolution), above the limit of 65536 per side");
}

TEST(GiOverride, LeavesCameraWindowsToTheGiCode) {
    Scene scene = lantern::test::parse_scene_ok(R"({"lantern_scene": 1, "world": {"rows": ["."]},
        "camera": {"position": [0, 100, 0], "target": [0, 0, 1]}})");
    EXPECT_TRUE(apply_override(scene, "gi.resolution=32").ok());
    EXPECT_TRUE(apply_override(scene, "gi.padding=8").ok());
}

TEST(ValidateGiSettings, AcceptsTheDefaults) {
    EXPECT_TRUE(validate_gi_settings(GiSettings{}).ok());
}

TEST(ValidateGiSettings, ReportsTheFirstFieldOutOfRange) {
    GiSettings gi;
    gi.ao.strength = 2.0f;
    gi.max_lights = -1;
    auto result = validate_gi_settings(gi);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message, "gi.ao.strength: must be in [0, 1], got 2");
    EXPECT_EQ(result.error().exit_code, 2);
}

TEST(ValidateGiSettings, RejectsNanInfinityAndUnnamedEnumValues) {
    GiSettings nan_padding;
    nan_padding.padding = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(validate_gi_settings(nan_padding).error().message,
              "gi.padding: must be in [1, 8], got nan");
    GiSettings infinite;
    infinite.range_boost = std::numeric_limits<float>::infinity();
    EXPECT_EQ(validate_gi_settings(infinite).error().message,
              "gi.range_boost: inf does not fit a 32-bit float");
    GiSettings bad_enum;
    bad_enum.tone_map = static_cast<ToneMap>(17);
    EXPECT_EQ(validate_gi_settings(bad_enum).error().message,
              "gi.tone_map: expected one of \"none\", \"reinhard\", \"reinhard_white\", \"aces\", "
              "got null");
}
