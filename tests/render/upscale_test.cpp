// Whole-number upscaling and letterboxing math, and mapping back (the mouse).
#include "lantern/render/upscale.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace lantern::render {
namespace {

TEST(Upscale, LargestWholeScaleThatFitsIsCentred) {
    EXPECT_EQ(fit_integer_scale({480, 270}, {1920, 1080}), (PresentRect{0, 0, 1920, 1080, 4}));
    EXPECT_EQ(fit_integer_scale({480, 270}, {1280, 720}), (PresentRect{160, 90, 960, 540, 2}));
    EXPECT_EQ(fit_integer_scale({480, 270}, {480, 270}), (PresentRect{0, 0, 480, 270, 1}));
    // 1366x768: 2x is 960x540; leftovers 406 and 228 split evenly.
    EXPECT_EQ(fit_integer_scale({480, 270}, {1366, 768}), (PresentRect{203, 114, 960, 540, 2}));
    // 2560x1440: scale 5 = 2400x1350.
    EXPECT_EQ(fit_integer_scale({480, 270}, {2560, 1440}), (PresentRect{80, 45, 2400, 1350, 5}));
}

TEST(Upscale, TheNarrowerSideDecides) {
    // Tall window: width allows 3x, height only 1x.
    EXPECT_EQ(fit_integer_scale({480, 270}, {1500, 300}), (PresentRect{510, 15, 480, 270, 1}));
    // Wide window: height allows 4x, width 2x.
    EXPECT_EQ(fit_integer_scale({480, 270}, {1000, 1100}), (PresentRect{20, 280, 960, 540, 2}));
}

TEST(Upscale, OddLeftoversGoToTheRightAndBottomBars) {
    const PresentRect r = fit_integer_scale({10, 10}, {25, 23});
    EXPECT_EQ(r, (PresentRect{2, 1, 20, 20, 2}));
    EXPECT_EQ(25 - (r.x + int(r.width)), 3);  // right bar
    EXPECT_EQ(23 - (r.y + int(r.height)), 2); // bottom bar
}

TEST(Upscale, SmallerDestinationShrinksWithTheAspectKept) {
    EXPECT_EQ(fit_integer_scale({480, 270}, {240, 200}), (PresentRect{0, 32, 240, 135, 0}));
    EXPECT_EQ(fit_integer_scale({480, 270}, {400, 100}), (PresentRect{111, 0, 177, 100, 0}));
    EXPECT_EQ(fit_integer_scale({480, 270}, {1, 1}), (PresentRect{0, 0, 1, 1, 0}));
}

TEST(Upscale, FillingScaleFollowsTheWindow) {
    // 1280x720 (the game's default window): 3x of 426x240 instead of 2x of 480x270 with 44 %
    // of the window in bars.
    EXPECT_EQ(fill_integer_scale({480, 270}, {1280, 720}), (platform::Extent{426, 240}));
    EXPECT_EQ(fit_integer_scale({426, 240}, {1280, 720}), (PresentRect{1, 0, 1278, 720, 3}));
    EXPECT_EQ(fill_integer_scale({480, 270}, {1920, 1080}), (platform::Extent{480, 270}));
    EXPECT_EQ(fill_integer_scale({480, 270}, {960, 540}), (platform::Extent{480, 270}));
    EXPECT_EQ(fill_integer_scale({480, 270}, {2560, 1440}), (platform::Extent{512, 288})); // 5.33 -> 5
    EXPECT_EQ(fill_integer_scale({480, 270}, {1366, 768}), (platform::Extent{455, 256}));  // 2.84 -> 3
    // Smaller than the design: scale 1, the window's own size.
    EXPECT_EQ(fill_integer_scale({480, 270}, {100, 100}), (platform::Extent{100, 100}));
    // An extreme shape is clamped to 4x the design per axis, the rest barred.
    EXPECT_EQ(fill_integer_scale({480, 270}, {16384, 64}), (platform::Extent{1920, 64}));
    EXPECT_TRUE(fill_integer_scale({480, 270}, {0, 720}).empty());
    EXPECT_TRUE(fill_integer_scale({0, 270}, {1280, 720}).empty());
}

TEST(Upscale, FillingScaleLeavesBarsNarrowerThanOneSourcePixel) {
    const platform::Extent design{480, 270};
    int windows = 0;
    for (std::uint32_t w = 64; w <= 4000; w += 37)
        for (std::uint32_t h = 64; h <= 2400; h += 41) {
            const platform::Extent dest{w, h};
            const platform::Extent src = fill_integer_scale(design, dest);
            const PresentRect r = fit_integer_scale(src, dest);
            ASSERT_GE(r.scale, 1u) << w << "x" << h;
            if (src.width < 4 * design.width) {
                EXPECT_LT(w - r.width, r.scale) << w << "x" << h;
            }
            if (src.height < 4 * design.height) {
                EXPECT_LT(h - r.height, r.scale) << w << "x" << h;
            }
            // The pixels keep about the design's size: the scale is the nearest whole number
            // to the smaller ratio.
            const double ratio = std::min(double(w) / design.width, double(h) / design.height);
            if (ratio >= 1.0) {
                EXPECT_LE(std::abs(double(r.scale) - ratio), 0.5) << w << "x" << h;
            }
            ++windows;
        }
    EXPECT_GT(windows, 5000);
}

TEST(Upscale, EmptySizesGiveAnEmptyRect) {
    EXPECT_TRUE(fit_integer_scale({480, 270}, {0, 0}).empty());
    EXPECT_TRUE(fit_integer_scale({480, 270}, {1280, 0}).empty());
    EXPECT_TRUE(fit_integer_scale({0, 270}, {1280, 720}).empty());
}

TEST(Upscale, DestinationPointsMapBackToSourcePixels) {
    const platform::Extent source{480, 270};
    const PresentRect r = fit_integer_scale(source, {1280, 720}); // 2x at (160, 90)
    EXPECT_EQ(destination_to_source(r, source, {160.0f, 90.0f}), glm::vec2(0.0f, 0.0f));
    EXPECT_EQ(destination_to_source(r, source, {161.5f, 91.0f}), glm::vec2(0.75f, 0.5f));
    EXPECT_EQ(destination_to_source(r, source, {1119.0f, 629.0f}), glm::vec2(479.5f, 269.5f));
    EXPECT_FALSE(destination_to_source(r, source, {159.9f, 300.0f}));  // left bar
    EXPECT_FALSE(destination_to_source(r, source, {1120.0f, 300.0f})); // right bar
    EXPECT_FALSE(destination_to_source(r, source, {500.0f, 630.0f}));  // bottom bar
    EXPECT_FALSE(destination_to_source(PresentRect{}, source, {0.0f, 0.0f}));
}

} // namespace
} // namespace lantern::render
