// The void-and-cluster blue-noise tile (blue_noise.hpp), after Ulichney (1993).
//
// A pixel's energy is the sum of a toroidal Gaussian centred on every 1 of the binary
// pattern: high where 1s crowd (the tightest cluster is the 1 of highest energy), low in
// holes (the largest void is the 0 of lowest energy). Setting or clearing a pixel adds or
// subtracts the kernel centred on it, so each step costs one pass over the tile and the
// whole tile O(N^2) for N pixels.
//
// Deterministic across machines and compilers: the initial pattern comes from splitmix64
// written here (std:: distributions are implementation-defined), the kernel from a literal
// and products (never std::exp, whose last bit differs between libraries), the energy only
// from double additions and subtractions in a fixed order (nothing for FMA contraction to
// change), and every argmin / argmax keeps the lowest index on ties.
#include "lantern/gi/blue_noise.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>

namespace lantern::gi {
namespace {

constexpr int n = blue_noise_size;
constexpr int pixels = n * n;
constexpr int initial_ones = pixels / 10; // Ulichney's initial pattern: ~10% minority pixels
constexpr std::uint64_t seed = 0x6c616e7465726e31ull; // "lantern1"

// splitmix64 (Steele, Lea and Flood 2014): fully specified, so the same everywhere.
std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// The energy filter exp(-r^2 / (2 sigma^2)), sigma 1.5, centred on pixel (0, 0), with r the
// toroidal distance. It is q^(r^2) with q = exp(-1 / 4.5) rounded to nearest (a literal), and
// r^2 is an integer, so the powers are repeated products: exact IEEE operations, the same on
// every machine. Their accumulated rounding (< 3e-13 relative) does not matter, only that it
// is the same everywhere. Each row is stored twice over (2n wide) so that the kernel centred
// on column px reads, for target columns 0 .. n-1, the contiguous run from n - px.
struct Kernel {
    std::vector<double> rows = std::vector<double>(pixels * 2);
};

Kernel make_kernel() {
    constexpr double q = 0x1.99fa40bc6c5f7p-1; // exp(-1 / 4.5), correctly rounded
    constexpr int half = n / 2;
    std::vector<double> power(2 * half * half + 1);
    power[0] = 1.0;
    for (std::size_t m = 1; m < power.size(); ++m) power[m] = power[m - 1] * q;

    Kernel kernel;
    for (int y = 0; y < n; ++y) {
        const int dy = y <= half ? y : n - y;
        for (int x = 0; x < 2 * n; ++x) {
            const int dx = x % n <= half ? x % n : n - x % n;
            kernel.rows[y * 2 * n + x] = power[dx * dx + dy * dy];
        }
    }
    return kernel;
}

struct Pattern {
    std::vector<unsigned char> bit = std::vector<unsigned char>(pixels, 0); // 1: a minority pixel
    std::vector<double> energy = std::vector<double>(pixels, 0.0);
};

// Sets (add) or clears pixel p, adding or subtracting the kernel centred on it. Target row
// (py + ky) mod n takes kernel row ky: fixed-length contiguous runs, one addition per
// element whatever the compiler makes of the loop.
void toggle(Pattern& pat, const Kernel& kernel, int p, bool add) {
    const int px = p % n, py = p / n;
    double* energy = pat.energy.data();
    const double* rows = kernel.rows.data();
    for (int ky = 0; ky < n; ++ky) {
        double* row = energy + ((py + ky) % n) * n;
        const double* k = rows + ky * 2 * n + (n - px);
        if (add) {
            for (int x = 0; x < n; ++x) row[x] += k[x];
        } else {
            for (int x = 0; x < n; ++x) row[x] -= k[x];
        }
    }
    pat.bit[p] = add ? 1 : 0;
}

// The lowest energy among the pixels whose bit is `bit` (the highest, when `highest`); the
// lowest index on ties. Two passes: the extreme value, then its first index. Neither branches
// on the bits (they follow no pattern a predictor could learn): the other pixels get +inf
// added. sign * energy is exact, so a fused multiply-add changes nothing. Four running
// minima keep the first pass from being one long chain of dependent comparisons.
int extreme(const Pattern& pat, unsigned char bit, bool highest) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double sign = highest ? -1.0 : 1.0; // reverses the order, rounds nothing
    double penalty[2] = {inf, inf};
    penalty[bit] = 0.0;
    const double* energy = pat.energy.data();
    const unsigned char* bits = pat.bit.data();

