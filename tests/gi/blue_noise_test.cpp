// The blue-noise tile (engine/gi blue_noise.hpp): every rank once, one shared tile, and blue.
// Blue is checked by properties, not a checksum (that would only restate the output): the
// pixels below a threshold of the ranks (1/16, 1/8 and 1/2, and the last 1/16, which phase 3
// ranks) keep apart and carry little power at low frequencies, where the same count of
// pixels from a fixed-seed shuffle (white noise) does neither. The last test runs the same
// checks on shuffles, so a check that cannot tell white from blue fails there.
#include "lantern/gi/blue_noise.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <utility>
#include <vector>

using namespace lantern::gi;

namespace {

constexpr int n = blue_noise_size;
constexpr int pixels = n * n;
constexpr int max_frequency = 6;         // cycles per tile: "low" frequencies are 0 < |f| <= this
constexpr double max_power_ratio = 0.25; // blue against white, over those frequencies

// A white-noise permutation: Fisher-Yates driven by splitmix64, both written here, since
// std::shuffle's result differs between standard libraries.
std::vector<std::uint16_t> shuffled_ranks(std::uint64_t seed) {
    std::vector<std::uint16_t> ranks(pixels);
    std::iota(ranks.begin(), ranks.end(), std::uint16_t(0));
    std::uint64_t state = seed;
    for (int i = pixels - 1; i > 0; --i) {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
        std::swap(ranks[i], ranks[std::size_t(z % std::uint64_t(i + 1))]);
    }
    return ranks;
}

// The pixels whose rank is in [lo, hi).
std::vector<int> ranked(const std::vector<std::uint16_t>& ranks, int lo, int hi) {
    std::vector<int> set;
    for (int i = 0; i < pixels; ++i)
        if (ranks[i] >= lo && ranks[i] < hi) set.push_back(i);
    return set;
}

// The smallest squared toroidal distance between two pixels of `set`.
int min_squared_distance(const std::vector<int>& set) {
    int best = 2 * n * n;
    for (std::size_t a = 0; a < set.size(); ++a) {
        for (std::size_t b = a + 1; b < set.size(); ++b) {
            int dx = std::abs(set[a] % n - set[b] % n), dy = std::abs(set[a] / n - set[b] / n);
            dx = std::min(dx, n - dx);
            dy = std::min(dy, n - dy);
            best = std::min(best, dx * dx + dy * dy);
        }
    }
    return best;
}

// The power of the 0/1 mask of `set`, mean removed, summed over the frequencies
// 0 < |f| <= max_frequency: a direct 2D DFT over the whole tile.
double low_frequency_power(const std::vector<int>& set) {
    std::vector<double> mask(pixels, 0.0);
    for (int p : set) mask[p] = 1.0;
    const double mean = double(set.size()) / pixels;
    for (double& m : mask) m -= mean;

    const double pi = std::acos(-1.0);
    double cosine[n], sine[n];
    for (int i = 0; i < n; ++i) {
        cosine[i] = std::cos(2.0 * pi * i / n);
        sine[i] = std::sin(2.0 * pi * i / n);
    }
    double power = 0.0;
    for (int fy = -max_frequency; fy <= max_frequency; ++fy) {
        for (int fx = -max_frequency; fx <= max_frequency; ++fx) {
            const int f2 = fx * fx + fy * fy;
            if (f2 == 0 || f2 > max_frequency * max_frequency) continue;
            double re = 0.0, im = 0.0;
            for (int y = 0; y < n; ++y) {
                for (int x = 0; x < n; ++x) {
                    const int phase = ((fx * x + fy * y) % n + n) % n;
                    re += mask[y * n + x] * cosine[phase];
                    im -= mask[y * n + x] * sine[phase];
                }
            }
            power += re * re + im * im;
        }
    }
    return power;
}

struct Threshold {
    const char* name;
    int lo, hi; // ranks [lo, hi)
};

// 1/16, 1/8 and 1/2 of the ranks from the bottom (phases 1 and 2), and 1/16 from the top
// (phase 3).
const Threshold thresholds[] = {{"ranks < 256", 0, 256},
                                {"ranks < 512", 0, 512},
                                {"ranks < 2048", 0, 2048},
                                {"ranks >= 3840", 3840, pixels}};

constexpr std::uint64_t white_seed = 0x5eed0001ull;

} // namespace

