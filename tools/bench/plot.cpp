#include "plot.hpp"

#include "lantern/core/png.hpp"

#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace lantern::bench {
namespace {

constexpr std::uint32_t black = 0x000000, grid_grey = 0xE4E4E4, axis_grey = 0x606060;
constexpr int text_scale = 2; // stb_easy_font glyphs are ~6 x 7 pixels
constexpr int title_band = 40;
constexpr int legend_row = 30;

class Canvas {
  public:
    Canvas(int w, int h) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3, 255) {}

    void pixel(int x, int y, std::uint32_t c) {
        if (x < 0 || y < 0 || x >= width || y >= height) return;
        std::uint8_t* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
        p[0] = std::uint8_t(c >> 16), p[1] = std::uint8_t(c >> 8), p[2] = std::uint8_t(c);
    }
    void fill(int x0, int y0, int x1, int y1, std::uint32_t c) { // [x0, x1) x [y0, y1)
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) pixel(x, y, c);
    }
    // A line of `thickness` pixels: squares stamped along the major axis.
    void line(double x0, double y0, double x1, double y1, std::uint32_t c, int thickness = 1) {
        const int steps =
            std::max(1, int(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))));
        const int lo = -(thickness - 1) / 2, hi = thickness / 2;
        for (int i = 0; i <= steps; ++i) {
            const double t = double(i) / steps;
            const int x = int(std::lround(x0 + (x1 - x0) * t)),
                      y = int(std::lround(y0 + (y1 - y0) * t));
            fill(x + lo, y + lo, x + hi + 1, y + hi + 1, c);
        }
    }
    void marker(double cx, double cy, Marker m, double r, std::uint32_t c, bool hollow) {
        const int x0 = int(std::floor(cx - r - 1)), x1 = int(std::ceil(cx + r + 1));
        const int y0 = int(std::floor(cy - r - 1)), y1 = int(std::ceil(cy + r + 1));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
                const double outer = shape_distance(m, dx, dy, r);
                if (outer <= 0.0 && (!hollow || outer > -2.0)) pixel(x, y, c);
            }
    }
    // Text with its top-left corner at (x, y); vertical text reads bottom to top, with
    // (x, y) its bottom-left corner.
    void text(int x, int y, const std::string& s, std::uint32_t c, int scale = text_scale,
              bool vertical = false) {
        std::string copy = s;
        std::vector<char> buffer(copy.size() * 1024 +
                                 64); // a glyph is at most ~14 quads of 64 bytes
        const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, buffer.data(),
                                              int(buffer.size()));
        for (int q = 0; q < quads; ++q) {
            const float* v =
                reinterpret_cast<const float*>(buffer.data() + std::size_t(q) * 64); // 4 x 16 bytes
            const int gx0 = int(v[0]) * scale, gy0 = int(v[1]) * scale;
            const int gx1 = int(v[8]) * scale, gy1 = int(v[9]) * scale; // the opposite corner
            if (vertical)
                fill(x + gy0, y - gx1, x + gy1, y - gx0, c);
            else
                fill(x + gx0, y + gy0, x + gx1, y + gy1, c);
        }
    }
    static int text_width(const std::string& s, int scale = text_scale) {
        std::string copy = s;
        return stb_easy_font_width(copy.data()) * scale;
    }

    int width, height;
    std::vector<std::uint8_t> rgb;

  private:
    // <= 0 inside the shape of "radius" r, growing outwards (in pixels, roughly).
    static double shape_distance(Marker m, double dx, double dy, double r) {
        switch (m) {
        case Marker::circle:
            return std::sqrt(dx * dx + dy * dy) - r;
        case Marker::square:
            return std::max(std::abs(dx), std::abs(dy)) - r * 0.85;
        case Marker::diamond:
            return (std::abs(dx) + std::abs(dy)) / 1.2 - r;
        case Marker::triangle: // pointing up, centred
            return std::max(dy - r * 0.8, (std::abs(dx) * 1.7 - dy) / 2.0 - r * 0.55);
        case Marker::triangle_down:
            return std::max(-dy - r * 0.8, (std::abs(dx) * 1.7 + dy) / 2.0 - r * 0.55);
        }
        return 0.0;
    }
};

std::string tick_label(double v) {
    char b[32];
    std::snprintf(b, sizeof(b), "%g", v);
    return b;
}

// 1-2-5 ticks inside [lo, hi] (logarithmic axes).
std::vector<double> log_ticks(double lo, double hi) {
    std::vector<double> ticks;
    for (int e = int(std::floor(std::log10(lo))); e <= int(std::ceil(std::log10(hi))); ++e)
        for (double m : {1.0, 2.0, 5.0}) {
            const double v = m * std::pow(10.0, e);
            if (v >= lo && v <= hi) ticks.push_back(v);
        }
    return ticks;
}

// About five round ticks from 0 to hi (linear axes).
std::vector<double> linear_ticks(double hi) {
    const double raw = hi / 5.0, base = std::pow(10.0, std::floor(std::log10(raw)));
    const double step = raw / base < 1.5   ? base
                        : raw / base < 3.5 ? 2.0 * base
                        : raw / base < 7.5 ? 5.0 * base
                                           : 10.0 * base;
    std::vector<double> ticks;
    for (double v = 0.0; v <= hi + step * 1e-9; v += step) ticks.push_back(v);
    return ticks;
}

struct Axes {
    int left, top, width, height; // plot area in pixels
    bool log_x;
    double x_lo, x_hi, y_hi;
    double px(double x) const {
        const double t = log_x ? (std::log(x) - std::log(x_lo)) / (std::log(x_hi) - std::log(x_lo))
                               : (x - x_lo) / (x_hi - x_lo);
        return left + t * width;
    }
    double py(double y) const { return top + height - y / y_hi * height; }
};

