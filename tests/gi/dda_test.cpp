// Edge cases of the grid traversals (issue 3): axes, exact grid corners with both / one /
// neither side cell a wall, boundaries, lights inside walls, zero-length rays.
#include "gi_test_util.hpp"

#include "lantern/gi/reference.hpp"

#include <gtest/gtest.h>

using namespace lantern::gi;
using gi_test::grid_from_rows;
using gi_test::view_of;

namespace {
// A 6x6 room; rows[0] is z = 0.
const std::vector<std::string> open6 = {"......", "......", "......", "......", "......", "......"};
} // namespace

TEST(ShadowDda, AlongTheAxes) {
    auto g = grid_from_rows({"......", "......", "..#...", "......", "......", "......"});
    auto w = view_of(g);
    // Along +x at z = 2.5 through the wall at (2, 2).
    EXPECT_EQ(shadow_dda(w, {0.5f, 2.5f}, {4.5f, 2.5f}, 10.0f), 0.0f);
    // Along -x, stopping before the wall.
    EXPECT_EQ(shadow_dda(w, {5.5f, 2.5f}, {3.5f, 2.5f}, 10.0f), 1.0f);
    // Along +z through the wall column, and along z one column over.
    EXPECT_EQ(shadow_dda(w, {2.5f, 0.5f}, {2.5f, 5.5f}, 10.0f), 0.0f);
    EXPECT_EQ(shadow_dda(w, {3.5f, 0.5f}, {3.5f, 5.5f}, 10.0f), 1.0f);
    // Exactly on a grid line (x = 2.0): the bias puts the start in one cell consistently.
    EXPECT_EQ(shadow_dda(w, {2.0f, 0.5f}, {2.0f, 5.5f}, 10.0f), 0.0f);
}

TEST(ShadowDda, ThroughGridCorners) {
    // Light at (0.5, 0.5) to (2.5, 2.5) passes exactly through the corner (1, 1) and (2, 2).
    const glm::vec2 light(0.5f, 0.5f), pixel(2.5f, 2.5f);
    {   // Both side cells of the first corner are walls: blocked.
        auto g = grid_from_rows({".#....", "#.....", "......", "......", "......", "......"});
        EXPECT_EQ(shadow_dda(view_of(g), light, pixel, 10.0f), 0.0f);
    }
    {   // Only one side cell: light squeezes through the corner.
        auto g = grid_from_rows({".#....", "......", "......", "......", "......", "......"});
        EXPECT_EQ(shadow_dda(view_of(g), light, pixel, 10.0f), 1.0f);
        auto h = grid_from_rows({"......", "#.....", "......", "......", "......", "......"});
        EXPECT_EQ(shadow_dda(view_of(h), light, pixel, 10.0f), 1.0f);
    }
    {   // Neither.
        auto g = grid_from_rows(open6);
        EXPECT_EQ(shadow_dda(view_of(g), light, pixel, 10.0f), 1.0f);
    }
    {   // The diagonal cell itself is a wall: blocked whatever the sides.
        auto g = grid_from_rows({"......", ".#....", "......", "......", "......", "......"});
        EXPECT_EQ(shadow_dda(view_of(g), light, pixel, 10.0f), 0.0f);
    }
}

TEST(ShadowDda, ZeroLengthAndShortRays) {
    auto g = grid_from_rows(open6);
    EXPECT_EQ(shadow_dda(view_of(g), {2.5f, 2.5f}, {2.5f, 2.5f}, 10.0f), 1.0f);
    EXPECT_EQ(shadow_dda(view_of(g), {2.5f, 2.5f}, {2.50005f, 2.5f}, 10.0f), 1.0f);
}

TEST(ShadowDda, LightOnABoundaryAndInsideAWall) {
    auto g = grid_from_rows({"......", "......", "..#...", "......", "......", "......"});
    auto w = view_of(g);
    // A light inside a wall cell is blocked everywhere (its own cell is a wall).
    EXPECT_EQ(shadow_dda(w, {2.5f, 2.5f}, {4.5f, 4.5f}, 10.0f), 0.0f);
    EXPECT_EQ(shadow_dda(w, {2.5f, 2.5f}, {0.5f, 0.5f}, 10.0f), 0.0f);
    // A light on the wall's boundary: the bias moves the start off the line towards the
    // pixel, so rays leaving away from the wall are lit and rays crossing it are not.
    EXPECT_EQ(shadow_dda(w, {3.0f, 2.5f}, {5.5f, 2.5f}, 10.0f), 1.0f);
    EXPECT_EQ(shadow_dda(w, {3.0f, 2.5f}, {0.5f, 2.5f}, 10.0f), 0.0f);
}

TEST(ShadowDda, OutOfGridIsAir) {
    auto g = grid_from_rows({"##", "##"}, {10, 10});
    auto w = view_of(g);
    EXPECT_EQ(shadow_dda(w, {0.5f, 0.5f}, {8.5f, 0.5f}, 10.0f), 1.0f);  // never touches the grid
    EXPECT_EQ(shadow_dda(w, {9.5f, 10.5f}, {12.5f, 10.5f}, 10.0f), 0.0f); // crosses it
}

