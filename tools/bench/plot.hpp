// Small PNG charts for the benchmarks: scatter plots of error against cost with a marked
// Pareto front, drawn by a minimal rasteriser with stb_easy_font text. No dependencies
// beyond stb; written atomically (lantern::write_png).
#pragma once

#include "lantern/core/result.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace lantern::bench {

enum class Marker : std::uint8_t { circle, square, triangle, diamond, triangle_down };

struct PlotPoint {
    double x = 0.0, y = 0.0;
    std::uint32_t color = 0x000000; // 0xRRGGBB
    Marker marker = Marker::circle;
    bool hollow = false;
    std::string tag;    // a few characters drawn next to the marker ("" for none)
    bool front = false; // on the Pareto front: ringed and joined by the front line
    // Fronts are drawn per series (a method): the front points of one series are joined,
    // ring and line in the series' front colour.
    int series = 0;
    std::uint32_t front_color = 0x303030;
};

struct LegendEntry {
    std::string label;
    std::uint32_t color = 0x000000;
    Marker marker = Marker::circle;
    bool hollow = false;
    bool line = false; // a line sample instead of a marker
};

struct Panel {
    std::string title, x_label, y_label;
    bool log_x = true; // x from the smallest to the largest value, logarithmic
    std::vector<PlotPoint> points;
};

struct Figure {
    std::string title;
    std::vector<Panel> panels;       // side by side
    std::vector<LegendEntry> legend; // below the panels
    int panel_width = 560, panel_height = 420;
};

// Indices of the points not dominated by another (one at most as large in both
// coordinates, smaller in one): the Pareto front of minimising x and y, sorted by x.
std::vector<std::size_t> pareto_front(const std::vector<double>& x, const std::vector<double>& y);

Result<void> write_figure_png(const Figure& figure, const std::string& path);

} // namespace lantern::bench
