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
    glm::vec3 fluence() const { return c[0]; }

    CircularHarmonics& operator+=(const CircularHarmonics& o);
    friend CircularHarmonics operator*(const CircularHarmonics& h, float w);
    friend bool operator==(const CircularHarmonics&, const CircularHarmonics&) = default;
};

} // namespace lantern::bake
