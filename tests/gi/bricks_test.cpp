// Adaptive bricks (lantern/gi/bricks.hpp, seed 002 in 2D): RGBM's error bound, flat light
// in the largest bricks, a linear ramp reproduced by bilinear filtering, rock left empty, and
// the error growing with eps while memory falls.
#include "lantern/gi/bricks.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

using namespace lantern::gi;

namespace {

Field field(int w, int h, auto value) {
    Field f;
    f.width = w;
    f.height = h;
    f.rgb.resize(std::size_t(w * h) * 3);
    f.air.assign(std::size_t(w * h), 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec3 v = value(x, y);
            for (int c = 0; c < 3; ++c) f.rgb[std::size_t((y * w + x) * 3 + c)] = v[c];
        }
    return f;
}

} // namespace

TEST(Bricks, RgbmKeepsEachChannelWithinHalfAStepOfItsScale) {
    for (glm::vec3 c : {glm::vec3(0.0f), glm::vec3(1.0f, 0.5f, 0.25f), glm::vec3(7.9f, 0.01f, 3.0f), glm::vec3(1e-3f, 2e-3f, 0.0f),
                        glm::vec3(8.0f, 8.0f, 8.0f)}) {
        std::uint8_t e[4];
        encode_rgbm(c, e);
        const glm::vec3 d = decode_rgbm(e);
        const float step = float(e[3]) / 255.0f * rgbm_range / 255.0f; // one rgb unit at this m
        for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(d[k] - c[k]), 0.5f * step + 1e-6f) << k;
    }
    std::uint8_t e[4];
    encode_rgbm(glm::vec3(100.0f, 0.0f, 0.0f), e); // above the range: clamped to 8, not wrapped
    EXPECT_NEAR(decode_rgbm(e).r, 8.0f, 1e-5f);
}

TEST(Bricks, FlatLightTakesTheLargestBricksAndARampIsExact) {
    const Field flat = field(64, 64, [](int, int) { return glm::vec3(0.5f, 0.4f, 0.3f); });
    const BrickAtlas a = build_bricks(flat, 0.01f);
    EXPECT_EQ(a.bricks_per_level[3], 4); // two 32-texel cells a side
    EXPECT_EQ(a.bricks(), 4);
    // Seed 002's maxLevel caps how coarse a brick may get: level 1 at most, 16-texel bricks.
    const BrickAtlas capped = build_bricks(flat, 0.01f, 0, 1);
    EXPECT_EQ(capped.bricks_per_level[1], 4 * 4 * 4);
    EXPECT_EQ(capped.bricks(), 4 * 4 * 4);
    for (int y = 0; y < 64; y += 7)
        for (int x = 0; x < 64; x += 7) EXPECT_NEAR(sample_bricks(capped, float(x) + 0.5f, float(y) + 0.5f).r, 0.5f, 0.01f);
    // A linear ramp at eps 0 (every brick at level 0): bilinear filtering between probes
    // reproduces it up to RGBM's rounding.
    const Field ramp = field(64, 64, [](int x, int y) { return glm::vec3(0.01f * float(x), 0.02f * float(y), 0.5f); });
    const BrickAtlas r = build_bricks(ramp, 0.0f);
    EXPECT_EQ(r.bricks_per_level[0], 16 * 16);
    for (int y = 0; y < 64; y += 3)
        for (int x = 0; x < 64; x += 5) {
            const glm::vec3 got = sample_bricks(r, float(x) + 0.5f, float(y) + 0.5f), want = ramp.at(x, y);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 0.01f) << x << ", " << y;
        }
}