TEST(BlueNoise, EveryRankOnce) {
    const std::vector<std::uint16_t>& ranks = blue_noise_ranks();
    ASSERT_EQ(ranks.size(), std::size_t(pixels));
    std::vector<int> seen(pixels, 0);
    for (std::uint16_t r : ranks) {
        ASSERT_LT(int(r), pixels);
        ++seen[r];
    }
    for (int r = 0; r < pixels; ++r) EXPECT_EQ(seen[r], 1) << "rank " << r;
}

TEST(BlueNoise, OneSharedTile) {
    const std::vector<std::uint16_t>& a = blue_noise_ranks();
    const std::vector<std::uint16_t> copy = a;
    const std::vector<std::uint16_t>& b = blue_noise_ranks();
    EXPECT_EQ(&a, &b);
    EXPECT_EQ(copy, b);
}

// Void-and-cluster spreads the sparse sets evenly: 256 pixels of 4096 average 4 pixels
// apart, and none come closer than 2; of the 512 lowest, none are neighbours (diagonals
// included: on the grid the next distance below 2 is sqrt(2)). White noise puts pairs side
// by side at these densities (see ChecksRejectWhiteNoise).
TEST(BlueNoise, SparseSetsKeepApart) {
    const std::vector<std::uint16_t>& ranks = blue_noise_ranks();
    const int lowest_256 = min_squared_distance(ranked(ranks, 0, 256));
    const int highest_256 = min_squared_distance(ranked(ranks, pixels - 256, pixels));
    const int lowest_512 = min_squared_distance(ranked(ranks, 0, 512));
    std::printf("min distance: ranks < 256 %.3f, ranks >= 3840 %.3f, ranks < 512 %.3f\n",
                std::sqrt(double(lowest_256)), std::sqrt(double(highest_256)),
                std::sqrt(double(lowest_512)));
    EXPECT_GE(lowest_256, 4);
    EXPECT_GE(highest_256, 4);
    EXPECT_GT(lowest_512, 2);
}

// Blue noise has little power below its principal frequency: at every threshold, under a
// quarter of what the same count of white-noise pixels carries.
TEST(BlueNoise, LittleLowFrequencyPower) {
    const std::vector<std::uint16_t>& ranks = blue_noise_ranks();
    const std::vector<std::uint16_t> white = shuffled_ranks(white_seed);
    for (const Threshold& t : thresholds) {
        const double blue_power = low_frequency_power(ranked(ranks, t.lo, t.hi));
        const double white_power = low_frequency_power(ranked(white, t.lo, t.hi));
        std::printf("%s: low-frequency power %.1f, white noise %.1f, ratio %.4f\n", t.name,
                    blue_power, white_power, blue_power / white_power);
        EXPECT_LT(blue_power, max_power_ratio * white_power) << t.name;
    }
}

// The same checks on white noise fail: a shuffle's sparse set has neighbours, and its
// low-frequency power against another shuffle's is nowhere near a quarter.
TEST(BlueNoise, ChecksRejectWhiteNoise) {
    const std::vector<std::uint16_t> white = shuffled_ranks(white_seed);
    const std::vector<std::uint16_t> other = shuffled_ranks(white_seed + 1);
    EXPECT_LT(min_squared_distance(ranked(other, 0, 256)), 4);
    EXPECT_LE(min_squared_distance(ranked(other, 0, 512)), 2);
    for (const Threshold& t : thresholds) {
        const double ratio = low_frequency_power(ranked(other, t.lo, t.hi)) /
                             low_frequency_power(ranked(white, t.lo, t.hi));
        std::printf("%s: white noise against white noise, ratio %.4f\n", t.name, ratio);
        EXPECT_GT(ratio, max_power_ratio) << t.name;
    }
}
