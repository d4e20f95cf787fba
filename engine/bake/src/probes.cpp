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

glm::vec3 CircularHarmonics::irradiance(float phi) const { return irradiance(phi, 2); }

glm::vec3 CircularHarmonics::irradiance(float phi, int order) const {
    constexpr float pi = std::numbers::pi_v<float>;
    glm::vec3 e = c[0] / pi + (c[1] * std::cos(phi) + c[2] * std::sin(phi)) * 0.5f;
    if (order >= 2) e += (c[3] * std::cos(2.0f * phi) + c[4] * std::sin(2.0f * phi)) * (2.0f / (3.0f * pi));
    return glm::max(e, glm::vec3(0.0f));
}

glm::vec3 ProbeSamples::irradiance(float phi) const {
    glm::vec3 e(0.0f);
    for (std::size_t i = 0; i < theta.size(); ++i) e += flux[i] * std::max(0.0f, std::cos(theta[i] - phi));
    return e;
}

void ProbeOrderError::add(const CircularHarmonics& h, const ProbeSamples& s, int angles) {
    constexpr double two_pi = 2.0 * std::numbers::pi;
    double probe_exact2 = 0.0;
    std::array<double, 2> probe_err2{};
    for (int a = 0; a < angles; ++a) {
        const float phi = float(two_pi * a / angles);
        const glm::vec3 want = s.irradiance(phi);
        for (int order = 1; order <= 2; ++order) {
            const glm::vec3 got = h.irradiance(phi, order);
            for (int ch = 0; ch < 3; ++ch) {
                const double d = double(got[ch]) - double(want[ch]);
                err2[std::size_t(order - 1)] += d * d;
                err1[std::size_t(order - 1)] += std::abs(d);
                probe_err2[std::size_t(order - 1)] += d * d;
            }
        }
        for (int ch = 0; ch < 3; ++ch) {
            exact2 += double(want[ch]) * double(want[ch]);
            exact1 += double(want[ch]);
            probe_exact2 += double(want[ch]) * double(want[ch]);
        }
        ++samples;
    }
    ++probes;
    if (probe_exact2 > 0.0)
        for (std::size_t o = 0; o < 2; ++o) worst_probe[o] = std::max(worst_probe[o], std::sqrt(probe_err2[o] / probe_exact2));
}

double ProbeOrderError::relative_rms(int order) const {
    return exact2 > 0.0 ? std::sqrt(err2[std::size_t(order - 1)] / exact2) : 0.0;
}
double ProbeOrderError::relative_mean_abs(int order) const {
    return exact1 > 0.0 ? err1[std::size_t(order - 1)] / exact1 : 0.0;
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
