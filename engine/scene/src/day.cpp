#include "lantern/scene/day.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::scene {
namespace {

constexpr float two_pi = 6.28318531f;
constexpr float lean = 0.35f; // the path's lean to the south: z of the unnormalised direction

} // namespace

glm::vec3 day_sun_direction(float time_of_day) {
    const float angle = (time_of_day - day_sunrise) * two_pi; // 0 at sunrise, pi at sunset
    return glm::normalize(glm::vec3(-std::cos(angle), -std::sin(angle), lean));
}

glm::vec3 day_sun_light(float time_of_day) {
    const float elevation = -day_sun_direction(time_of_day).y;
    const float day = std::clamp(elevation * 3.0f, 0.0f, 1.0f);
    const glm::vec3 noon(1.0f, 0.95f, 0.85f), dusk(1.0f, 0.55f, 0.3f);
    // 0.6 at noon: with the ground's bounce on top, a full-strength sun washes the view out.
    return glm::mix(dusk, noon, std::clamp(elevation * 2.0f, 0.0f, 1.0f)) * (day * 0.6f);
}

float day_time_of(glm::vec3 direction) {
    // day_sun_direction's (x, y) is (-cos a, -sin a) scaled alike: a = atan2(-y, -x).
    float angle = std::atan2(-direction.y, -direction.x); // (-pi, pi]; the day is [0, pi]
    if (!std::isfinite(angle)) angle = 0.0f;
    if (angle < 0.0f) angle = direction.x > 0.0f ? two_pi / 2.0f : 0.0f; // night: the nearer end of the day
    return day_sunrise + std::clamp(angle, 0.0f, two_pi / 2.0f) / two_pi;
}

float sun_key_time(int k, int keys) {
    return day_sunrise + (day_sunset - day_sunrise) * float(k) / float(std::max(keys - 1, 1));
}

SunKeyBlend sun_key_blend(glm::vec3 direction, int keys) {
    if (keys < 2) return {};
    const float u = (day_time_of(direction) - day_sunrise) / (day_sunset - day_sunrise) * float(keys - 1);
    const int key = std::clamp(int(std::floor(u)), 0, keys - 2);
    return {key, std::clamp(u - float(key), 0.0f, 1.0f)};
}

} // namespace lantern::scene
