// Adaptive brick storage of a light field (seed 002's brick probe volume, in 2D;
// docs/baked.md, "Bricks"). The baked light's run-time form: the `baked` GI row samples it
// (baked_light.hpp), the bake reports its memory and error (lantern-bake --bricks).
//
// A field: RGB probes on a grid (the bake's texels, `resolution` a tile). It is stored as
// bricks of 4 x 4 probes with a one-probe apron (6 x 6 atlas texels, so bilinear filtering
// inside a brick never reads another brick) at levels 0-3, whose probes are 1, 2, 4 or 8
// grid texels apart: a brick of level L covers 4 x 2^L grid texels a side.
//
// Choosing the level, top down: a level-3 cell (32 x 32 texels) whose colour range (max -
// min of each channel over the cell and its apron) is at most `eps` is one brick; otherwise
// its four children are tried at level 2, and so on; a level-0 cell is always stored. A
// cell with no open texel within one brick of it (wholly inside rock) stores nothing (the
// seed's rule).
//
// Several fields of one size (layers: the ground and the four wall faces) share one atlas;
// each has its own indirection. Atlas: RGBA8, RGBM with range 8 (rgb = colour / (8 m),
// a = m, m quantised up so that no channel clips), bricks in rows. Indirection: one RGBA8
// texel per level-0 cell (4 x 4 grid texels), layer after layer (layer k's rows are
// k x cells_y ..): the atlas brick's x and y (12 bits each, over r, g and b), and a =
// level + 1, 0 for empty. A lookup reads the indirection texel of its cell (nearest), then
// filters bilinearly inside the brick: two texture reads on the GPU (shaders/gi_baked.comp.glsl).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace lantern::gi {

struct Field {
    int width = 0, height = 0;     // grid texels
    std::vector<float> rgb;        // width x height x 3, row-major
    std::vector<std::uint8_t> air; // width x height: 1 where the texel holds light to keep (open ground, an exposed face)

    Field() = default;
    Field(int w, int h) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3, 0.0f), air(std::size_t(w) * std::size_t(h), 0) {}

    glm::vec3 at(int x, int y) const {
        const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
};

inline constexpr int brick_probes = 4;                // probes a side
inline constexpr int brick_texels = brick_probes + 2; // with the apron
inline constexpr int brick_levels = 4;                // 0..3
inline constexpr int brick_max_atlas = 4096;          // bricks a side of the atlas (12-bit indices)
inline constexpr float rgbm_range = 8.0f;             // seed 002's

struct BrickAtlas {
    int cells_x = 0, cells_y = 0; // level-0 cells of one layer (4 x 4 grid texels each)
    int layers = 1;
    int atlas_bricks_x = 0, atlas_bricks_y = 0;
    std::vector<std::uint8_t> atlas;       // (atlas_bricks_x x 6) x (atlas_bricks_y x 6) x RGBA8
    std::vector<std::uint8_t> indirection; // cells_x x (cells_y x layers) x RGBA8
    int bricks_per_level[brick_levels] = {0, 0, 0, 0};
    int empty_cells = 0; // level-0 cells without a brick, over every layer
    // > 0: the field needs this many bricks, more than the atlas's 12-bit indices address in
    // rows of the requested width; nothing is stored (no atlas, no indirection).
    int too_many = 0;

    int atlas_width() const { return atlas_bricks_x * brick_texels; }
    int atlas_height() const { return atlas_bricks_y * brick_texels; }
    std::size_t bytes() const { return atlas.size() + indirection.size(); }
    int bricks() const { return bricks_per_level[0] + bricks_per_level[1] + bricks_per_level[2] + bricks_per_level[3]; }
};

// Builds the atlas of `field` (one layer) with colour range `eps` (light units, per channel).
// Bricks go in rows of `bricks_per_row` (0: as square an atlas as fits them). No brick is
// coarser than `max_level` (seed 002's maxLevel, 0..3).
BrickAtlas build_bricks(const Field& field, float eps, int bricks_per_row = 0, int max_level = brick_levels - 1);
// The same for several fields of one size in one atlas (layer k = fields[k]). With
// `finest_level` (one value per level-0 cell, row-major, cells_x x cells_y, for every
// layer): a cell whose field holds no detail finer than level L there (a chunk baked at
// 1 / 2^L of the grid's resolution: texel density per chunk) is not split below L, whatever
// its colour range (but never stored coarser than `max_level`).
BrickAtlas build_bricks(std::span<const Field> fields, float eps, int bricks_per_row = 0,
                        int max_level = brick_levels - 1, std::span<const std::uint8_t> finest_level = {});

// The field of `layer` as the atlas gives it back at grid position (x, y) (texel i's centre
// at i + 0.5): indirection (nearest), then bilinear between the brick's probes on the stored
// RGBM values, then decoded, as the GPU's sampler does (in float; a GPU filters with fewer
// fraction bits). Zero in an empty cell.
glm::vec3 sample_bricks(const BrickAtlas& atlas, float x, float y, int layer = 0);
// The level of the brick that covers (x, y) in `layer` (0..3), -1 where none does.
int brick_level(const BrickAtlas& atlas, float x, float y, int layer = 0);

// RGBM encoding of one colour and back (seed 002: range 8).
void encode_rgbm(glm::vec3 c, std::uint8_t out[4]);
glm::vec3 decode_rgbm(const std::uint8_t in[4]);

} // namespace lantern::gi
