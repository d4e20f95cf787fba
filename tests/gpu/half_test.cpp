// The CPU half-float reference used by the GPU tests (no GPU needed).
#include "gpu/gpu_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using lantern::test::float_to_half;
using lantern::test::half_to_float;

TEST(HalfReference, EveryNonNanHalfRoundTrips) {
    for (std::uint32_t h = 0; h < 0x10000u; ++h) {
        const auto half = static_cast<std::uint16_t>(h);
        const float f = half_to_float(half);
        if (std::isnan(f)) {
            EXPECT_TRUE(std::isnan(half_to_float(float_to_half(f)))) << h;
            continue;
        }
        ASSERT_EQ(float_to_half(f), half) << "half 0x" << std::hex << h << " = " << f;
    }
}

TEST(HalfReference, KnownValuesAndRoundingToNearestEven) {
    EXPECT_EQ(float_to_half(1.0f), 0x3c00u);
    EXPECT_EQ(float_to_half(-2.0f), 0xc000u);
    EXPECT_EQ(float_to_half(65504.0f), 0x7bffu);
    EXPECT_EQ(float_to_half(65520.0f), 0x7c00u); // rounds to infinity
    EXPECT_EQ(float_to_half(std::numeric_limits<float>::infinity()), 0x7c00u);
    EXPECT_EQ(float_to_half(std::ldexp(1.0f, -24)), 0x0001u); // smallest subnormal
    EXPECT_EQ(float_to_half(std::ldexp(1.0f, -25)), 0x0000u); // halfway: ties to even (0)
    EXPECT_EQ(float_to_half(std::ldexp(3.0f, -25)), 0x0002u); // 1.5 ulp: ties to even (2)
    // 1 + 2^-11 is halfway between 1 and 1 + 2^-10: ties to even (1).
    EXPECT_EQ(float_to_half(1.0f + std::ldexp(1.0f, -11)), 0x3c00u);
    EXPECT_EQ(float_to_half(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3c02u);
    EXPECT_EQ(half_to_float(0x3555u), 0.333251953125f);
}
