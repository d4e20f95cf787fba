// The shading library: how a surface samples the GI textures. C++ twin of
// shaders/include/lantern/shading.glsl (the game's lit shader and the lit-image pass use
// the GLSL side); keep the two in step, operation for operation.
//
// Routing (seed 000, "Sampling in the Lit shader"):
// - wall faces: a mostly horizontal normal (|n.xz| >= 0.5) on a wall cell: the dominant
//   face's wall-direct + wall-indirect textures, sampled half a GI texel into the wall (with
//   unfolded proxy shadows, wall-direct below the edge height, the upper texture above it);
// - wall tops: an upward normal (n.y >= 0.5, |n.xz| <= 0.35) on a wall cell: the main
//   sun's colour by angle, plus the 3x3 average of the ground indirect light around it;
//   (x the AO of the ground texel just outside the face when gi.ao.walls is on);
// - ground: (direct + indirect + directional bounce) x AO x conduction.
// gi.wall_lighting off routes every surface to the ground (the seed's _WallLightingEnabled):
// wall tiles then shade as ground, which conduction makes black.
// Then the tone map. Every texture is sampled at the texel containing the position
// (clamped to the window): point sampling at texel centres, as the seed snaps.
#pragma once

#include "lantern/gi/reference.hpp"

#include <cstdint>
#include <vector>

namespace lantern::gi {

struct ShadingInputs {
    const FrameInputs* frame = nullptr;
    const Texture* direct = nullptr;
    const Texture* indirect = nullptr; // null: no indirect light
    const Texture* ao = nullptr;       // null: AO off
    const Texture* shadow = nullptr;
    std::array<const Texture*, 4> wall_direct{};
    std::array<const Texture*, 4> wall_indirect{}; // null entries: none
    std::array<const Texture*, 4> wall_upper{};    // gi.proxy_wall_shadows unfold; null: none
};

enum SurfaceKind : int { surface_ground = 0, surface_wall_face = 1, surface_wall_top = 2 };

glm::vec3 tone_map(glm::vec3 color, scene::ToneMap mode, float white_point);
int dominant_face(glm::vec3 normal);
// With wall lighting off (gi.wall_lighting false) every surface is ground, as in the seed.
SurfaceKind classify_surface(const WallView& walls, const GiWindow& window, glm::vec3 pos, glm::vec3 normal,
                             bool wall_lighting = true);
// Linear (before tone mapping) light arriving at the surface.
glm::vec3 surface_light(const ShadingInputs& in, glm::vec3 pos, glm::vec3 normal);
// The bounce part of surface_light (the indirect textures' terms, with AO as it applies
// them): what the game's raster reshapes with seed 002's runtime knobs (shading.glsl's
// surface_bounce; game::reflected_bounce).
glm::vec3 surface_bounce(const ShadingInputs& in, glm::vec3 pos, glm::vec3 normal);
glm::vec3 shade(const ShadingInputs& in, glm::vec3 pos, glm::vec3 normal);

// The lit image of the GI window seen from above, one pixel per GI texel, tone-mapped and
// sRGB-encoded (RGB8). Ground texels show the ground; wall texels show the wall top, except
// a band of max(1, res / 4) texels along each exposed edge, which shows that face (as a
// tilted camera would glimpse it). Rows from min z.
struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
};
// Surface position and normal that the top-down image shows at texel (x, y).
void lit_surface_at(const FrameInputs& frame, int x, int y, glm::vec3& pos, glm::vec3& normal);
Image reference_lit_image(const ShadingInputs& in, const RefOptions& options = {});

std::uint8_t linear_to_srgb8(float v);

} // namespace lantern::gi
