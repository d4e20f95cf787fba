// Seeded procedural caves for worlds of unbounded size.
//
// Whether a tile is a wall depends only on (x, z, seed): any rectangle of the world can be
// generated on its own, in any order, on any thread, and always comes out the same (the
// streaming system loads chunks this way). The caves are fractal value noise (three
// octaves, 24/12/6 tiles) thresholded to about 45 % walls, giving open chambers joined by
// winding passages.
//
// With `minerals`, veins of lava and glowing crystal run through the rock where it meets
// open ground (cave_cell): patches of a fourth, sparser noise, so they come in seams a few
// tiles long. Their materials are cave_materials() (cell material_cell(cave_lava) ...).
#pragma once

#include "lantern/scene/scene.hpp"

#include <cstdint>
#include <vector>

namespace lantern::scene {

struct CaveParams {
    std::uint32_t seed = 1;
    float wall_threshold = 0.52f; // noise above this is wall; lower = more walls
    bool minerals = false;        // lava and crystal in the walls (cave_cell)
};

// The mineral materials, in cell order: cave_lava (material_cell(0)), cave_crystal (1).
inline constexpr int cave_lava = 0, cave_crystal = 1;
// The crystal veins' glow breathes (seed 004's pulsing emission): a cycle every five seconds.
inline constexpr float crystal_pulse_hz = 0.2f;
std::vector<Material> cave_materials();

bool cave_wall(int x, int z, const CaveParams& params);
// The tile's cell value: 0 open, 1 rock, or (params.minerals) a mineral's material cell on
// wall tiles beside open ground.
std::uint8_t cave_cell(int x, int z, const CaveParams& params);
// The rectangle [origin, origin + size) of the cave world as a WallGrid.
WallGrid generate_caves(glm::ivec2 origin, glm::ivec2 size, const CaveParams& params);

} // namespace lantern::scene