    double m0 = inf, m1 = inf, m2 = inf, m3 = inf;
    for (int i = 0; i < pixels; i += 4) {
        m0 = std::min(m0, sign * energy[i] + penalty[bits[i]]);
        m1 = std::min(m1, sign * energy[i + 1] + penalty[bits[i + 1]]);
        m2 = std::min(m2, sign * energy[i + 2] + penalty[bits[i + 2]]);
        m3 = std::min(m3, sign * energy[i + 3] + penalty[bits[i + 3]]);
    }
    const double best = std::min(std::min(m0, m1), std::min(m2, m3));
    if (best == inf) return -1; // no pixel has that bit: never asked
    int i = 0;
    while (sign * energy[i] + penalty[bits[i]] != best) ++i;
    return i;
}

// The 1 of highest energy.
int tightest_cluster(const Pattern& pat) {
    return extreme(pat, 1, true);
}

// The 0 of lowest energy.
int largest_void(const Pattern& pat) {
    return extreme(pat, 0, false);
}

std::vector<std::uint16_t> make_ranks() {
    const Kernel kernel = make_kernel();

    // The initial binary pattern: `initial_ones` distinct pixels at random. pixels is a power
    // of two, so the remainder is uniform.
    static_assert((pixels & (pixels - 1)) == 0);
    Pattern proto;
    std::uint64_t state = seed;
    for (int placed = 0; placed < initial_ones;) {
        const int p = int(splitmix64(state) % pixels);
        if (proto.bit[p]) continue;
        toggle(proto, kernel, p, true);
        ++placed;
    }

    // The prototype: move the tightest cluster's 1 into the largest void until the void it
    // leaves is the largest, i.e. until the move would put it back. The cap only guards
    // against a cycle (none seen); the result is deterministic either way.
    for (int step = 0; step < pixels; ++step) {
        const int cluster = tightest_cluster(proto);
        toggle(proto, kernel, cluster, false);
        const int hole = largest_void(proto);
        toggle(proto, kernel, hole, true);
        if (hole == cluster) break;
    }

    std::vector<std::uint16_t> rank(pixels);

    // Phase 1: the prototype's 1s, ranked from the last by removing the tightest cluster.
    Pattern pat = proto;
    for (int r = initial_ones - 1; r >= 0; --r) {
        const int p = tightest_cluster(pat);
        toggle(pat, kernel, p, false);
        rank[p] = std::uint16_t(r);
    }

    // Phase 2: from the prototype, fill the largest void up to half the pixels.
    pat = std::move(proto);
    for (int r = initial_ones; r < pixels / 2; ++r) {
        const int p = largest_void(pat);
        toggle(pat, kernel, p, true);
        rank[p] = std::uint16_t(r);
    }

    // Phase 3: the 0s are now the minority; the paper ranks the tightest cluster of 0s by
    // the energy of the inverted pattern, which at every pixel is sum(kernel) - energy. Its
    // maximum over the 0s is the 0 of lowest energy (but for the rounding of that
    // subtraction): the largest void, so phase 3 goes on as phase 2.
    for (int r = pixels / 2; r < pixels; ++r) {
        const int p = largest_void(pat);
        toggle(pat, kernel, p, true);
        rank[p] = std::uint16_t(r);
    }
    return rank;
}

} // namespace

const std::vector<std::uint16_t>& blue_noise_ranks() {
    static const std::vector<std::uint16_t> ranks = make_ranks(); // thread-safe since C++11
    return ranks;
}

} // namespace lantern::gi
