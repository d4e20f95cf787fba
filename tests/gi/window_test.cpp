#include "lantern/gi/window.hpp"

#include <gtest/gtest.h>

#include <cmath>

using lantern::gi::compute_window;
using lantern::scene::OrthoView;
using lantern::scene::PerspectiveCamera;

TEST(GiWindow, OrthoPaddingSnapAndMinimum) {
    // 30 x 16.875 tiles (480x270 at 16 px per tile), padding 1.4, giRes 16: the seed's table.
    auto w = compute_window(OrthoView{{100.3f, 50.7f}, {30.0f, 16.875f}}, 1.4f, 16);
    ASSERT_TRUE(w);
    // 42 x 23.625 padded -> 672 x 378 texels -> snapped up to whole tiles: 672 x 384.
    EXPECT_EQ(w->width, 672);
    EXPECT_EQ(w->height, 384);
    EXPECT_FLOAT_EQ(w->view.width, 42.0f);
    EXPECT_FLOAT_EQ(w->view.height, 24.0f);
    // Origin phase-locked down to whole tiles: 100.3 - 21 = 79.3 -> 79; 50.7 - 11.8125 -> 38.
    EXPECT_EQ(w->view.min_x, 79.0f);
    EXPECT_EQ(w->view.min_z, 38.0f);
    // Texel centres follow (floor(p * res) + 0.5) / res.
    auto c = w->texel_center(5, 7);
    EXPECT_FLOAT_EQ(c.x, 79.0f + 5.5f / 16.0f);
    EXPECT_FLOAT_EQ(c.y, 38.0f + 7.5f / 16.0f);

    auto small = compute_window(OrthoView{{0.5f, 0.5f}, {3.0f, 2.0f}}, 1.0f, 8);
    ASSERT_TRUE(small);
    EXPECT_EQ(small->width, 64); // 24 -> minimum 64 (a multiple of 8: still whole tiles)
    EXPECT_EQ(small->height, 64);
    EXPECT_FLOAT_EQ(small->view.width, 8.0f);
}

TEST(GiWindow, MinimumKeepsWholeTilesForOddResolutions) {
    auto w = compute_window(OrthoView{{0.0f, 0.0f}, {2.0f, 2.0f}}, 1.0f, 7);
    ASSERT_TRUE(w);
    EXPECT_EQ(w->width, 64); // the minimum applies after the snap (seed order)
    EXPECT_FLOAT_EQ(w->view.width, 64.0f / 7.0f);
}

TEST(GiWindow, PhaseLockIgnoresSubTileMotion) {
    auto a = compute_window(OrthoView{{40.05f, 20.85f}, {30.0f, 16.875f}}, 1.4f, 8);
    auto b = compute_window(OrthoView{{40.9f, 21.7f}, {30.0f, 16.875f}}, 1.4f, 8);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(*a, *b);
    auto c = compute_window(OrthoView{{41.5f, 20.85f}, {30.0f, 16.875f}}, 1.4f, 8); // crosses a tile
    ASSERT_TRUE(c);
    EXPECT_EQ(c->view.min_x, a->view.min_x + 1.0f);
}

TEST(GiWindow, CameraFootprint) {
    // Straight down from 20 units with a 90 degree vertical fov and aspect 1: a 40 x 40 square.
    PerspectiveCamera cam{{10.0f, 20.0f, 10.0f}, {10.0f, 0.0f, 10.0f}, 90.0f, 1.0f};
    auto area = lantern::gi::visible_area(cam);
    ASSERT_TRUE(area);
    EXPECT_NEAR(area->min.x, -10.0f, 1e-4);
    EXPECT_NEAR(area->size.x, 40.0f, 1e-4);
    EXPECT_NEAR(area->size.y, 40.0f, 1e-4);
    // Tilted like SCENES.md's example: the far edge is wider than the near one.
    PerspectiveCamera tilted{{32.0f, 20.0f, 30.0f}, {32.0f, 0.0f, 40.0f}, 40.0f, 1.7778f};
    auto t = compute_window(tilted, 1.4f, 8);
    ASSERT_TRUE(t);
    EXPECT_GT(t->view.height, 10.0f);
    EXPECT_EQ(t->view.min_x, std::floor(t->view.min_x));
}

TEST(GiWindow, CameraBailsOutCleanly) {
    std::string reason;
    // Looking at the horizon: the top corner rays never reach the ground.
    PerspectiveCamera horizon{{0.0f, 5.0f, 0.0f}, {0.0f, 5.0f, 100.0f}, 40.0f, 1.0f};
    EXPECT_FALSE(compute_window(horizon, 1.4f, 8, &reason));
    EXPECT_FALSE(reason.empty());
    // A corner ray exactly parallel to the ground.
    PerspectiveCamera parallel{{0.0f, 5.0f, 0.0f}, {0.0f, 0.0f, 5.0f}, 90.0f, 1.0f};
    reason.clear();
    EXPECT_FALSE(compute_window(parallel, 1.4f, 8, &reason));
    EXPECT_NE(reason.find("parallel"), std::string::npos) << reason;
    // Non-finite input.
    PerspectiveCamera nan_cam{{NAN, 5.0f, 0.0f}, {0.0f, 0.0f, 5.0f}, 60.0f, 1.0f};
    EXPECT_FALSE(compute_window(nan_cam, 1.4f, 8));
    EXPECT_FALSE(compute_window(OrthoView{{INFINITY, 0.0f}, {10.0f, 10.0f}}, 1.4f, 8));
    // Too large for the texture limit.
    EXPECT_FALSE(compute_window(OrthoView{{0.0f, 0.0f}, {5000.0f, 10.0f}}, 1.0f, 32, &reason, 16384));
    EXPECT_NE(reason.find("limit"), std::string::npos);
}
