// What the world renderer draws this frame: the ground, the walls in view, props, torches,
// the player and the cursor highlight, as boxes (world_renderer.hpp).
#pragma once

#include "lantern/game/baking.hpp"
#include "lantern/game/game_components.hpp"
#include "lantern/game/gameplay.hpp"
#include "lantern/game/world_renderer.hpp"
#include "lantern/systems/streaming.hpp"

namespace lantern::game {

struct DrawContext {
    scene::PerspectiveCamera camera;
    float wall_height = 2.0f;
    double time = 0.0;
    // The walls' materials (cell value 2 + k): lava and crystal glow in their colour.
    const std::vector<scene::Material>* materials = nullptr;
    // The baked light probes (lights the player and props from the direction the baked light
    // comes from); nullptr without baked light.
    const BakedChunks* probes = nullptr;
    // The tile under the cursor and whether the player can act on it (highlighted).
    std::optional<glm::ivec2> cursor_tile;
    bool cursor_on_wall = false;
};

// Appends the world's boxes in view (walls from the streaming mirror) to `out`.
void build_draw_list(ecs::World& world, const systems::Streaming& streaming, const DrawContext& context, DrawList& out);

// The tile the cursor points at, as interaction picks it (wall first, else ground), when
// within the player's reach.
std::optional<std::pair<glm::ivec2, bool>> cursor_target(const Controls& controls, const scene::PerspectiveCamera& camera,
                                                         glm::vec2 player, float wall_height, const IsWall& is_wall);

} // namespace lantern::game
