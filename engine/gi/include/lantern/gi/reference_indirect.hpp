// Reference of the indirect-light half of the pipeline (seed 000 section 4 onwards):
// emission extraction, heat-transfer diffusion with adaptive hierarchical taps at full,
// half or quarter resolution, the edge-aware blur, and the wall-indirect projection.
// Same rules as reference.hpp: scalar, clear, quantised like the GPU stores.
#pragma once

#include "lantern/gi/reference.hpp"

namespace lantern::gi {

// Geometry of the heat grid: the GI window at 1/scale resolution (scale 1, 2 or 4).
struct HeatGrid {
    int scale = 1;
    int width = 0, height = 0; // ceil(window size / scale)
    float texels_per_unit = 1.0f; // window resolution / scale
    glm::vec2 origin{0.0f};
    glm::vec2 texel_center(int i, int j) const {
        return {origin.x + (float(i) + 0.5f) / texels_per_unit, origin.y + (float(j) + 0.5f) / texels_per_unit};
    }
};
HeatGrid heat_grid(const GiWindow& window, scene::HeatScale scale);

// One heat-transfer tap: offset in heat texels and its tier weight.
struct HeatTap {
    glm::vec2 offset;
    float weight;        // 1/sqrt(2) diagonals, times the tier share (0.3 / 0.3 / 0.4)
    bool segment_check;  // skips over a texel: check the straight segment for walls
};
// The taps for a diffusion distance in heat texels: 8 neighbours at that distance, or the
// three tiers (1.5 texels, half and full distance) when it exceeds 2.5 texels.
std::vector<HeatTap> heat_taps(float distance_texels);
// Whether that distance takes the three tiers (24 taps; heat_tap_count in gi_heat_taps.glsl).
inline bool heat_tap_rings(float distance_texels) { return distance_texels > 2.5f; }

// Emission extraction (rgba16f, full resolution): 1 - exp(-2 * maxChannel) roll-off,
// emission strength, saturation boost 1.2 around Rec.601 luma, negative channels clamped.
Texture reference_emission(const FrameInputs& in, const Texture& direct, const RefOptions& options = {});

// Heat transfer: seeds with the emission (box-downsampled to the heat grid), runs
// settings.heat_rounds rounds, and returns the indirect light at full resolution
// (conduction-aware bilinear upsample when scale > 1). `rounds_override` >= 0 replaces the
// round count (tests).
Texture reference_heat(const FrameInputs& in, const Texture& emission, const Texture& shadow,
                       const RefOptions& options = {}, int rounds_override = -1);
// Its three stages, as the heat row runs them (one iteration each): the seed at the heat
// grid, one round, and the upsample of the last round into the indirect light.
Texture reference_heat_seed(const FrameInputs& in, const Texture& emission, const Texture& shadow,
                            const RefOptions& options = {});
Texture reference_heat_round(const FrameInputs& in, const Texture& heat, const RefOptions& options = {});
Texture reference_heat_upsample(const FrameInputs& in, const Texture& heat, const RefOptions& options = {});

// A grid texture (the heat grid's, the radiosity grid's) at full resolution as the indirect
// light: a copy at scale 1, else bilinear over the grid texels whose centres are not in a
// wall (nearest when none is).
Texture reference_upsample(const FrameInputs& in, const HeatGrid& grid, const Texture& texture,
                           const RefOptions& options = {});

// Two-pass separable blur (5 taps, Gaussian sigma 1) that only mixes texels of the same
// conduction class (the conduction texture: 1 in air, 0 in walls) and renormalises, so a
// uniform region keeps its brightness.
Texture reference_blur(const FrameInputs& in, const Texture& indirect, const Texture& conduction,
                       const RefOptions& options = {});

// Wall indirect: for each exposed face of a wall texel, the indirect light of the texel one
// world unit away across that face (clamped to the window). Faces not computed
// (computed_faces) are left empty.
std::array<Texture, 4> reference_wall_indirect(const FrameInputs& in, const Texture& indirect,
                                               const RefOptions& options = {});

} // namespace lantern::gi
