// Point lights' grid shadows by an angular map per light (gi.shadow_method = "shadow_map";
// docs/gi.md, "Point lights' shadow maps").
//
// The seed's DDA marches a grid ray from the light to every texel in reach: O(R^3) per light
// of radius R. The map is built once per light instead and looked up per texel. Around the
// light, directions are split into `bins` wedges of equal pseudo-angle (a cheap monotone
// stand-in for atan2, in [0, 4)). Walls enter as runs: maximal horizontal runs of wall tiles
// in a row, and for shadows also vertical runs in a column. Per wedge the map keeps
//  - lit1, lit2: the two smallest distances at which the wedge meets a horizontal run (each
//    run widened by `margin`), with the run that gives the first (run1);
//  - shadow: a distance beyond which every ray of the wedge has crossed the inside of a run
//    (each run narrowed by `margin`), from runs that cover the whole wedge.
// A texel at distance d in a wedge is then
//  - lit when d < lit1: no wall comes near its ray;
//  - shadowed when d > shadow: its ray went through a wall;
//  - decided by an exact segment-against-box test of run1 when d < lit2: only that run comes
//    near the ray. The test answers "misses the widened run", "crosses the narrowed run" or
//    "unsure";
//  - else handed to the DDA itself, as every "unsure".
// lavapipe runs both sides of every branch and gathers every component a lane loads, so the
// lookup is straight-line code reading one 64-bit entry: distances as 16-bit (lit1, shadow)
// and 8-bit (lit2) fractions of the light's reach, rounded the safe way.
// Exact by construction: every certificate holds with `margin` to spare, which exceeds the
// DDA's own float error, so the DDA with its corner rule (shadow_dda, the specification)
// decides every close call: a ray passing within `margin` of a wall's corner or edge. The
// C++ reference and gi_point_map.glsl read the same arrays; tests/gi/point_map_test.cpp
// checks every visibility against the DDA and counts the hand-offs.
#pragma once

#include "lantern/gi/frame_inputs.hpp"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace lantern::gi {

// Lights outside these radii get no map (their visibility is the DDA's): below, the DDA's
// step budget could cut a ray short; above, a run's position no longer fits its 8-bit code.
inline constexpr float point_map_min_radius = 4.0f;
inline constexpr float point_map_max_radius = 120.0f;
inline constexpr std::uint32_t point_map_no_run = 0xffffffu;

// The maps of a frame's point lights. Per light a header: the first bin (-1: no map, the
// DDA) and the margin; the direct pass carries them in the light's spare fields
// (position_radius.w, color.w). A light's bin count follows from its radius and the GI
// resolution (point_map_bins). Per bin: x = lit1 | shadow << 16 (16-bit fractions of
// reach = radius + 3, lit1 rounded down, shadow up, 0xffff: none), y = run1 | lit2 << 24
// (run as (dx + 128) | (dz + 128) << 8 | length << 16 relative to the light's tile,
// point_map_no_run: none; lit2 an 8-bit fraction rounded down). Never empty (a zero element
// stands in), so they can be bound.
struct PointMaps {
    std::vector<glm::vec2> headers;
    std::vector<glm::uvec2> bins;
    int resolution = 1;
};

// The bins of a light of `radius` at GI resolution `res` (gi_point_map.glsl has its twin).
int point_map_bins(float radius, int res);

// The maps of every point light of `in` (its window and walls), in its order.
PointMaps build_point_maps(const FrameInputs& in);

// Light `light`'s grid visibility of `target` from its map alone: 0 blocked, 1 lit, -1 when
// the map cannot tell (a close call, or no map): shadow_dda decides those. The direct pass
// adds the lights the map decides first and the close calls after them, 32 lights at a time
// (gi_direct.comp.glsl; reference_passes.cpp follows the same order).
float point_map_lookup(const PointMaps& maps, std::size_t light, glm::vec2 pos, glm::vec2 target, float radius);

// Light `light`'s grid visibility of `target`: 0 blocked, 1 lit. Same meaning as
// shadow_dda(walls, pos, target, radius), which decides the close calls (counted in
// *handed_to_dda when given).
float point_map_visibility(const PointMaps& maps, const WallView& walls, std::size_t light, glm::vec2 pos,
                           glm::vec2 target, float radius, int* handed_to_dda = nullptr);

// The pseudo-angle of d in [0, 4], monotone in atan2(d.y, d.x) from the +x axis
// (gi_point_map.glsl has its twin).
float pseudo_angle(glm::vec2 d);

} // namespace lantern::gi
