// RenderTarget formats and read-back, and the headless upscale (nearest blit, letterboxing)
// compared pixel for pixel.
#include "lantern/render/render_target.hpp"

#include "common/test_support.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/render/quad_batch.hpp"
#include "lantern/render/upscale.hpp"
#include "render/render_test_support.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace lantern::render {
namespace {

class RenderTargetTest : public test::RenderTest {
  protected:
    // Four quads in the corners and one across the middle, drawn into `target`.
    void draw_pattern(gpu::CommandList& cmd, RenderTarget& target) {
        const float w = float(target.extent().width), h = float(target.extent().height);
        batch_ = QuadBatch::create(
            device(), {target.color_format(), target.depth_format(), gpu::BlendMode::opaque});
        batch_.add({{0, 0}, {3, 2}, 0.5f, {1, 0, 0, 1}});
        batch_.add({{w - 2, 0}, {w, 3}, 0.5f, {0, 1, 0, 1}});
        batch_.add({{0, h - 1}, {1, h}, 0.5f, {0, 0, 1, 1}});
        batch_.add({{w - 1, h - 1}, {w, h}, 0.5f, {1, 1, 1, 1}});
        batch_.add({{4, h / 2}, {w - 4, h / 2 + 1}, 0.5f, {1, 0, 1, 1}});
        batch_.upload(cmd);
        target.begin(cmd, {{0.0f, 0.0f, 0.0f, 1.0f}});
        batch_.draw(cmd, target.extent());
        target.end(cmd);
    }
    // The upscale into a bigger image, read back: bars black, every source pixel an exact
    // scale x scale block. `source_format` and `destination_format` share an encoding.
    void expect_exact_upscale(VkFormat source_format, VkFormat destination_format) {
        gpu::Device& dev = device();
        RenderTarget target =
            RenderTarget::create(dev, {32, 16, source_format, VK_FORMAT_UNDEFINED, "source"});
        gpu::Image destination = dev.create_image(
            {100, 60, destination_format, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "destination"});
        const PresentRect rect = fit_integer_scale({32, 16}, {100, 60});
        ASSERT_EQ(rect, (PresentRect{2, 6, 96, 48, 3}));
        gpu::CommandList cmd = dev.begin("upscale");
        draw_pattern(cmd, target);
        record_upscale(cmd, target.color(), destination, rect,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        dev.submit(std::move(cmd));
        const Rgba8Image source = target.read_back();
        const std::vector<std::byte> bytes =
            dev.read_back(destination, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        const bool bgra = destination_format == VK_FORMAT_B8G8R8A8_UNORM ||
                          destination_format == VK_FORMAT_B8G8R8A8_SRGB;
        int mismatches = 0;
        for (std::uint32_t y = 0; y < 60; ++y) {
            for (std::uint32_t x = 0; x < 100; ++x) {
                const auto* p =
                    reinterpret_cast<const std::uint8_t*>(bytes.data()) + (y * 100 + x) * 4;
                const std::uint32_t got = bgra ? (0xff000000u | p[2] | (p[1] << 8) | (p[0] << 16))
                                               : (0xff000000u | p[0] | (p[1] << 8) | (p[2] << 16));
                const bool inside = x >= 2 && x < 98 && y >= 6 && y < 54;
                const std::uint32_t want =
                    inside ? (source.at((x - 2) / 3, (y - 6) / 3) | 0xff000000u) : 0xff000000u;
                if (got != want && ++mismatches <= 5)
                    ADD_FAILURE() << "(" << x << ", " << y << "): " << std::hex << got
                                  << " != " << want;
            }
        }
        EXPECT_EQ(mismatches, 0);
        EXPECT_EQ(source.at(0, 0), 0xff0000ffu); // the pattern is really there
    }

    void TearDown() override {
        batch_ = {};
        RenderTest::TearDown();
    }
    QuadBatch batch_;
};

TEST_F(RenderTargetTest, DefaultIsTheInternalPixelArtResolution) {
    RenderTarget target = RenderTarget::create(device());
    EXPECT_EQ(target.extent().width, 480u);
    EXPECT_EQ(target.extent().height, 270u);
    EXPECT_EQ(target.color_format(), VK_FORMAT_R8G8B8A8_SRGB);
    EXPECT_EQ(target.depth_format(), VK_FORMAT_D32_SFLOAT);
}

TEST_F(RenderTargetTest, BgraTargetReadsBackAsRgba) {
    RenderTarget target = RenderTarget::create(
        device(), {8, 4, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_UNDEFINED, "bgra"});
    gpu::CommandList cmd = device().begin("bgra");
    draw_pattern(cmd, target);
    device().submit(std::move(cmd));
    const Rgba8Image image = target.read_back();
    EXPECT_EQ(image.at(0, 0), 0xff0000ffu); // red, as r, g, b, a bytes
    EXPECT_EQ(image.at(7, 0), 0xff00ff00u);
    EXPECT_EQ(image.at(0, 3), 0xffff0000u);
    EXPECT_EQ(image.at(5, 1), 0xff000000u);
}

TEST_F(RenderTargetTest, SrgbTargetEncodesLinearColours) {
    RenderTarget target = RenderTarget::create(
        device(), {4, 2, VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_UNDEFINED, "srgb"});
    QuadBatch batch = QuadBatch::create(
        device(), {target.color_format(), VK_FORMAT_UNDEFINED, gpu::BlendMode::opaque});
    batch.add({{0, 0}, {1, 1}, 0.0f, {1, 0, 0, 1}});
    batch.add({{1, 0}, {2, 1}, 0.0f, {0.5f, 0.5f, 0.5f, 1}}); // linear 128/255
    gpu::CommandList cmd = device().begin("srgb");
    batch.upload(cmd);
    target.begin(cmd);
    batch.draw(cmd, target.extent());
    target.end(cmd);
    device().submit(std::move(cmd));
    const Rgba8Image image = target.read_back();
    EXPECT_EQ(image.at(0, 0), 0xff0000ffu); // 0 and 1 encode exactly
    const std::uint32_t grey = image.at(1, 0) & 0xff;
    EXPECT_GE(grey, 187u); // sRGB(128/255) = 187.9: encoded, not stored linearly (128)
    EXPECT_LE(grey, 189u);
}

TEST_F(RenderTargetTest, ScreenshotIsAPng) {
    RenderTarget target = RenderTarget::create(
        device(), {8, 4, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_UNDEFINED, "png"});
    gpu::CommandList cmd = device().begin("png");
    draw_pattern(cmd, target);
    device().submit(std::move(cmd));
    test::TempDir dir;
    ASSERT_TRUE(write_png(dir.file("shot.png"), target.read_back()));
    const std::string bytes = test::read_file(dir.file("shot.png"));
    ASSERT_GT(bytes.size(), 8u);
    EXPECT_EQ(bytes.substr(1, 3), "PNG");
}

TEST_F(RenderTargetTest, UpscaleIsExactAndLetterboxed) {
    expect_exact_upscale(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM);
}

TEST_F(RenderTargetTest, UpscaleBetweenSrgbFormatsIsExact) {
    expect_exact_upscale(VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_SRGB);
}

TEST_F(RenderTargetTest, UpscaleIntoATooSmallImageShrinks) {
    RenderTarget target = RenderTarget::create(
        device(), {32, 16, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_UNDEFINED, "source"});
    gpu::Image destination = device().create_image(
        {16, 16, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "small"});
    const PresentRect rect = fit_integer_scale({32, 16}, {16, 16});
    ASSERT_EQ(rect, (PresentRect{0, 4, 16, 8, 0}));
    gpu::CommandList cmd = device().begin("shrink");
    draw_pattern(cmd, target);
    record_upscale(cmd, target.color(), destination, rect, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    device().submit(std::move(cmd));
    const std::vector<std::byte> bytes =
        device().read_back(destination, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    auto pixel = [&](std::uint32_t x, std::uint32_t y) {
        std::uint32_t v = 0;
        std::memcpy(&v, bytes.data() + (y * 16 + x) * 4, 4);
        return v;
    };
    EXPECT_EQ(pixel(0, 0), 0xff000000u);  // top bar
    EXPECT_EQ(pixel(0, 15), 0xff000000u); // bottom bar
    EXPECT_EQ(pixel(0, 4), 0xff0000ffu);  // the red corner, halved
}

} // namespace
} // namespace lantern::render
