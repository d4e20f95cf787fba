#include "lantern/transport/progress.hpp"

#include "lantern/core/clock.hpp"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace lantern::transport {
namespace {

constexpr int bar_width = 30;
constexpr std::int64_t redraw_interval_ns = 100'000'000; // 10 Hz

} // namespace

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), interactive_(isatty(STDERR_FILENO)) {}

ProgressBar::~ProgressBar() {
    if (drawn_) std::fputc('\n', stderr);
}

void ProgressBar::update(double fraction, const std::string& status) {
    if (!interactive_) return;
    const std::int64_t now = now_ns();
    if (drawn_ && now - last_draw_ns_ < redraw_interval_ns) return;
    last_draw_ns_ = now;
    draw(fraction, status);
}

void ProgressBar::finish(const std::string& status) {
    if (interactive_) {
        draw(1.0, status);
        std::fputc('\n', stderr);
        drawn_ = false;
    } else {
        std::fprintf(stderr, "%s: %s\n", label_.c_str(), status.c_str());
    }
}

void ProgressBar::draw(double fraction, const std::string& status) {
    const int filled = int(std::clamp(fraction, 0.0, 1.0) * bar_width + 0.5);
    char bar[bar_width + 1];
    for (int i = 0; i < bar_width; ++i) bar[i] = i < filled ? '#' : '.';
    bar[bar_width] = '\0';
    // \033[K clears what a longer previous line left behind.
    std::fprintf(stderr, "\r%s [%s] %3d%% %s\033[K", label_.c_str(), bar,
                 int(std::clamp(fraction, 0.0, 1.0) * 100.0), status.c_str());
    std::fflush(stderr);
    drawn_ = true;
}

} // namespace lantern::transport
