// What the world renderer draws this frame: the ground, the walls in view, props, torches,
// the player and the cursor highlight, as boxes (world_renderer.hpp).
#pragma once

#include "lantern/game/baking.hpp"
#include "lantern/game/game_components.hpp"
#include "lantern/game/gameplay.hpp"
#include "lantern/game/world_renderer.hpp"
#include "lantern/systems/streaming.hpp"
#include "lantern/texel/texel.hpp"

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
    // The GI's live probes (gi.probe_rays > 0): records carry the object's anchor, and the
    // vertex stage adds the live probes there (world_renderer.hpp ProbeRecord).
    bool live_probes = false;
    // The tile under the cursor and whether the player can act on it (highlighted).
    std::optional<glm::ivec2> cursor_tile;
    bool cursor_on_wall = false;
    // The player, trees, lamp posts and torch sticks as texel_lit boxes with a TexelPart each
    // (app/texel_world.hpp); off: lit per pixel as before.
    bool texel_lighting = false;
};

// How far a tree's crown sways in the wind (tiles; crown_sway is within it on each axis).
inline constexpr float crown_sway_tiles = 0.05f;
// The crown's offset on the ground (x, z) at `time` (seconds) for a tree standing at `at`.
glm::vec2 crown_sway(double time, glm::vec2 at);

// Fills `out` (emptied first: the frame's list is reused) with the world's boxes in view
// (walls from the streaming mirror).
void build_draw_list(ecs::World& world, const systems::Streaming& streaming, const DrawContext& context, DrawList& out);

// The lights the texel passes light the models by this frame (nothing without
// context.texel_lighting): point lights and emissive lights whose range reaches the view (the
// 32 nearest the view's centre), at their height (emissive lights at 0.3, without shadows;
// lamp posts' shadows blurred, the rest hard). Baked-mode lights are marked texel::as_baked
// while a bake is in use (context.probes). The frame's suns are the GI's (record_world).
void gather_texel_lights(ecs::World& world, const DrawContext& context, std::vector<texel::TexelLight>& out);

// The tile the cursor points at, as interaction picks it (wall first, else ground), when
// within the player's reach.
std::optional<std::pair<glm::ivec2, bool>> cursor_target(const Controls& controls, const scene::PerspectiveCamera& camera,
                                                         glm::vec2 player, float wall_height, const IsWall& is_wall);

} // namespace lantern::game
