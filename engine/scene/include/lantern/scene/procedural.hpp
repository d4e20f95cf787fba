// Seeded procedural caves for worlds of unbounded size.
//
// Whether a tile is a wall depends only on (x, z, seed): any rectangle of the world can be
// generated on its own, in any order, on any thread, and always comes out the same (the
// streaming system loads chunks this way). The caves are fractal value noise (three
// octaves, 24/12/6 tiles) thresholded to about 45 % walls, giving open chambers joined by
// winding passages.
#pragma once

#include "lantern/scene/scene.hpp"

#include <cstdint>

namespace lantern::scene {

struct CaveParams {
    std::uint32_t seed = 1;
    float wall_threshold = 0.52f; // noise above this is wall; lower = more walls
};

bool cave_wall(int x, int z, const CaveParams& params);
// The rectangle [origin, origin + size) of the cave world as a WallGrid.
WallGrid generate_caves(glm::ivec2 origin, glm::ivec2 size, const CaveParams& params);

} // namespace lantern::scene
