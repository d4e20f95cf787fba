// Baked light at run time (docs/baked.md, "At run time"): the light a bake holds for a
// rectangle of the world, as seed 002's brick atlas, which the `baked` GI row samples into
// the frame's indirect textures (ground and wall faces) so that baked lights, the glow of
// emissive materials and the bounce light of mixed lights cost one atlas read per texel.
//
// The rectangle is a grid of `resolution` texels a tile from world tile `origin`; grid
// texel (i, j) covers [origin + i / res, origin + (i + 1) / res) (rows along z alike).
// Layers: 0 the ground (fluence at open texels), 1 + f the wall face f (+X, -X, +Z, -Z) at
// the texels of wall tiles whose face f is exposed, as Lantern's wall textures hold it.
//
// Threads: immutable once built; frames share it through a shared_ptr (FrameInputs::baked).
#pragma once

#include "lantern/gi/bricks.hpp"

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <span>

namespace lantern::gi {

inline constexpr int baked_layers = 5;    // ground, +X, -X, +Z, -Z
inline constexpr float baked_eps = 0.01f; // the bricks' colour range at run time (docs/baked.md)
// Atlas rows of this many bricks (384 texels): the GPU image keeps its width and grows only
// in height as bakes come and go (renderer memory does not follow every composition).
inline constexpr int baked_bricks_per_row = 64;

struct BakedLight {
    glm::ivec2 origin{0}; // world tile of grid texel (0, 0)
    int resolution = 4;   // grid texels per tile
    int width = 0, height = 0; // grid texels
    BrickAtlas bricks;    // baked_layers layers, or twice that when `pulsing`
    std::uint64_t key = 0; // what it was built from: the baked row's input key
    // Seed 004's pulsing emission: layers baked_layers + k hold the light of the pulsing
    // glow alone (layer k's), which the frame adds scaled by FrameInputs::baked_pulse.
    bool pulsing = false;

    // Grid coordinates of world point p (texel i's centre at i + 0.5).
    glm::vec2 grid(glm::vec2 p) const {
        return (p - glm::vec2(origin)) * float(resolution);
    }
    // The baked light of `layer` at world point p (bilinear in the bricks), zero outside.
    glm::vec3 sample(int layer, glm::vec2 p) const;
    // The light the frame takes from layer `layer` (0..baked_layers - 1) at p with the pulsing
    // glow at `pulse` (scene::pulse_factor): sample(layer) + pulse x sample(pulsing layer).
    glm::vec3 light(int layer, glm::vec2 p, float pulse) const {
        return pulsing ? sample(layer, p) + pulse * sample(baked_layers + layer, p) : sample(layer, p);
    }
    // The level (0..3) of the brick that gives it, -1 where none does (outside, empty).
    int level(int layer, glm::vec2 p) const;
};

// The atlas of dense fields (each width x height texels, layer order as above; baked_layers
// of them, or twice that with the pulsing part's) at `eps`; `finest_level` as build_bricks
// takes it (coarser chunks' cells).
BakedLight make_baked_light(glm::ivec2 origin, int resolution, std::span<const Field> layers,
                            float eps, std::uint64_t key, int max_level = brick_levels - 1,
                            std::span<const std::uint8_t> finest_level = {});

} // namespace lantern::gi
