// Light colour from a temperature against published values: the CIE 1931 chromaticity of the
// Planckian locus (black-body radiators; CIE 15:2004 and Wyszecki & Stiles, "Color Science",
// table 1(3.3.4)), and what the conversion to linear sRGB must keep.
#include "lantern/scene/color.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace {

using lantern::scene::blackbody_rgb;
using lantern::scene::luminance;
using lantern::scene::planckian_xy;

struct LocusPoint {
    float kelvin;
    float x, y;
};

// CIE 1931 2-degree chromaticity of a black body (rounded to 4 digits as published).
constexpr LocusPoint published[] = {
    {2000.0f, 0.5267f, 0.4133f},
    {2856.0f, 0.4476f, 0.4074f}, // CIE illuminant A: a black body at 2856 K by definition
    {3000.0f, 0.4369f, 0.4041f},
    {4000.0f, 0.3805f, 0.3768f},
    {5000.0f, 0.3451f, 0.3516f},
    {6500.0f, 0.3135f, 0.3236f},
    {10000.0f, 0.2807f, 0.2884f},
};

TEST(ColorTemperature, PlanckianLocusMatchesPublishedChromaticities) {
    for (const LocusPoint& p : published) {
        const glm::vec2 xy = planckian_xy(p.kelvin);
        EXPECT_NEAR(xy.x, p.x, 1.5e-3f) << p.kelvin << " K";
        EXPECT_NEAR(xy.y, p.y, 1.5e-3f) << p.kelvin << " K";
    }
}

TEST(ColorTemperature, RgbKeepsLuminanceAndOrdersHues) {
    float last_blue_over_red = 0.0f;
    for (float k = lantern::scene::min_color_temperature; k <= lantern::scene::max_color_temperature; k *= 1.05f) {
        const glm::vec3 c = blackbody_rgb(k);
        EXPECT_NEAR(luminance(c), 1.0f, 1e-5f) << k << " K";
        EXPECT_GE(glm::min(c.r, glm::min(c.g, c.b)), 0.0f) << k << " K";
        const float blue_over_red = c.b / c.r;
        EXPECT_GE(blue_over_red, last_blue_over_red) << "hotter is bluer: " << k << " K";
        last_blue_over_red = blue_over_red;
    }
    // Near D65 (6504 K, just off the locus) a black body is nearly white in sRGB.
    const glm::vec3 daylight = blackbody_rgb(6504.0f);
    EXPECT_NEAR(daylight.r, 1.0f, 0.06f);
    EXPECT_NEAR(daylight.g, 1.0f, 0.06f);
    EXPECT_NEAR(daylight.b, 1.0f, 0.1f);
    // Candle light is orange: red well above blue.
    const glm::vec3 candle = blackbody_rgb(1900.0f);
    EXPECT_GT(candle.r, 2.0f * candle.b);
    // Out of range: clamped to the ends.
    EXPECT_EQ(blackbody_rgb(100.0f), blackbody_rgb(lantern::scene::min_color_temperature));
    EXPECT_EQ(blackbody_rgb(1e6f), blackbody_rgb(lantern::scene::max_color_temperature));
}

} // namespace