Axes axes_for(const Panel& p, int x0, int y0, int w, int h) {
    Axes a{x0 + 90, y0 + 40, w - 120, h - 100, p.log_x, 0.0, 1.0, 1.0};
    double lo = std::numeric_limits<double>::max(), hi = 0.0, top = 0.0;
    for (const PlotPoint& pt : p.points)
        lo = std::min(lo, pt.x), hi = std::max(hi, pt.x), top = std::max(top, pt.y);
    if (p.points.empty()) lo = 1.0, hi = 10.0;
    if (p.log_x) {
        lo = std::max(lo, 1e-9);
        a.x_lo = lo / 1.25, a.x_hi = std::max(hi, lo * 1.01) * 1.25;
    } else {
        const double pad = std::max(hi - lo, 1e-9) * 0.06;
        a.x_lo = lo - pad, a.x_hi = hi + pad;
    }
    a.y_hi = top > 0.0 ? top * 1.08 : 1.0;
    return a;
}

void draw_axes(Canvas& c, const Panel& p, const Axes& a) {
    for (double t : p.log_x ? log_ticks(a.x_lo, a.x_hi) : linear_ticks(a.x_hi)) {
        const int x = int(std::lround(a.px(t)));
        c.line(x, a.top, x, a.top + a.height, grid_grey);
        const std::string label = tick_label(t);
        c.text(x - Canvas::text_width(label) / 2, a.top + a.height + 8, label, axis_grey);
    }
    for (double t : linear_ticks(a.y_hi)) {
        const int y = int(std::lround(a.py(t)));
        c.line(a.left, y, a.left + a.width, y, grid_grey);
        const std::string label = tick_label(t);
        c.text(a.left - 8 - Canvas::text_width(label), y - 6, label, axis_grey);
    }
    c.line(a.left, a.top, a.left, a.top + a.height, black, 2);
    c.line(a.left, a.top + a.height, a.left + a.width, a.top + a.height, black, 2);
    c.text(a.left + (a.width - Canvas::text_width(p.title)) / 2, a.top - 28, p.title, black);
    c.text(a.left + (a.width - Canvas::text_width(p.x_label)) / 2, a.top + a.height + 34, p.x_label,
           black);
    c.text(a.left - 80, a.top + (a.height + Canvas::text_width(p.y_label)) / 2, p.y_label, black,
           text_scale, true);
}

void draw_points(Canvas& c, const Panel& p, const Axes& a) {
    std::vector<const PlotPoint*> front;
    for (const PlotPoint& pt : p.points)
        if (pt.front) front.push_back(&pt);
    std::sort(front.begin(), front.end(), [](const PlotPoint* l, const PlotPoint* r) {
        return l->series != r->series ? l->series < r->series : l->x < r->x;
    });
    for (std::size_t i = 1; i < front.size(); ++i) { // a staircase: what each cost buys at best
        if (front[i - 1]->series != front[i]->series) continue;
        const double x0 = a.px(front[i - 1]->x), y0 = a.py(front[i - 1]->y), x1 = a.px(front[i]->x),
                     y1 = a.py(front[i]->y);
        c.line(x0, y0, x1, y0, front[i]->front_color, 2);
        c.line(x1, y0, x1, y1, front[i]->front_color, 2);
    }
    for (const PlotPoint* pt : front)
        c.marker(a.px(pt->x), a.py(pt->y), Marker::circle, 10.0, pt->front_color, true);
    for (const PlotPoint& pt : p.points) {
        c.marker(a.px(pt.x), a.py(pt.y), pt.marker, 5.5, pt.color, pt.hollow);
        if (!pt.tag.empty()) c.text(int(a.px(pt.x)) + 8, int(a.py(pt.y)) - 12, pt.tag, pt.color, 1);
    }
}

// Legend entries flow left to right in rows; returns the rows' total height.
int draw_legend(Canvas* c, const std::vector<LegendEntry>& legend, int width, int y0) {
    int x = 20, y = y0 + 8;
    for (const LegendEntry& e : legend) {
        const int w = 40 + Canvas::text_width(e.label) + 24;
        if (x + w > width - 10 && x > 20) x = 20, y += legend_row;
        if (c) {
            if (e.line)
                c->line(x, y + 7, x + 28, y + 7, e.color, 2);
            else
                c->marker(x + 14, y + 7, e.marker, 6.0, e.color, e.hollow);
            c->text(x + 36, y, e.label, black);
        }
        x += w;
    }
    return y + legend_row - y0;
}

} // namespace

std::vector<std::size_t> pareto_front(const std::vector<double>& x, const std::vector<double>& y) {
    std::vector<std::size_t> order(x.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return x[a] != x[b] ? x[a] < x[b] : y[a] < y[b];
    });
    std::vector<std::size_t> front;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i : order)
        if (y[i] < best) { // cheaper points all have more error
            front.push_back(i);
            best = y[i];
        }
    return front;
}

Result<void> write_figure_png(const Figure& f, const std::string& path) {
    const int width = f.panel_width * std::max<int>(1, int(f.panels.size()));
    const int legend_height = draw_legend(nullptr, f.legend, width, 0);
    Canvas c(width, title_band + f.panel_height + legend_height);
    c.text((width - Canvas::text_width(f.title)) / 2, 12, f.title, black);
    for (std::size_t i = 0; i < f.panels.size(); ++i) {
        const Axes a = axes_for(f.panels[i], int(i) * f.panel_width, title_band, f.panel_width,
                                f.panel_height);
        draw_axes(c, f.panels[i], a);
        draw_points(c, f.panels[i], a);
    }
    draw_legend(&c, f.legend, width, title_band + f.panel_height);
    return write_png(path, c.width, c.height, 3, c.rgb);
}

} // namespace lantern::bench
