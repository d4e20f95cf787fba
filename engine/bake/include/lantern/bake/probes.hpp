// Light probes for things that move (seed 004's light probes, in 2D; docs/baked.md,
// "Probes"): the radiance arriving at a point in the ground plane as circular harmonics of
// order 2, five coefficients per channel,
//   L(theta) = a0 / 2pi + sum over k = 1, 2 of (a_k cos k theta + b_k sin k theta) / pi,
// so a0 is the fluence there (what the ground textures hold). A surface facing angle phi
// receives E(phi) = integral of L(theta) max(0, cos(theta - phi)): the clamped cosine's
// coefficients are 2, pi / 2 and 2 / 3, so
//   E(phi) = a0 / pi + (a1 cos phi + b1 sin phi) / 2 + 2 (a2 cos 2 phi + b2 sin 2 phi) / (3 pi),
// clamped at 0 (order 2 rings below 0 behind a single bright direction).
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <vector>

namespace lantern::bake {

struct CircularHarmonics {
    // Per coefficient (a0, a1, b1, a2, b2), RGB.
    std::array<glm::vec3, 5> c{};

    // Adds radiance `l` arriving from angle theta over an arc dtheta (a ray of a gather).
    void add_ray(float theta, glm::vec3 l, float dtheta);
    // Adds a point source of fluence f arriving from angle theta (a delta in direction).
    void add_delta(float theta, glm::vec3 f);
    // Irradiance on a surface whose outward normal in the ground plane has angle phi
    // (atan2(n.z, n.x)), clamped at 0.
    glm::vec3 irradiance(float phi) const;
    // The same from the harmonics up to `order` (1: a0, a1, b1 only; 2: all five).
    glm::vec3 irradiance(float phi, int order) const;
    glm::vec3 fluence() const { return c[0]; }

    CircularHarmonics& operator+=(const CircularHarmonics& o);
    friend CircularHarmonics operator*(const CircularHarmonics& h, float w);
    friend bool operator==(const CircularHarmonics&, const CircularHarmonics&) = default;
};

// What a probe was captured from: its rays' radiance times their arcs and the baked lights'
// fluence, each arriving from an angle theta. The harmonics approximate this; a surface facing
// phi receives exactly the sum of flux x max(0, cos(theta - phi)) from it. Measures the
// harmonics' order (bake_chunk's `samples`, lantern-bake --probe-orders).
struct ProbeSamples {
    std::vector<float> theta;
    std::vector<glm::vec3> flux;

    void add(float angle, glm::vec3 f) {
        theta.push_back(angle);
        flux.push_back(f);
    }
    glm::vec3 irradiance(float phi) const;
};

// How well harmonics of order 1 and 2 give the irradiance of their samples, over probes and
// `angles` surface orientations each: sums to report relative errors from.
struct ProbeOrderError {
    long long probes = 0, samples = 0;
    double exact2 = 0.0;                   // sum of exact irradiance squared (all channels)
    double exact1 = 0.0;                   // sum of exact irradiance
    std::array<double, 2> err2{};          // order 1, 2: sum of squared errors
    std::array<double, 2> err1{};          // order 1, 2: sum of absolute errors
    std::array<double, 2> worst_probe{};   // order 1, 2: the largest probe's relative RMS error
    void add(const CircularHarmonics& h, const ProbeSamples& s, int angles = 64);
    double relative_rms(int order) const;       // sqrt(err2 / exact2)
    double relative_mean_abs(int order) const;  // err1 / exact1
};

} // namespace lantern::bake
