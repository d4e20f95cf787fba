// Live light probes (seed 004's realtime light probes, in 2D; docs/baked.md, "Live probes"):
// every frame, at the centre of every other tile of the GI window (the bake's probe lattice,
// lantern/bake/probes.hpp), `gi.probe_rays` rays equally spaced over the circle find the first
// wall face they enter (the gather's integer traversal, gather_trace) and bring back its light
// as radiance B / 2, B = albedo x (wall_direct + wall_indirect) + emission of the face's tile
// (the gather's model of a Lambertian wall). The radiance is projected on circular harmonics
// of order 2, as the bake's probes:
//   a0 = sum L dtheta, a1 = sum L cos dtheta, b1 = sum L sin dtheta, a2 = sum L cos 2 dtheta, b2 = ...
// so a0 is the fluence the walls send to the point. The game lights the things that move with
// them (their directional part, beside the bake's probes). The probes run before the mixed and
// baked rows: they hold the light of realtime lights only (a bake's probes hold the rest).
#pragma once

#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/gather.hpp"
#include "lantern/gi/texture.hpp"

#include <glm/vec2.hpp>

namespace lantern::gi {

inline constexpr int live_probe_spacing = 2;      // tiles between probes (bake::probe_spacing)
inline constexpr int live_probe_coefficients = 5; // texels per probe: a0, a1, b1, a2, b2 (rgb)

// The probes of a frame: probe (i, j) stands at the centre of world tile
// first_tile + live_probe_spacing x (i, j), for the tiles the window touches.
struct ProbeGrid {
    glm::ivec2 first_tile{0};
    glm::ivec2 count{0};
};
ProbeGrid probe_grid(const FrameInputs& in);
// Tex::probes: probe (i, j)'s coefficient k at texel (5 i + k, j); coefficient 0's alpha is
// 1 where the probe stands in open ground, 0 in a wall (then all of it is 0).
glm::ivec2 probe_texture_size(const FrameInputs& in);

// The arc of each ray, 2 pi / rays (computed on the host for both backends).
float probe_dtheta(int rays);

// The reference: `direct` and `indirect` hold wall_direct_* and wall_indirect_* (absent
// faces: nullptr, read as 0).
Texture reference_probes(const FrameInputs& in, const FaceTextures& direct, const FaceTextures& indirect);

} // namespace lantern::gi
