#include "lantern/scene/procedural.hpp"

#include <cmath>

namespace lantern::scene {
namespace {

// Integer hash of a lattice point to [0, 1).
float lattice(int x, int z, std::uint32_t seed) {
    std::uint32_t h = std::uint32_t(x) * 0x8DA6B343u ^ std::uint32_t(z) * 0xD8163841u ^ seed * 0xCB1AB31Fu;
    h ^= h >> 13;
    h *= 0x5BD1E995u;
    h ^= h >> 15;
    return float(h & 0xFFFFFFu) / float(0x1000000);
}

float smooth(float t) { return t * t * (3.0f - 2.0f * t); }

// Value noise with lattice spacing `scale` tiles, sampled at the tile centre.
float value_noise(int x, int z, int scale, std::uint32_t seed) {
    const float fx = (float(x) + 0.5f) / float(scale), fz = (float(z) + 0.5f) / float(scale);
    const int ix = int(std::floor(fx)), iz = int(std::floor(fz));
    const float tx = smooth(fx - float(ix)), tz = smooth(fz - float(iz));
    const float a = lattice(ix, iz, seed), b = lattice(ix + 1, iz, seed);
    const float c = lattice(ix, iz + 1, seed), d = lattice(ix + 1, iz + 1, seed);
    return (a + (b - a) * tx) * (1.0f - tz) + (c + (d - c) * tx) * tz;
}

} // namespace

bool cave_wall(int x, int z, const CaveParams& p) {
    const float n = 0.55f * value_noise(x, z, 24, p.seed) + 0.30f * value_noise(x, z, 12, p.seed + 101u) +
                    0.15f * value_noise(x, z, 6, p.seed + 202u);
    return n > p.wall_threshold;
}

std::vector<Material> cave_materials() {
    // Emission in the transport model's units: a lava wall seen over half the horizon gives
    // the ground about pi / 2 x 0.5 = 0.8 of fluence, a torch's light at a few tiles.
    return {{"lava", {0.35f, 0.12f, 0.05f}, {0.5f, 0.17f, 0.04f}},
            {"crystal", {0.45f, 0.55f, 0.8f}, {0.06f, 0.14f, 0.35f}, EmissionGi::baked, 1.0f, crystal_pulse_hz}};
}

std::uint8_t cave_cell(int x, int z, const CaveParams& p) {
    if (!cave_wall(x, z, p)) return 0;
    if (!p.minerals) return 1;
    // Patches of a sparse noise, only where the rock meets open ground (a vein you can see).
    const float lava = value_noise(x, z, 9, p.seed + 7001u), crystal = value_noise(x, z, 7, p.seed + 9103u);
    if (lava < 0.78f && crystal < 0.8f) return 1;
    if (cave_wall(x + 1, z, p) && cave_wall(x - 1, z, p) && cave_wall(x, z + 1, p) && cave_wall(x, z - 1, p)) return 1;
    return material_cell(lava - 0.78f >= crystal - 0.8f ? cave_lava : cave_crystal);
}

WallGrid generate_caves(glm::ivec2 origin, glm::ivec2 size, const CaveParams& params) {
    WallGrid g;
    g.width = size.x;
    g.height = size.y;
    g.origin = origin;
    g.cells.resize(std::size_t(size.x) * std::size_t(size.y));
    for (int r = 0; r < size.y; ++r)
        for (int c = 0; c < size.x; ++c)
            g.cells[std::size_t(c) + std::size_t(r) * std::size_t(size.x)] =
                cave_cell(origin.x + c, origin.y + r, params);
    return g;
}

} // namespace lantern::scene
