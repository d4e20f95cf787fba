// The day's sun path (lantern/scene/day.hpp): the path the game's day cycle and a bake's sun
// keys share, its inverse and the keys' blend.
#include "lantern/scene/day.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace {

using namespace lantern::scene;

TEST(DayPath, TheSunRisesInTheEastStandsHighAtNoonAndIsDarkAtNight) {
    EXPECT_LT(day_sun_direction(0.5f).y, -0.9f); // noon: from above
    EXPECT_LT(day_sun_direction(0.3f).x, 0.0f);  // morning: travels west (rises in the east)
    EXPECT_GT(day_sun_direction(0.7f).x, 0.0f);
    EXPECT_GT(day_sun_direction(0.0f).y, 0.0f); // midnight: below the horizon
    EXPECT_NEAR(glm::length(day_sun_direction(0.37f)), 1.0f, 1e-6f);
    EXPECT_EQ(day_sun_light(0.0f), glm::vec3(0.0f));
    EXPECT_GT(day_sun_light(0.5f).g, 0.5f);
    EXPECT_GT(day_sun_light(0.28f).r, day_sun_light(0.28f).b); // dawn is warm
}

TEST(DayPath, TheTimeOfADirectionInvertsThePathOverTheDay) {
    for (int k = 0; k <= 100; ++k) {
        const float t = day_sunrise + (day_sunset - day_sunrise) * float(k) / 100.0f;
        EXPECT_NEAR(day_time_of(day_sun_direction(t)), t, 1e-5f) << t;
    }
    // Scaled, or off the path's lean: the same time (the azimuth in the path's plane).
    const glm::vec3 d = day_sun_direction(0.42f);
    EXPECT_NEAR(day_time_of(3.0f * d), 0.42f, 1e-5f);
    EXPECT_NEAR(day_time_of({d.x, d.y, -0.9f}), 0.42f, 1e-5f);
    // Night: the nearer end of the day.
    EXPECT_EQ(day_time_of(day_sun_direction(0.2f)), day_sunrise);
    EXPECT_EQ(day_time_of(day_sun_direction(0.8f)), day_sunset);
    EXPECT_EQ(day_time_of({0.0f, 0.0f, 0.0f}), day_sunrise);
}

TEST(DayPath, KeysSpanTheDayAndTheBlendFindsTheTwoAround) {
    EXPECT_EQ(sun_key_time(0, 5), day_sunrise);
    EXPECT_EQ(sun_key_time(4, 5), day_sunset);
    EXPECT_EQ(sun_key_time(2, 5), 0.5f);
    for (int k = 0; k < 5; ++k) {
        const SunKeyBlend at = sun_key_blend(day_sun_direction(sun_key_time(k, 5)), 5);
        // On a key: that key, or the one below at weight 1 for the last.
        const float u = float(at.key) + at.blend;
        EXPECT_NEAR(u, float(k), 1e-4f) << k;
    }
    const SunKeyBlend mid = sun_key_blend(day_sun_direction(0.4375f), 5); // halfway from key 1 to key 2
    EXPECT_EQ(mid.key, 1);
    EXPECT_NEAR(mid.blend, 0.5f, 1e-4f);
    EXPECT_EQ(sun_key_blend(day_sun_direction(0.5f), 0).key, 0); // no keys: nothing to blend
    const SunKeyBlend night = sun_key_blend(day_sun_direction(0.9f), 3);
    EXPECT_EQ(night.key, 1);
    EXPECT_EQ(night.blend, 1.0f);
}

} // namespace
