#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/window.hpp"
#include <optional>

#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

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

// gi.window_snap "texel": the origin locks to texel boundaries (times the heat scale), so the
// window steps a quarter of a tile at 4 texels per tile instead of a whole tile, still
// covering the view; walking changes the window (and so the GI's cache key) that
// much more often.
TEST(GiWindow, TexelSnapStepsByTexelsAndCoversTheView) {
    lantern::scene::GiSettings tile, texel, texel_half;
    tile.resolution = texel.resolution = texel_half.resolution = 4;
    tile.padding = texel.padding = texel_half.padding = 1.25f;
    texel.window_snap = texel_half.window_snap = lantern::scene::WindowSnap::texel;
    texel_half.heat_scale = lantern::scene::HeatScale::half;
    EXPECT_EQ(lantern::gi::window_snap_texels(tile), 4);
    EXPECT_EQ(lantern::gi::window_snap_texels(texel), 1);
    EXPECT_EQ(lantern::gi::window_snap_texels(texel_half), 2);

    int changes[3] = {0, 0, 0};
    std::optional<lantern::gi::GiWindow> last[3];
    const lantern::scene::GiSettings* settings[3] = {&tile, &texel, &texel_half};
    for (int step = 0; step <= 400; ++step) { // 8 tiles in steps of 0.02 along x and 0.01 along z
        const OrthoView view{{100.0f + 0.02f * float(step), 50.0f - 0.01f * float(step)}, {30.0f, 16.875f}};
        for (int m = 0; m < 3; ++m) {
            auto w = compute_window(view, *settings[m]);
            ASSERT_TRUE(w);
            const int snap = lantern::gi::window_snap_texels(*settings[m]);
            const glm::ivec2 origin = lantern::gi::window_texel_origin(*w);
            EXPECT_EQ(origin.x % snap, 0);
            EXPECT_EQ(origin.y % snap, 0);
            EXPECT_FLOAT_EQ(w->view.min_x * 4.0f, float(origin.x)); // a whole texel
            // The view lies inside the window (the padding absorbs the snap).
            EXPECT_LE(w->view.min_x, view.center.x - 0.5f * view.size.x);
            EXPECT_GE(w->view.min_x + w->view.width, view.center.x + 0.5f * view.size.x);
            EXPECT_LE(w->view.min_z, view.center.y - 0.5f * view.size.y);
            EXPECT_GE(w->view.min_z + w->view.height, view.center.y + 0.5f * view.size.y);
            if (last[m] && !(*last[m] == *w)) ++changes[m];
            last[m] = w;
        }
    }
    // 8 tiles along x and 4 along z: ~12 whole-tile steps, ~48 texel steps, ~24 two-texel steps.
    EXPECT_NEAR(changes[0], 12, 2);
    EXPECT_NEAR(changes[1], 48, 4);
    EXPECT_NEAR(changes[2], 24, 3);
}

TEST(GiWindow, TexelSnapOnATileBoundaryIsTheTileWindow) {
    lantern::scene::GiSettings tile, texel;
    texel.window_snap = lantern::scene::WindowSnap::texel;
    // padding 1.4 around centre (21, 11.2) with size 30 x 16: min (0, 0), a tile corner.
    const OrthoView view{{21.0f, 11.2f}, {30.0f, 16.0f}};
    EXPECT_EQ(*compute_window(view, tile), *compute_window(view, texel));
}

// Shadow proxies beyond the cap fade instead of popping (issue 19; gather_offers_faded): as
// the camera slides past a row of proxies, each proxy's strength (0 when not gathered) moves
// by at most twice the window's own move over the fade band (a priority and the cut each
// move by at most the window's move), so none appears or vanishes at once: the window
// phase-locks to whole tiles, so with a band of 4 a proxy fades out over at least 2 window
// steps. Nearer ones are whole; under the cap nothing fades.
TEST(GatherOffers, ProxiesNearTheCapFadeContinuouslyAsTheWindowMoves) {
    using namespace lantern::gi;
    std::vector<Offer> offers;
    for (std::uint32_t i = 0; i < 40; ++i) offers.push_back({{float(i) * 1.5f, 3.0f}, 2.0f, i, 0.0f});
    constexpr float band = 4.0f;
    constexpr std::size_t cap = 8;
    std::vector<float> last(offers.size(), -1.0f);
    glm::vec2 last_center(0.0f);
    int steps = 0;
    const float step = 1.0f / 16.0f; // the camera moves a sixteenth of a tile per frame
    for (float x = 0.0f; x < 50.0f; x += step) {
        auto w = compute_window(OrthoView{{x, 3.0f}, {30.0f, 16.875f}}, 1.25f, 4);
        ASSERT_TRUE(w);
        const FadedOffers kept = gather_offers_faded(offers, *w, cap, band);
        ASSERT_LE(kept.ids.size(), cap);
        ASSERT_EQ(kept.fade.size(), kept.ids.size());
        std::vector<float> now(offers.size(), 0.0f);
        for (std::size_t k = 0; k < kept.ids.size(); ++k) now[kept.ids[k]] = kept.fade[k];
        EXPECT_EQ(kept.ids, gather_offers(offers, *w, cap)) << "the same set as without fading";
        // The proxy nearest the window's centre is whole.
        std::uint32_t nearest = 0;
        for (std::uint32_t i = 1; i < offers.size(); ++i)
            if (glm::distance(offers[i].position, w->center()) < glm::distance(offers[nearest].position, w->center()))
                nearest = i;
        EXPECT_FLOAT_EQ(now[nearest], 1.0f) << "x " << x;
        if (last[0] >= 0.0f) {
            const float moved = glm::distance(w->center(), last_center);
            EXPECT_LE(moved, 1.0f + 1e-4f) << "the window steps a tile at a time";
            steps += moved > 0.0f ? 1 : 0;
            for (std::size_t i = 0; i < offers.size(); ++i)
                EXPECT_LE(std::abs(now[i] - last[i]), 2.0f * moved / band + 1e-4f) << "proxy " << i << " popped at x " << x;
        }
        last = now;
        last_center = w->center();
    }
    EXPECT_GT(steps, 40) << "the window moved";
    // Under the cap: no fading at all.
    auto w = compute_window(OrthoView{{0.0f, 3.0f}, {30.0f, 16.875f}}, 1.25f, 4);
    const FadedOffers all = gather_offers_faded(offers, *w, 100, band);
    for (float f : all.fade) EXPECT_EQ(f, 1.0f);
    // band 0: the old cut, every kept proxy whole.
    const FadedOffers hard = gather_offers_faded(offers, *w, cap, 0.0f);
    for (float f : hard.fade) EXPECT_EQ(f, 1.0f);
}

