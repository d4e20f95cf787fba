// Circular harmonics (probes.hpp).
#include "lantern/bake/probes.hpp"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lantern::bake {

void CircularHarmonics::add_ray(float theta, glm::vec3 l, float dtheta) {
    add_delta(theta, l * dtheta);
}

void CircularHarmonics::add_delta(float theta, glm::vec3 f) {
    c[0] += f;
    c[1] += f * std::cos(theta);
    c[2] += f * std::sin(theta);
    c[3] += f * std::cos(2.0f * theta);
    c[4] += f * std::sin(2.0f * theta);
}

glm::vec3 CircularHarmonics::irradiance(float phi) const {
    constexpr float pi = std::numbers::pi_v<float>;
    const glm::vec3 e = c[0] / pi + (c[1] * std::cos(phi) + c[2] * std::sin(phi)) * 0.5f +
                        (c[3] * std::cos(2.0f * phi) + c[4] * std::sin(2.0f * phi)) * (2.0f / (3.0f * pi));
    return glm::max(e, glm::vec3(0.0f));
}

CircularHarmonics& CircularHarmonics::operator+=(const CircularHarmonics& o) {
    for (std::size_t k = 0; k < c.size(); ++k) c[k] += o.c[k];
    return *this;
}

CircularHarmonics operator*(const CircularHarmonics& h, float w) {
    CircularHarmonics out = h;
    for (glm::vec3& v : out.c) v *= w;
    return out;
}

} // namespace lantern::bake
