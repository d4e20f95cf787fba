// Texel-by-texel comparison of a GPU texture with the C++ reference, with tolerances that
// follow from the storage formats: unorm8 within one step (1/255: the reference and the
// GPU may round a value that sits on a step boundary differently), half within two units in
// the last place (both round to nearest even; GLSL pow/exp/division may differ from the
// C++ library by a few float ulps, which can move a value across one half rounding
// boundary, and sums of many lights can do that twice). A live probe's harmonic
// coefficients are measured against the probe's own light (probe_magnitude).
#pragma once

#include "lantern/gi/probes.hpp"
#include "lantern/gi/texture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace gi_test {

struct TexelDiff {
    std::size_t mismatches = 0;
    std::size_t compared = 0;
    float worst = 0.0f; // largest |a - b| / allowed
    int x = -1, y = -1, channel = -1;
    float gpu = 0.0f, ref = 0.0f;
};

// `magnitude` floors the values' own: the size of the sum whose rounding the difference measures.
inline float allowed_difference(lantern::gi::TexFormat f, float a, float b, float half_ulps,
                                float magnitude = 0.0f) {
    if (f != lantern::gi::TexFormat::rgba16f) return 1.0f / 255.0f + 1e-6f;
    magnitude = std::max({magnitude, std::abs(a), std::abs(b)});
    // One half ulp is 2^-10 of the magnitude for normal halves, 2^-24 absolute below 2^-14.
    return half_ulps * std::max(magnitude * std::ldexp(1.0f, -10), std::ldexp(1.0f, -24));
}

// The "probes" texture holds each live probe's circular harmonics in five texels (a0, a1, b1,
// a2, b2). a1..b2 sum the probe's rays' light times cos and sin, so their rounding error
// follows the rays' total light, a0, not their own value, which cancellation can make
// far smaller: the same half-ulp count is taken of the larger of the two backends' a0 of
// that probe and channel. (On an NVIDIA H200, whose arithmetic differs from lavapipe's in
// contraction and built-ins, six such coefficients failed the old rule by 1.05-4.6x: b2 of
// a probe came out 7e-6 off a reference of -8.0e-4, 4.6x two half ulps of its own size and
// 0.01x two of its a0, 0.384.) 0 for every other texel.
inline float probe_magnitude(const lantern::gi::Texture& gpu, const lantern::gi::Texture& ref, int x, int y,
                             int channel) {
    if (gpu.name != "probes" || channel >= 3) return 0.0f;
    const int x0 = x - x % lantern::gi::live_probe_coefficients;
    return std::max(std::abs(gpu.at(x0, y)[channel]), std::abs(ref.at(x0, y)[channel]));
}

inline TexelDiff compare_textures(const lantern::gi::Texture& gpu, const lantern::gi::Texture& ref,
                                  float half_ulps = 2.0f) {
    TexelDiff d;
    EXPECT_EQ(gpu.width, ref.width);
    EXPECT_EQ(gpu.height, ref.height);
    EXPECT_EQ(gpu.format, ref.format);
    if (gpu.width != ref.width || gpu.height != ref.height || gpu.format != ref.format) return d;
    for (int y = 0; y < gpu.height; ++y)
        for (int x = 0; x < gpu.width; ++x)
            for (int c = 0; c < gpu.channels(); ++c) {
                const float a = gpu.at(x, y)[c], b = ref.at(x, y)[c];
                const float ratio = std::abs(a - b) / allowed_difference(gpu.format, a, b, half_ulps,
                                                                         probe_magnitude(gpu, ref, x, y, c));
                ++d.compared;
                if (!(std::isfinite(a)) || ratio > 1.0f) ++d.mismatches;
                if (!(ratio <= d.worst)) {
                    d.worst = ratio;
                    d.x = x, d.y = y, d.channel = c, d.gpu = a, d.ref = b;
                }
            }
    return d;
}

// The largest colour channel over texels [x0, x1) x [y0, y1).
inline float max_in(const lantern::gi::Texture& t, int x0, int y0, int x1, int y1) {
    float m = 0.0f;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < std::min(3, t.channels()); ++c) m = std::max(m, t.at(x, y)[c]);
    return m;
}

inline std::string describe(const std::string& what, const TexelDiff& d) {
    std::ostringstream s;
    s << what << ": " << d.mismatches << " of " << d.compared << " values outside tolerance; worst at (" << d.x
      << ", " << d.y << ") channel " << d.channel << ": gpu " << d.gpu << " reference " << d.ref << " ("
      << d.worst << " x the allowed difference)";
    return s.str();
}

} // namespace gi_test
