// The physical GI method (gi.method = gather; docs/gi.md, "The gather method"): light after
// its first hit on a wall, under engine/transport's model (docs/accuracy.md, "Model"), so
// that it converges to the transport reference. The scalar C++ specification of its steps
// and the exact integer rules both backends share.
//
//   Direct light stays Lantern's exact direct pass: its wall-face textures (wall_direct_*)
//   are the first bounce's sources. A lit face leaves with radiosity
//     B = wall_albedo x (E_direct + E_indirect)
//   as radiance B / 2 into its half plane.
//   face bounce  every exposed face texel gathers E_indirect = integral of radiance x cos
//                over its half circle, from the faces its rays hit (gi.gather.face_rays
//                rays equally spaced in angle, turned per texel by blue noise, each
//                weighted by its cosine). gi.gather.bounces per frame; the history goes on
//                across frames (a converging row), so a still scene converges to the
//                multi-bounce solution at wall_albedo^(frames x bounces).
//   fill         wall_indirect_*: E_indirect of each face texel copied across its tile's
//                texels (the layout of Lantern's wall textures, which the shading reads)
//   ground       fluence = integral of radiance over the circle, gi.gather.rays rays per
//                texel of the ground grid (gi.gather.scale), then the upsample into
//                `indirect`.
//
// Rays cross the wall grid tile by tile (walls are whole tiles) in fixed point: positions in
// 1/4096 of a tile, directions from the 4096-entry table of radiosity.hpp, tile crossings
// decided by integer cross-multiplication, so the GPU takes exactly the reference's path and
// the hit face texel is the same on both. A ray crossing a tile corner exactly steps along x
// first: it enters a wall on either side, so light never passes between two walls that
// touch at a corner.
#pragma once

#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/reference.hpp"
#include "lantern/gi/reference_indirect.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>

namespace lantern::gi {

// The ground gather's grid: the GI window at 1 / gi.gather.scale.
HeatGrid gather_grid(const FrameInputs& in);

inline constexpr int gather_unit = 4096;    // fixed-point positions: 1/4096 tile
inline constexpr int gather_max_steps = 255; // tile crossings per ray

// Where the window lies on the tile grid: the tile of its min corner and the window texels
// from that tile's corner to the window's (the window is texel-aligned).
struct GatherFrame {
    glm::ivec2 origin_tile{0};
    glm::ivec2 offset{0}; // texels, 0 <= offset < resolution
    glm::ivec2 tiles{0};  // tiles from origin_tile that the window touches
    int resolution = 1;
    glm::ivec2 size{0};   // window texels
    glm::ivec2 noise_origin{0}; // window texel 0's blue-noise coordinate (world-fixed, mod 64)
};
GatherFrame gather_frame(const FrameInputs& in);
// The frame as the shaders' parameters carry it (lantern/gi_gather_trace.glsl's fields): the
// origin tile, offset x | y << 8 | resolution << 16, tiles x | z << 16, window width | height << 16.
struct PackedGatherFrame {
    std::int32_t origin_x = 0, origin_z = 0, offset = 0, tiles = 0, window = 0;
};
inline PackedGatherFrame pack(const GatherFrame& f) {
    return {f.origin_tile.x, f.origin_tile.y, f.offset.x | (f.offset.y << 8) | (f.resolution << 16),
            f.tiles.x | (f.tiles.y << 16), f.size.x | (f.size.y << 16)};
}

// A ray's first wall: the face it enters (0 +X, 1 -X, 2 +Z, 3 -Z; -1: it left the window
// first) and the window texel inside the wall that holds that face at the entry point.
struct GatherHit {
    int face = -1;
    glm::ivec2 texel{0};
    // The ray's length to the entry point: t_num / t_den lengths of the direction `d` (see
    // distance); only the C++ reference's weighted bake reads it.
    int t_num = 0, t_den = 1;
    // The length in tiles for the direction the ray was traced along.
    float distance(glm::ivec2 d) const;
};
// `p`: fixed-point position relative to origin_tile's corner; `cell`: its tile (relative);
// `d`: a direction of the table.
GatherHit gather_trace(const FrameInputs& in, const GatherFrame& f, glm::ivec2 p, glm::ivec2 cell, glm::ivec2 d);

// Whether window texel (x, y) is the edge texel of its wall tile on `face`, with air across.
bool gather_face_texel(const FrameInputs& in, const GatherFrame& f, int x, int y, int face);

// Whether the centre of gather-grid texel (i, j) lies in air (walls' grid texels gather
// nothing and stay zero).
bool gather_ground_texel_in_air(const FrameInputs& in, const GatherFrame& f, const HeatGrid& g, int i, int j);

// The face textures gather_face_a/b: E_indirect per face texel, face f of texel (x, y) at
// (x, f x height + y).
glm::ivec2 gather_face_size(const FrameInputs& in);

// Step `step` of the face bounces (0 at the first frame's first bounce) reads one of the
// two face textures and writes the other.
inline Tex gather_face_source(int step) { return step % 2 == 0 ? Tex::gather_face_a : Tex::gather_face_b; }
inline Tex gather_face_target(int step) { return step % 2 == 0 ? Tex::gather_face_b : Tex::gather_face_a; }

// Seed 002's own one-bounce bake (lantern-bake --solver seed002; C++ only, never a frame's
// pass): every face a ray hits receives `ambient` besides its direct light (the seed's
// ambient fill), and its radiosity counts 1 / (1 + (d / falloff)^2), d the ray's length in
// tiles, so near walls dominate. The default weighs nothing: the gather itself.
struct GatherWeighting {
    float falloff = 0.0f; // tiles; 0: no falloff
    float ambient = 0.0f; // received by every hit face, as direct light is

    float weight(float distance) const {
        if (falloff <= 0.0f) return 1.0f;
        const float q = distance / falloff;
        return 1.0f / (1.0f + q * q);
    }
};

// The reference's steps. `direct` holds wall_direct_px..nz (absent faces: nullptr).
using FaceTextures = std::array<const Texture*, 4>;
// The radiosity B leaving face `face` at window texel t (a hit of gather_trace): albedo x
// (direct + indirect `faces`, nullptr: none + `ambient`) + emission, by the material of t's
// tile.
glm::vec3 gather_radiosity(const FrameInputs& in, const FaceTextures& direct, const Texture* faces, int face,
                           glm::ivec2 t, float ambient = 0.0f);
// One face bounce: E_indirect of every exposed face texel from B = albedo x (direct +
// `previous`) (nullptr: no indirect yet).
// `weighting`: seed 002's bake (GatherWeighting); the frame's passes use none.
Texture reference_gather_faces(const FrameInputs& in, const FaceTextures& direct, const Texture* previous,
                               const RefOptions& options = {}, const GatherWeighting& weighting = {});
// wall_indirect_* from the face texture.
std::array<Texture, 4> reference_gather_fill(const FrameInputs& in, const Texture& faces,
                                             const RefOptions& options = {});
// The ground's fluence on the gather grid.
Texture reference_gather_ground(const FrameInputs& in, const FaceTextures& direct, const Texture& faces,
                                const RefOptions& options = {}, const GatherWeighting& weighting = {});

} // namespace lantern::gi
