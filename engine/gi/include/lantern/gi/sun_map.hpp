// The sun's shadows by a shadow map (gi.sun_shadow_method = "shadow_map"; docs/gi.md, "The
// sun's shadow map").
//
// A directional light's rays are parallel, so every wall tile that can shade the window lies
// on a line along the sun: a 1D map across the sun direction. The map splits the window's
// extent across the sun (v = dot(p, perp)) into bins of `sun_map_bin_width` tiles and lists,
// per bin, the wall tiles whose footprint across the sun overlaps it, sorted by their
// distance along the sun (u = dot(centre, dir)). A texel's visibility then looks up its bin,
// finds the tiles ahead of it by binary search and tests only those: is the tile on the
// ray's path (the line passes through its interior: its distance across the sun from the
// tile centre is below the tile's half width across the sun), ahead of the start, left by
// the ray within max_distance, and does the seed's wall-height test (distance to the tile
// centre x the sun's slope < wall height) block it. That is the DDA's specification
// (directional_shadow_dda) without walking the empty tiles.
//
// Exact by construction: where a float rounding could make the DDA and the map disagree (a
// ray passing within `sun_map_ambiguity` of a wall tile's corner, where the DDA's tie rule
// decides which side tile it visits, or leaving a wall tile within it of the start or of
// max_distance), the texel is handed to the DDA itself. tests/gi/sun_map_test.cpp checks
// every texel against the DDA on the test scenes, real maps and the stability grids, with
// suns from every direction, and counts the hand-offs.
//
// Built on the CPU (one pass over the wall tiles in reach) whenever the directional pass
// runs; the reference and the shader (gi_sun_map.glsl) read the same arrays.
#pragma once

#include "lantern/gi/frame_inputs.hpp"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace lantern::gi {

inline constexpr float sun_map_bin_width = 0.25f;  // tiles across the sun per bin
inline constexpr float sun_map_ambiguity = 1e-3f; // tiles: closer calls go to the DDA

// One sun's map. Entries of bin b: [first[b], first[b + 1]) of `entries`.
struct SunMap {
    bool lit_everywhere = false; // the sun is overhead or below the horizon: no grid shadow
    glm::vec2 dir{0.0f};         // towards the sun, unit, in xz
    glm::vec2 perp{0.0f};        // (-dir.y, dir.x)
    float v0 = 0.0f;             // v at the start of bin 0
    int bins = 0;
    float reach = 0.0f;          // tiles along the sun beyond which no tile can shade
    std::vector<std::uint32_t> first;  // bins + 1
    std::vector<glm::vec4> entries;    // (u of the tile centre, tile x, tile z, 0), sorted by u per bin
};

// The map of `sun` for start points inside [lo, hi] (world xz): the window's texels and the
// points just outside its wall faces.
SunMap build_sun_map(const WallView& walls, glm::vec2 lo, glm::vec2 hi, const GpuDirectionalLight& sun,
                     float wall_height);
// Which suns build_sun_maps maps (is_mixed_sun).
enum class SunKinds : std::uint8_t { all, realtime, mixed };
// The maps of the frame's suns of `kinds`, for the window's start points, one per sun of the
// frame: a sun of another kind gets a stand-in (lit everywhere, no bins, no tiles), so each
// map keeps its sun's index (the directional shader lights one kind and skips the other).
std::vector<SunMap> build_sun_maps(const FrameInputs& in, SunKinds kinds = SunKinds::all);

// The grid visibility of the sun from `pixel` by the map: 0 blocked, 1 lit. Same meaning as
// directional_shadow_dda(walls, pixel, sun direction, max distance, wall height), which
// decides the close calls (counted in *handed_to_dda when given).
float sun_map_visibility(const SunMap& map, const WallView& walls, const GpuDirectionalLight& sun, glm::vec2 pixel,
                         float wall_height, int* handed_to_dda = nullptr);

// The maps packed for the GPU (gi_sun_map.glsl): per sun two header texels (v0, 1 / bin
// width, bins, first-table base) and (reach, 0, 0, 0); the first-table (entry indices,
// absolute); the entries. Never empty (a zero element stands in), so they can be bound.
struct PackedSunMaps {
    std::vector<glm::vec4> headers;
    std::vector<std::uint32_t> first;
    std::vector<glm::vec4> entries;
};
PackedSunMaps pack_sun_maps(const std::vector<SunMap>& maps);

} // namespace lantern::gi