TEST(DirectionalDda, WallHeightTest) {
    // One wall at x = 5, sun low in the +x direction (light travels towards -x).
    auto g = grid_from_rows({"..........", ".....#....", ".........."});
    auto w = view_of(g);
    // to_sun = (0.8, 0.6, 0): vertical rate 0.75. Wall centre at distance d: blocked when
    // 0.75 * d < wall height.
    const glm::vec3 dir = glm::normalize(glm::vec3(-0.8f, -0.6f, 0.0f));
    EXPECT_EQ(directional_shadow_dda(w, {3.5f, 1.5f}, dir, 100.0f, 2.0f), 0.0f); // d = 2: 1.5 < 2
    EXPECT_EQ(directional_shadow_dda(w, {1.5f, 1.5f}, dir, 100.0f, 2.0f), 1.0f); // d = 4: 3 >= 2
    EXPECT_EQ(directional_shadow_dda(w, {1.5f, 1.5f}, dir, 100.0f, 4.0f), 0.0f); // taller walls
    // The reach limit: a short base distance stops before the wall.
    EXPECT_EQ(directional_shadow_dda(w, {3.5f, 1.5f}, dir, 1.0f, 2.0f), 1.0f);
    // Overhead sun: no grid shadow.
    EXPECT_EQ(directional_shadow_dda(w, {4.5f, 1.5f}, glm::vec3(0.0f, -1.0f, 0.0f), 100.0f, 2.0f), 1.0f);
    // Behind the wall relative to the sun: lit (the ray leaves the grid).
    EXPECT_EQ(directional_shadow_dda(w, {7.5f, 1.5f}, dir, 100.0f, 2.0f), 1.0f);
}

TEST(Penumbra, Modes) {
    // Hard edge.
    EXPECT_EQ(penumbra_factor(0.9f, 1.0f, 0.0f, 1.0f, 2), 1.0f);
    EXPECT_EQ(penumbra_factor(1.1f, 1.0f, 0.0f, 1.0f, 2), 0.0f);
    // Inward: fully occluded up to edge - width, none from the edge on.
    EXPECT_EQ(penumbra_factor(0.5f, 1.0f, 0.5f, 1.0f, 0), 1.0f);
    EXPECT_FLOAT_EQ(penumbra_factor(0.75f, 1.0f, 0.5f, 1.0f, 0), 0.5f);
    EXPECT_EQ(penumbra_factor(1.0f, 1.0f, 0.5f, 1.0f, 0), 0.0f);
    // Outward: full up to the edge, none from edge + width.
    EXPECT_EQ(penumbra_factor(1.0f, 1.0f, 0.5f, 1.0f, 1), 1.0f);
    EXPECT_FLOAT_EQ(penumbra_factor(1.25f, 1.0f, 0.5f, 1.0f, 1), 0.5f);
    // Both: centred on the edge.
    EXPECT_FLOAT_EQ(penumbra_factor(1.0f, 1.0f, 0.5f, 1.0f, 2), 0.5f);
    // Power shapes the curve.
    EXPECT_FLOAT_EQ(penumbra_factor(1.0f, 1.0f, 0.5f, 2.0f, 2), 0.25f);
}

TEST(ShadowProxy, CircleShadowBehindItOnly) {
    GpuShadowProxy p{glm::vec4(5.0f, 0.0f, 0.5f, 0.5f), glm::vec4(3.0f, 0.0f, 0.0f, 0.0f),
                     glm::vec4(1.0f, 1.0f, 0.0f, 2.0f)};
    std::vector<GpuShadowProxy> proxies{p};
    const glm::vec2 light(0.0f, 0.0f);
    EXPECT_EQ(point_proxy_shadow(proxies, light, {7.0f, 0.0f}), 0.0f);  // right behind it
    EXPECT_EQ(point_proxy_shadow(proxies, light, {7.0f, 2.0f}), 1.0f);  // off to the side
    EXPECT_EQ(point_proxy_shadow(proxies, light, {9.0f, 0.0f}), 1.0f);  // beyond max length
    EXPECT_EQ(point_proxy_shadow(proxies, light, {3.0f, 0.0f}), 1.0f);  // in front of it
    EXPECT_EQ(point_proxy_shadow(proxies, {10.0f, 0.0f}, {7.0f, 0.0f}), 1.0f); // light on the other side
    // The sun casts along its travel direction.
    EXPECT_EQ(directional_proxy_shadow(proxies, {7.0f, 0.0f}, glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f))), 0.0f);
    EXPECT_EQ(directional_proxy_shadow(proxies, {3.0f, 0.0f}, glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f))), 1.0f);
}

TEST(ShadowProxy, BoxWidthModes) {
    GpuShadowProxy box{glm::vec4(0.0f, 0.0f, 1.0f, 0.25f), glm::vec4(3.0f, 0.0f, 0.0f, 0.0f),
                       glm::vec4(1.0f, 0.0f, 0.0f, 2.0f)};
    // Projected width onto the perpendicular axis.
    EXPECT_FLOAT_EQ(proxy_width(box, {0.0f, 1.0f}), 0.25f);
    EXPECT_FLOAT_EQ(proxy_width(box, {1.0f, 0.0f}), 1.0f);
    box.modes.z = 1.0f; // max axis
    EXPECT_FLOAT_EQ(proxy_width(box, {0.0f, 1.0f}), 1.0f);
}
