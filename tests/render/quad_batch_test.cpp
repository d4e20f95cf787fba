// QuadBatch drawn offscreen and read back, compared pixel for pixel with a CPU reference:
// coverage, depth order, painter's order, alpha blending, nearest texturing, large batches.
#include "lantern/render/quad_batch.hpp"

#include "lantern/gpu/device.hpp"
#include "lantern/render/render_target.hpp"
#include "render/render_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace lantern::render {
namespace {

std::uint32_t rgba8(const glm::vec4& c) {
    std::uint32_t packed = 0;
    for (int i = 0; i < 4; ++i) packed |= std::uint32_t(std::lround(c[i] * 255.0f)) << (8 * i);
    return packed;
}

// The colour the pixel (x, y) gets: the covering quad nearest in depth (later wins ties),
// or the clear colour. Quads are pixel-aligned, so coverage is exact.
std::uint32_t reference(const std::vector<Quad>& quads, bool depth_test, std::uint32_t x,
                        std::uint32_t y, std::uint32_t clear) {
    const float cx = float(x) + 0.5f, cy = float(y) + 0.5f;
    std::uint32_t color = clear;
    float nearest = 2.0f;
    for (const Quad& q : quads) {
        if (cx < q.min.x || cx >= q.max.x || cy < q.min.y || cy >= q.max.y) continue;
        if (depth_test && q.depth > nearest) continue;
        nearest = q.depth;
        color = rgba8(q.color);
    }
    return color;
}

class QuadBatchTest : public test::RenderTest {
  protected:
    // Draws `quads` into a fresh target and reads it back.
    Rgba8Image render(const std::vector<Quad>& quads, RenderTargetDesc target_desc,
                      gpu::BlendMode blend, const gpu::Image* texture = nullptr) {
        RenderTarget target = RenderTarget::create(device(), target_desc);
        QuadBatch batch =
            QuadBatch::create(device(), {target.color_format(), target.depth_format(), blend,
                                         static_cast<std::uint32_t>(quads.size())});
        for (const Quad& q : quads) batch.add(q);
        gpu::CommandList cmd = device().begin("quads");
        batch.upload(cmd);
        target.begin(cmd, {{0.0f, 0.0f, 0.0f, 1.0f}});
        batch.draw(cmd, target.extent(), texture);
        target.end(cmd);
        device().submit(std::move(cmd));
        return target.read_back();
    }