TEST(Bricks, RockIsEmptyAndErrorGrowsWithEpsWhileMemoryFalls) {
    // A light at (20, 20) falling off over 24 texels; everything right of x = 48 is rock.
    Field f = field(96, 64, [](int x, int y) {
        const float d = std::hypot(float(x) - 20.0f, float(y) - 20.0f);
        return glm::vec3(std::max(0.0f, 2.0f * (1.0f - d / 24.0f)), std::max(0.0f, 1.0f - d / 24.0f), 0.2f);
    });
    for (int y = 0; y < 64; ++y)
        for (int x = 48; x < 96; ++x) f.air[std::size_t(y * 96 + x)] = 0;
    double last_error = -1.0;
    std::size_t last_bytes = ~std::size_t(0);
    for (float eps : {0.0f, 0.05f, 0.3f}) {
        const BrickAtlas a = build_bricks(f, eps);
        // A cell wholly in rock and more than one brick from open ground holds no brick: the
        // level-3 cell x 64..95 (a flat brick over open ground may still reach into rock
        // nearer than that, as the level-2 brick x 48..63 does).
        for (int cy = 0; cy < a.cells_y; ++cy)
            for (int cx = 16; cx < a.cells_x; ++cx)
                EXPECT_EQ(a.indirection[std::size_t(cy * a.cells_x + cx) * 4 + 3], 0) << "eps " << eps << " cell " << cx;
        double err2 = 0.0, ref2 = 0.0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 48; ++x) {
                const glm::vec3 d = sample_bricks(a, float(x) + 0.5f, float(y) + 0.5f) - f.at(x, y);
                err2 += double(glm::dot(d, d));
                ref2 += double(glm::dot(f.at(x, y), f.at(x, y)));
            }
        const double error = std::sqrt(err2 / ref2);
        std::printf("eps %.2f: %d bricks, %zu bytes, relative RMS error %.3f %%\n", double(eps), a.bricks(), a.bytes(),
                    100.0 * error);
        EXPECT_GE(error, last_error);
        EXPECT_LE(a.bytes(), last_bytes);
        last_error = error;
        last_bytes = a.bytes();
        if (eps == 0.0f) {
            EXPECT_LT(error, 0.01) << "RGBM and bilinear alone";
        }
    }
}

// Layers (the ground and the four faces at run time) share one atlas; each keeps its own
// indirection and reads back its own field.
TEST(Bricks, LayersShareOneAtlasAndEachReadsItsOwnField) {
    const Field ramp = field(40, 24, [](int x, int y) { return glm::vec3(0.05f * float(x), 0.02f * float(y), 0.3f); });
    const Field flat = field(40, 24, [](int, int) { return glm::vec3(0.1f, 0.9f, 0.2f); });
    Field dark = field(40, 24, [](int, int) { return glm::vec3(0.0f); });
    std::fill(dark.air.begin(), dark.air.end(), std::uint8_t(0)); // nothing kept: no bricks
    const Field layers[] = {ramp, flat, dark};
    const BrickAtlas a = build_bricks(layers, 0.0f);
    EXPECT_EQ(a.layers, 3);
    EXPECT_EQ(a.indirection.size(), std::size_t(a.cells_x * a.cells_y * 3 * 4));
    const BrickAtlas alone[] = {build_bricks(ramp, 0.0f), build_bricks(flat, 0.0f)};
    EXPECT_EQ(a.bricks(), alone[0].bricks() + alone[1].bricks());
    for (int y = 0; y < 24; y += 5)
        for (int x = 0; x < 40; x += 3) {
            const float px = float(x) + 0.5f, py = float(y) + 0.5f;
            for (int layer = 0; layer < 2; ++layer) {
                const glm::vec3 got = sample_bricks(a, px, py, layer), want = sample_bricks(alone[layer], px, py);
                for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(got[c], want[c]) << layer << " at " << x << ", " << y;
            }
            EXPECT_EQ(sample_bricks(a, px, py, 2), glm::vec3(0.0f));
        }
}

// More bricks than the atlas's 12-bit indices address (here 4,225 level-0 bricks in rows of
// one, 4,096 at most): reported in `too_many`, nothing stored, no abort. bake::runtime_light
// turns it into an error naming the world's size (lantern-render --bake of a huge world).
TEST(Bricks, MoreBricksThanTheIndicesAddressAreReportedNotStored) {
    const Field noisy = field(260, 260, [](int x, int y) {
        const float v = float((x * 7919 + y * 104729) % 97) / 97.0f;
        return glm::vec3(v, 1.0f - v, 0.5f);
    });
    const BrickAtlas a = build_bricks(noisy, 0.0f, 1);
    EXPECT_EQ(a.too_many, 65 * 65);
    EXPECT_TRUE(a.atlas.empty());
    EXPECT_TRUE(a.indirection.empty());
    const BrickAtlas fits = build_bricks(noisy, 0.0f, 2);
    EXPECT_EQ(fits.too_many, 0);
    EXPECT_EQ(fits.bricks(), 65 * 65);
}