TEST(GiWindow, BlocksInOneTileOnlyWhereEveryBlocksTexelsShareTheirTile) {
    using lantern::gi::blocks_in_one_tile;
    using lantern::gi::GiWindow;
    // A window at texel origin (tx, tz) of w x h texels at `res`, as compute_window places it.
    auto window = [](int res, long tx, long tz, int w, int h) {
        GiWindow win;
        win.resolution = res;
        win.width = w;
        win.height = h;
        win.view = {float(double(tx) / res), float(double(tz) / res), float(double(w) / res), float(double(h) / res)};
        return win;
    };
    // Whether every 4 x block_h block's texel centres (as the shaders and GiWindow compute
    // them, in float) fall in the tile of the block's first texel.
    auto shares = [](const GiWindow& win, int block_h) {
        for (int y = 0; y < win.height; ++y)
            for (int x = 0; x < win.width; ++x) {
                const glm::vec2 p = win.texel_center(x, y), o = win.texel_center(x & ~3, y - y % block_h);
                if (std::floor(p.x) != std::floor(o.x) || std::floor(p.y) != std::floor(o.y)) return false;
            }
        return true;
    };
    int yes = 0, no = 0;
    for (int res : {1, 2, 3, 4, 6, 8, 12, 16})
        for (int block_h : {1, 2, 4, 8})
            for (long tx : {0L, 2L, 4L, 8L, -4L, -6L, -16L, 36L, 4000000L, -4194300L})
                for (long tz : {0L, 1L, 4L, -8L, 12L}) {
                    const GiWindow win = window(res, tx, tz, 64, 40);
                    if (!blocks_in_one_tile(win, std::uint32_t(block_h))) {
                        ++no;
                        continue;
                    }
                    ++yes;
                    EXPECT_TRUE(shares(win, block_h)) << "res " << res << " block_h " << block_h << " origin " << tx << ", " << tz;
                    // And every centre is exact: (t + i + 0.5) / res.
                    EXPECT_EQ(double(win.texel_center(63, 39).x), (double(tx) + 63.5) / res);
                    EXPECT_EQ(double(win.texel_center(63, 39).y), (double(tz) + 39.5) / res);
                }
    EXPECT_GT(yes, 50);
    EXPECT_GT(no, 50);
    // The cases the rule names.
    EXPECT_TRUE(blocks_in_one_tile(window(8, 16, 8, 64, 64), 4));
    EXPECT_TRUE(blocks_in_one_tile(window(4, -8, -4, 64, 64), 1));
    EXPECT_FALSE(blocks_in_one_tile(window(8, 18, 8, 64, 64), 4)); // x origin not a multiple of 4
    EXPECT_FALSE(blocks_in_one_tile(window(8, 16, 2, 64, 64), 4)); // z origin not a multiple of block_h
    EXPECT_FALSE(blocks_in_one_tile(window(12, 0, 0, 64, 64), 4)); // not a power of two
    EXPECT_FALSE(blocks_in_one_tile(window(2, 0, 0, 64, 64), 1));  // a tile narrower than a block
    EXPECT_FALSE(blocks_in_one_tile(window(4, 0, 0, 64, 64), 8));  // a block taller than a tile
    EXPECT_FALSE(blocks_in_one_tile(window(8, 1L << 22, 0, 64, 64), 4)); // centres no longer exact
    GiWindow half = window(8, 16, 8, 64, 64);
    half.view.min_x += 0.0625f; // half a texel: no whole texel origin
    EXPECT_FALSE(blocks_in_one_tile(half, 4));
}
