// Baked light at run time (docs/baked.md, "At run time"): the light a bake holds for a
// rectangle of the world, as seed 002's brick atlas, which the `baked` GI row samples into
// the frame's indirect textures (ground and wall faces) so that baked lights, the glow of
// emissive materials and the bounce light of mixed lights cost one atlas read per texel.
//
// The rectangle is a grid of `resolution` texels a tile from world tile `origin`; grid
// texel (i, j) covers [origin + i / res, origin + (i + 1) / res) (rows along z alike).
// Layers: 0 the ground (fluence at open texels), 1 + f the wall face f (+X, -X, +Z, -Z) at
// the texels of wall tiles whose face f is exposed, as Lantern's wall textures hold it. Then
// the same five for each further part: the pulsing glow's light (`pulsing`), then each sun
// key's (`sun_keys`).
//
// Threads: immutable once built; frames share it through a shared_ptr (FrameInputs::baked).
#pragma once

#include "lantern/gi/bricks.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>

namespace lantern::gi {

struct FrameInputs;

inline constexpr int baked_layers = 5;    // ground, +X, -X, +Z, -Z
inline constexpr float baked_eps = 0.01f; // the bricks' colour range at run time (docs/baked.md)
// Atlas rows of this many bricks (384 texels): the GPU image keeps its width and grows only
// in height as bakes come and go (renderer memory does not follow every composition).
inline constexpr int baked_bricks_per_row = 64;

// Seed 004's precomputed GI for the moving sun (docs/baked.md, "The moving sun"): how a frame
// takes the bake's sun keys. The keys hold the mixed sun's bounce at unit colour at times of
// the day's path; the frame adds colour x ((1 - blend) x key + blend x (key + 1)).
struct BakedSun {
    int key = -1; // the key below the sun's time of day; -1: no keyed sun this frame
    float blend = 0.0f;
    glm::vec3 color{0.0f}; // the sun's colour x intensity

    friend bool operator==(const BakedSun&, const BakedSun&) = default;
};

struct BakedLight {
    glm::ivec2 origin{0}; // world tile of grid texel (0, 0)
    int resolution = 4;   // grid texels per tile
    int width = 0, height = 0; // grid texels
    BrickAtlas bricks;    // baked_layers layers, or twice that when `pulsing`
    std::uint64_t key = 0; // what it was built from: the baked row's input key
    // Seed 004's pulsing emission: layers baked_layers + k hold the light of the pulsing
    // glow alone (layer k's), which the frame adds scaled by FrameInputs::baked_pulse.
    bool pulsing = false;
    // Seed 004's moving sun: the parts after the steady (and pulsing) one hold the mixed sun's
    // bounce at sun_keys times of the day (scene::sun_key_time); 0: none.
    int sun_keys = 0;

    // Grid coordinates of world point p (texel i's centre at i + 0.5).
    glm::vec2 grid(glm::vec2 p) const {
        return (p - glm::vec2(origin)) * float(resolution);
    }
    // The baked light of `layer` at world point p (bilinear in the bricks), zero outside.
    glm::vec3 sample(int layer, glm::vec2 p) const;
    // The light the frame takes from layer `layer` (0..baked_layers - 1) at p with the pulsing
    // glow at `pulse` (scene::pulse_factor): sample(layer) + pulse x sample(pulsing layer).
    // With a keyed sun, plus its colour x the two keys around its time blended.
    glm::vec3 light(int layer, glm::vec2 p, float pulse, const BakedSun& sun = {}) const {
        glm::vec3 v = pulsing ? sample(layer, p) + pulse * sample(baked_layers + layer, p) : sample(layer, p);
        if (sun.key >= 0 && sun.key + 1 < sun_keys) v += sun_light(layer, p, sun);
        return v;
    }
    // What the keyed sun adds to `layer` at p: its colour x the two keys around its time,
    // blended (zero without a keyed sun). The steady light is sample(layer, p) + sun_light.
    glm::vec3 sun_light(int layer, glm::vec2 p, const BakedSun& sun) const {
        if (sun.key < 0 || sun.key + 1 >= sun_keys) return glm::vec3(0.0f);
        return (sun.color * (1.0f - sun.blend)) * sample(sun_layer(sun.key, layer), p) +
               (sun.color * sun.blend) * sample(sun_layer(sun.key + 1, layer), p);
    }
    // The atlas layer of sun key `k`'s layer `layer`.
    int sun_layer(int k, int layer) const { return (pulsing ? 2 : 1) * baked_layers + k * baked_layers + layer; }
    // The level (0..3) of the brick that gives it, -1 where none does (outside, empty).
    int level(int layer, glm::vec2 p) const;
};

// The atlas of dense fields (each width x height texels, layer order as above: baked_layers
// of them for the steady part, as many for the pulsing part when there is one, and for each
// of `sun_keys`) at `eps`; `finest_level` as build_bricks takes it (coarser chunks' cells).
BakedLight make_baked_light(glm::ivec2 origin, int resolution, std::span<const Field> layers,
                            float eps, std::uint64_t key, int max_level = brick_levels - 1,
                            std::span<const std::uint8_t> finest_level = {}, int sun_keys = 0);

// How the frame takes the bake's sun keys: for its first mixed sun (is_mixed_sun) when the
// bake has keys, the keys around the sun's time of day (scene::sun_key_blend) and its colour;
// none otherwise.
BakedSun baked_sun_of(const FrameInputs& in);

} // namespace lantern::gi