    void expect_reference(const Rgba8Image& image, const std::vector<Quad>& quads,
                          bool depth_test) {
        int mismatches = 0;
        for (std::uint32_t y = 0; y < image.height; ++y) {
            for (std::uint32_t x = 0; x < image.width; ++x) {
                const std::uint32_t want = reference(quads, depth_test, x, y, 0xff000000u);
                if (image.at(x, y) != want && ++mismatches <= 5)
                    ADD_FAILURE() << "pixel (" << x << ", " << y << "): " << std::hex
                                  << image.at(x, y) << " != " << want;
            }
        }
        EXPECT_EQ(mismatches, 0);
    }
};

const RenderTargetDesc small_unorm{64, 32, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT,
                                   "test target"};

TEST_F(QuadBatchTest, DepthTestedQuadsMatchTheReference) {
    const std::vector<Quad> quads = {
        {{4, 4}, {20, 20}, 0.5f, {1, 0, 0, 1}},
        {{12, 12}, {30, 28}, 0.25f, {0, 1, 0, 1}}, // in front of the red one
        {{16, 2}, {40, 10}, 0.75f, {0, 0, 1, 1}},  // behind it, drawn last
        {{50, 20}, {60, 32}, 0.5f, {0.2f, 0.4f, 0.6f, 1.0f}},
        {{0, 0}, {1, 1}, 0.9f, {1, 1, 1, 1}}, // the corner pixels
        {{63, 31}, {64, 32}, 0.9f, {1, 1, 0, 1}},
    };
    const Rgba8Image image = render(quads, small_unorm, gpu::BlendMode::opaque);
    ASSERT_EQ(image.width, 64u);
    ASSERT_EQ(image.height, 32u);
    expect_reference(image, quads, true);
    EXPECT_EQ(image.at(17, 8), 0xff0000ffu);  // red over blue
    EXPECT_EQ(image.at(14, 14), 0xff00ff00u); // green over red
}

TEST_F(QuadBatchTest, WithoutDepthLaterQuadsDrawOver) {
    const std::vector<Quad> quads = {
        {{4, 4}, {20, 20}, 0.1f, {1, 0, 0, 1}},
        {{10, 10}, {30, 28}, 0.9f, {0, 1, 0, 1}}, // farther, but later
    };
    RenderTargetDesc desc = small_unorm;
    desc.depth_format = VK_FORMAT_UNDEFINED;
    const Rgba8Image image = render(quads, desc, gpu::BlendMode::opaque);
    expect_reference(image, quads, false);
    EXPECT_EQ(image.at(12, 12), 0xff00ff00u);
}

TEST_F(QuadBatchTest, AlphaBlendsOverWhatIsThere) {
    // Alpha 64/255 is exact in 8 bits: white over red gives (255, 64, 64), over black 64.
    const std::vector<Quad> quads = {
        {{0, 0}, {32, 32}, 0.5f, {1, 0, 0, 1}},
        {{16, 0}, {48, 32}, 0.25f, {1, 1, 1, 64.0f / 255.0f}},
    };
    const Rgba8Image image = render(quads, small_unorm, gpu::BlendMode::alpha);
    EXPECT_EQ(image.at(8, 8), 0xff0000ffu);  // red alone
    EXPECT_EQ(image.at(20, 8), 0xff4040ffu); // white at 25% over red
    EXPECT_EQ(image.at(40, 8), 0xff404040u); // white at 25% over opaque black
    EXPECT_EQ(image.at(56, 8), 0xff000000u); // clear
}

TEST_F(QuadBatchTest, TexturedQuadSamplesNearest) {
    // A 4x4 texture drawn 8x8: each texel becomes an exact 2x2 block.
    gpu::Image texture = device().create_image(
        {4, 4, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "texels"});
    std::vector<std::uint32_t> texels(16);
    for (std::uint32_t i = 0; i < 16; ++i)
        texels[i] = 0xff000000u | (i * 16) | ((255 - i * 16) << 8) | (i * 7 << 16);
    device().upload(texture, std::as_bytes(std::span(texels)),
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const std::vector<Quad> quads = {{{8, 8}, {16, 16}, 0.5f, {1, 1, 1, 1}}};
    const Rgba8Image image = render(quads, small_unorm, gpu::BlendMode::opaque, &texture);
    for (std::uint32_t y = 0; y < 8; ++y) {
        for (std::uint32_t x = 0; x < 8; ++x)
            EXPECT_EQ(image.at(8 + x, 8 + y), texels[(y / 2) * 4 + x / 2]) << x << ", " << y;
    }
    EXPECT_EQ(image.at(7, 8), 0xff000000u);
    EXPECT_EQ(image.at(16, 15), 0xff000000u);
}

TEST_F(QuadBatchTest, BatchesBeyondSixtyFourKilobytesUploadThroughStaging) {
    // 2000 one-pixel quads = 80000 bytes of instances: more than vkCmdUpdateBuffer takes.
    std::vector<Quad> quads;
    for (std::uint32_t i = 0; i < 2000; ++i) {
        const float x = float(i % 64), y = float(i / 64);
        quads.push_back({{x, y},
                         {x + 1, y + 1},
                         0.5f,
                         {float(i % 251) / 255.0f, float(i % 13) / 255.0f, 1, 1}});
    }
    const Rgba8Image image = render(quads, small_unorm, gpu::BlendMode::opaque);
    expect_reference(image, quads, true);
}

TEST_F(QuadBatchTest, ReuploadReplacesTheQuads) {
    RenderTarget target = RenderTarget::create(device(), small_unorm);
    QuadBatch batch = QuadBatch::create(device(), {target.color_format(), target.depth_format()});
    for (int frame = 0; frame < 3; ++frame) {
        batch.clear();
        const float x = float(frame * 10);
        batch.add({{x, 0}, {x + 5, 5}, 0.5f, {0, 1, 0, 1}});
        gpu::CommandList cmd = device().begin("frame");
        batch.upload(cmd);
        target.begin(cmd);
        batch.draw(cmd, target.extent());
        target.end(cmd);
        device().submit(std::move(cmd));
    }
    const Rgba8Image image = target.read_back();
    EXPECT_EQ(image.at(22, 2), 0xff00ff00u); // the last frame's quad
    EXPECT_EQ(image.at(2, 2), 0xff000000u);  // the first frame's is gone
    EXPECT_EQ(batch.size(), 1u);
}

} // namespace
} // namespace lantern::render
