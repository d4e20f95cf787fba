// Seed 003's radiosity as a GI method (gi.method = radiosity; docs/gi.md, "The radiosity
// method"): the scalar C++ specification of its passes, and the exact integer rules both
// backends share.
//
//   distance_field  jump flood from the wall texels of the radiosity grid (the seed's: seed
//                   texels hold their own coordinate, then log2 passes of 3x3 samples at
//                   halving offsets, with one more pass at offset 1 before and after), then the
//                   distance to the nearest wall texel's centre, as floats (distance_field) and as
//                   the fixed-point steps the raymarch takes (distance_steps)
//   radiosity       the light image (the direct light's emission on the ground + feedback x
//                   last frame's radiosity: a bounce per frame), the raymarch (N rays per
//                   texel turned by blue noise, the seed's hit colour and brightness
//                   normalisation), temporal accumulation, and the upsample into the
//                   indirect light
//
// The raymarch runs in fixed point (1/4096 of a grid texel for positions, 1/256 for step
// lengths, directions from a table of 4096) with integer steps, so the GPU takes exactly
// the reference's path through the grid: GPU and reference agree texel by texel, and a
// step never jumps a wall (it is no longer than the distance to the nearest wall texel
// less sqrt 2, or, near walls, just long enough to enter the next texel).
#pragma once

#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/reference.hpp"
#include "lantern/gi/reference_indirect.hpp"

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

namespace lantern::gi {

// The radiosity grid: the GI window at 1 / gi.radiosity.scale.
HeatGrid radiosity_grid(const FrameInputs& in);

// ---- jump flood

// A jump-flood texel: the grid coordinate of the nearest wall texel found, or none.
inline constexpr std::uint32_t jfa_none = 0xFFFFFFFFu;
inline std::uint32_t jfa_pack(int x, int y) {
    return std::uint32_t(x) | (std::uint32_t(y) << 16);
}
inline glm::ivec2 jfa_unpack(std::uint32_t v) {
    return {int(v & 0xFFFFu), int(v >> 16)};
}
// The offsets of the passes after the seed: 1, then the largest power of two below the
// grid's larger side halving down to 1, then 1 once more ("1+JFA+1": on random grids of
// 0.2-60 % walls it found the nearest wall texel for every texel, where JFA+1 missed 12 of
// 302080 by up to 0.7 texels; tests/gi/radiosity_test.cpp).
std::vector<int> jump_flood_offsets(glm::ivec2 size);
// The texture (jfa_a or jfa_b) that holds the flood's result, each texel the packed
// coordinate of its nearest wall texel (x | y << 16; 0xFFFFFFFF: none), after the row ran.
Tex jump_flood_result(const FrameInputs& in);

// floor(256 x sqrt(d2)), clamped to 65535 (256 texels): exact integer arithmetic.
std::uint32_t distance_steps_of(std::uint32_t d2);
// Step lengths are in 1/256 of a grid texel; positions in 1/4096.
inline constexpr int radiosity_step_unit = 256;
inline constexpr int radiosity_position_unit = 4096;
// A step never exceeds the distance to the nearest wall texel's centre less this (sqrt 2:
// the ray's offset from its texel's centre plus the wall texel's half-diagonal), rounded up.
inline constexpr int radiosity_step_margin = 363;

// Jump flood on the reference: the seed and one pass. Texels are raw floats (internal):
// channel 0 the packed coordinate's x, channel 1 its y, both -1 for none.
Texture reference_jump_flood_seed(const FrameInputs& in);
Texture reference_jump_flood_pass(const Texture& jfa, int offset, const RefOptions& options = {});
struct DistanceTextures {
    Texture field; // rgba16f: distance (grid texels), unit direction to the nearest wall texel, 0
    Texture steps; // one channel, raw floats: distance_steps_of(d2)
};
DistanceTextures reference_distance_field(const Texture& jfa, const RefOptions& options = {});

// ---- the raymarch

// The 4096 ray directions: round(4096 x (cos, sin)) of a / 4096 turns.
const std::vector<glm::ivec2>& radiosity_directions();
// The angle index every texel's rays turn by in frame `frame` (history age): the seed's
// rotation t / 2pi radians, or the golden-ratio shift fract(PHI t), in 1/4096 turns.
int radiosity_frame_shift(scene::NoiseShift noise, int frame);

// What the march pass reads besides the textures, as the GPU gets it in push constants.
struct RadiosityMarch {
    int rays = 16, steps = 32;
    int epsilon_steps = 128; // hit when distance_steps < this
    int shift = 0;           // radiosity_frame_shift
    bool noise = true;       // per-texel blue-noise angle
    // The grid's global texel origin mod 64 (the noise stays put as the window moves).
    glm::ivec2 noise_origin{0};
    float accumulate_weight = 1.0f; // 1: replace; else previous + (new - previous) x weight
    // The seed's own term: the texel's last light, fed back (feedback once there is a last
    // frame, else 0).
    float own_weight = 0.0f;
};
RadiosityMarch radiosity_march_params(const FrameInputs& in, int history);

// The light image: the emission box-averaged onto the grid, 0 in wall texels, plus
// `feedback` x last frame's radiosity (none when `previous` is null).
Texture reference_radiosity_light(const FrameInputs& in, const Texture& emission,
                                  const Texture* previous, float feedback,
                                  const RefOptions& options = {});
// One texel's raymarched light (the seed's main()), before accumulation; `previous` is last
// frame's radiosity (the own term; null: none).
glm::vec3 radiosity_texel(const Texture& light, const Texture& steps, const Texture* previous,
                          const RadiosityMarch& m, int i, int j);
// The march over the grid, accumulated into `radiosity` (its previous content is read when
// m.accumulate_weight < 1).
void reference_radiosity_march(const Texture& light, const Texture& steps, const RadiosityMarch& m,
                               Texture& radiosity, const RefOptions& options = {});

} // namespace lantern::gi
