// Distance to the nearest wall for game code (AI, sound, lasers): the radiosity method's
// distance field (seed 003's jump flood, radiosity.hpp) on the CPU, over the GI window at the
// radiosity grid's resolution (gi.radiosity.scale).
//
// It is built by the reference passes from the walls and the window, so it equals the GPU's
// distance_field texture texel by texel (tests/gi/radiosity_test.cpp) and a query never waits
// on the GPU: no read-back. The frame systems keep one up to date as the world resource
// systems::WallDistanceField (rebuilt when the walls or the window change).
//
// Threads: build() may run on any thread (with options.jobs, rows in parallel); a built
// WallDistance is immutable, and its queries are safe from any thread.
#pragma once

#include "lantern/gi/radiosity.hpp"

#include <glm/vec2.hpp>

namespace lantern::gi {

class WallDistance {
  public:
    WallDistance() = default;
    static WallDistance build(const FrameInputs& in, const RefOptions& options = {});

    bool empty() const { return field_.width == 0; }
    // Whether `p` (world x, z) lies in the window the field covers.
    bool covers(glm::vec2 p) const;
    // World units from the centre of p's grid texel to the centre of the nearest wall texel
    // (0 inside a wall); +infinity outside the window or when it holds no wall. A wall's
    // surface is about half a grid texel nearer.
    float distance(glm::vec2 p) const;
    // The unit direction from p's grid texel towards that wall texel (a normal map: bounce a
    // laser, steer away); (0, 0) inside a wall, outside the window or without walls.
    glm::vec2 direction(glm::vec2 p) const;

    const HeatGrid& grid() const { return grid_; }
    const Texture& field() const { return field_; } // as distance_field: distance (texels), direction, 0

  private:
    bool texel_of(glm::vec2 p, int& i, int& j) const;
    HeatGrid grid_;
    Texture field_;
};

} // namespace lantern::gi
