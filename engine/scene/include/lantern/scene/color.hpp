// Light colour from a temperature: the colour of a black body at T kelvin (a candle ~1900 K,
// a tungsten bulb ~2856 K, noon sun ~5800 K, overcast sky ~6500 K), for lights that give a
// "temperature" (docs/scenes.md).
//
// planckian_xy: the CIE 1931 chromaticity of the Planckian locus by the cubic spline of
// Kim et al. ("Design of advanced color temperature control system for HDTV applications",
// 2002), within about 1e-3 of the exact locus over its range. blackbody_rgb: that
// chromaticity at luminance 1 in linear sRGB (D65 primaries), negative components (deep red,
// below about 1900 K, lies outside sRGB) clamped to 0 and the result rescaled to luminance 1,
// so that a temperature changes a light's hue, not its brightness.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace lantern::scene {

inline constexpr float min_color_temperature = 1667.0f;  // kelvin: the spline's range
inline constexpr float max_color_temperature = 25000.0f;

// Clamps `kelvin` to [min_color_temperature, max_color_temperature].
glm::vec2 planckian_xy(float kelvin);
glm::vec3 blackbody_rgb(float kelvin);

// Rec. 709 / sRGB luminance of a linear colour.
float luminance(glm::vec3 rgb);

} // namespace lantern::scene
