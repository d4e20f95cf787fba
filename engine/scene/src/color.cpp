#include "lantern/scene/color.hpp"

#include <glm/common.hpp>

#include <algorithm>

namespace lantern::scene {

glm::vec2 planckian_xy(float kelvin) {
    const double t = std::clamp(double(kelvin), double(min_color_temperature), double(max_color_temperature));
    const double u = 1e3 / t; // the spline is a cubic in 1000 / T
    const double x = t <= 4000.0 ? ((-0.2661239 * u - 0.2343589) * u + 0.8776956) * u + 0.179910
                                 : ((-3.0258469 * u + 2.1070379) * u + 0.2226347) * u + 0.240390;
    double y = 0.0;
    if (t <= 2222.0) y = ((-1.1063814 * x - 1.34811020) * x + 2.18555832) * x - 0.20219683;
    else if (t <= 4000.0) y = ((-0.9549476 * x - 1.37418593) * x + 2.09137015) * x - 0.16748867;
    else y = ((3.0817580 * x - 5.87338670) * x + 3.75112997) * x - 0.37001483;
    return {float(x), float(y)};
}

float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

glm::vec3 blackbody_rgb(float kelvin) {
    const glm::vec2 xy = planckian_xy(kelvin);
    // xyY with Y = 1 to XYZ, then XYZ to linear sRGB (IEC 61966-2-1, D65).
    const double x = xy.x, y = xy.y;
    const double X = x / y, Y = 1.0, Z = (1.0 - x - y) / y;
    glm::dvec3 rgb(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z, -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
                   0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z);
    rgb = glm::max(rgb, glm::dvec3(0.0)); // outside the sRGB gamut: the nearest colour in it
    const double l = 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
    return glm::vec3(rgb / l);
}

} // namespace lantern::scene
