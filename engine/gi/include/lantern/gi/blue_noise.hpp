// A 64 x 64 blue-noise tile: the ranks of a dither array made by Ulichney's void-and-cluster
// method (R. Ulichney, "The void-and-cluster method for dither array generation", SPIE 1913,
// 1993). Thresholding the ranks at any level t gives t pixels spread evenly, with little
// power at low frequencies, so noise keyed by them reads as fine grain rather than blotches,
// and the tile wraps (it is made on a torus) so it can repeat without seams.
//
// Made on the CPU on first use (tens of milliseconds) and the same bit for bit on every
// machine and compiler: the initial pattern comes from a fixed-seed generator written here
// and the energy is kept with plain double additions in a fixed order (blue_noise.cpp).
// tests/gi/blue_noise_test.cpp checks that it is a permutation and that it is blue.
#pragma once

#include <cstdint>
#include <vector>

namespace lantern::gi {

inline constexpr int blue_noise_size = 64; // the tile is 64 x 64 and wraps (toroidal)

// The ranks 0 .. 4095 of the tile, row-major (index y * 64 + x), each rank exactly once:
// void-and-cluster on a torus with a Gaussian energy filter (sigma 1.5). Computed once, on
// first use, and thread-safe (a function-local static); every call returns the same object.
const std::vector<std::uint16_t>& blue_noise_ranks();

} // namespace lantern::gi
