#include "lantern/gi/texture.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>

using namespace lantern::gi;

TEST(Half, EveryFiniteHalfRoundTrips) {
    for (std::uint32_t h = 0; h < 0x10000; ++h) {
        const std::uint32_t exponent = (h >> 10) & 0x1F;
        if (exponent == 31) continue; // Inf/NaN are never stored
        float f = half_to_float(std::uint16_t(h));
        ASSERT_EQ(float_to_half(f), std::uint16_t(h)) << std::hex << h;
    }
}

TEST(Half, RoundsToNearestEven) {
    // 1 + 2^-11 is halfway between 1 and 1 + 2^-10: ties to even -> 1.
    EXPECT_EQ(float_to_half(1.0f + std::ldexp(1.0f, -11)), 0x3C00);
    // 1 + 3 * 2^-11 is halfway between 1 + 2^-10 (odd) and 1 + 2^-9 (even) -> up.
    EXPECT_EQ(float_to_half(1.0f + 3.0f * std::ldexp(1.0f, -11)), 0x3C02);
    // Just above halfway rounds up.
    EXPECT_EQ(float_to_half(std::nextafter(1.0f + std::ldexp(1.0f, -11), 2.0f)), 0x3C01);
    // Subnormals: 2^-25 is halfway between 0 and 2^-24 -> 0; 3 * 2^-25 -> 2 * 2^-24.
    EXPECT_EQ(float_to_half(std::ldexp(1.0f, -25)), 0x0000);
    EXPECT_EQ(float_to_half(3.0f * std::ldexp(1.0f, -25)), 0x0002);
}

TEST(Half, BeyondRangeStaysFinite) {
    EXPECT_EQ(half_to_float(float_to_half(1e6f)), max_half);
    EXPECT_EQ(half_to_float(float_to_half(-1e30f)), -max_half);
    EXPECT_EQ(half_to_float(float_to_half(INFINITY)), max_half);
    EXPECT_EQ(float_to_half(NAN), 0);
}

TEST(Unorm8, ClampsAndRounds) {
    EXPECT_EQ(float_to_unorm8(-1.0f), 0);
    EXPECT_EQ(float_to_unorm8(2.0f), 255);
    EXPECT_EQ(float_to_unorm8(0.5f), 128); // 127.5 rounds up
    EXPECT_EQ(float_to_unorm8(NAN), 0);
    EXPECT_FLOAT_EQ(quantize_unorm8(1.0f), 1.0f);
}
