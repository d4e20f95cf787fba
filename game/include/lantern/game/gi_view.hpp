// The HUD's GI views: which GI texture the world renderer draws over the world instead of the
// lit scene (WorldView::gi_view, the --gi-view option, the HUD's "GI views" list).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace lantern::game {

// The HUD's GI views (docs/game.md, "GI views"): instead of the lit scene, every surface shows
// the GI texture under it, seen from above, at that texture's own resolution.
enum class GiDebugView : std::uint8_t {
    lit,         // the game as it is
    direct,      // the direct light (Tex::direct), tone-mapped
    indirect,    // the indirect light (Tex::indirect), tone-mapped
    light_image, // radiosity: the scene image the rays read (emission + feedback x last bounce)
    radiosity,   // radiosity: the raymarch's result on its grid, before blur and upsample
    distance,    // radiosity: the distance field (grid texels; bands every 4, walls black)
    direction,   // radiosity: the direction map (unit vector to the nearest wall as red/green)
    jump_flood,  // radiosity: the jump flood's nearest wall texel per texel (Voronoi cells)
    baked,       // the baked light alone (docs/baked.md), tone-mapped
    bricks,      // the baked light's bricks by level (seed 002's debug view): 0 red, 1 yellow, 2 green, 3 blue
    count
};
// "lit", "direct", ..., "jump_flood" (the --gi-view values and the HUD's list).
std::span<const char* const> gi_debug_view_names();
std::optional<GiDebugView> gi_debug_view_by_name(std::string_view name);

} // namespace lantern::game
