// The day's sun path (the game's day cycle; docs/baked.md, "The moving sun"): where the sun
// is at each time of day, and its light. A bake's sun keys (scene::BakeSettings::sun_keys)
// hold a mixed sun's bounce at times along this path; the run time blends the two keys around
// the sun's direction.
//
// Time of day: 0 midnight, 0.25 sunrise, 0.5 noon, 0.75 sunset (wrapping at 1).
#pragma once

#include <glm/vec3.hpp>

namespace lantern::scene {

inline constexpr float day_sunrise = 0.25f, day_sunset = 0.75f;

// The sun's travel direction at `time_of_day` (unit length): it rises in the east (+x) and
// sets in the west, leaning south (-z). Below the horizon (y >= 0) at night.
glm::vec3 day_sun_direction(float time_of_day);
// Its colour x intensity: warm at dawn and dusk, 0.6 at noon, 0 at night.
glm::vec3 day_sun_light(float time_of_day);
// The time of day between sunrise and sunset whose path direction has the azimuth of
// `direction` in the path's plane (the inverse of day_sun_direction over the day; a
// direction off the path takes the nearest such time). Clamped to [sunrise, sunset].
float day_time_of(glm::vec3 direction);
// Key k of `keys` (>= 2): sunrise + k / (keys - 1) of the day, so the first key is at
// sunrise and the last at sunset.
float sun_key_time(int k, int keys);

// Where a direction falls between the keys: the key below (0 .. keys - 2) and the weight of
// the one above (0..1), for day_time_of(direction).
struct SunKeyBlend {
    int key = 0;
    float blend = 0.0f;
};
SunKeyBlend sun_key_blend(glm::vec3 direction, int keys);

} // namespace lantern::scene
