// gpu::Image and gpu::Sampler (engine/gpu additions for raster): upload/read-back round
// trips, deferred destruction, wrapped images, format helpers, depth attachments.
#include "lantern/gpu/device.hpp"
#include "lantern/render/quad_batch.hpp"

#include "gpu/gpu_test_support.hpp"
#include "render/render_test_support.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <numeric>
#include <vector>

namespace lantern::gpu {
namespace {

using ImageTest = test::RenderTest;

std::vector<std::byte> counting_bytes(std::size_t n) {
    std::vector<std::byte> bytes(n);
    for (std::size_t i = 0; i < n; ++i)
        bytes[i] = std::byte(static_cast<std::uint8_t>(i * 37 + 11));
    return bytes;
}

TEST_F(ImageTest, UploadAndReadBackRoundTrip) {
    for (VkFormat format : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB,
                            VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8_UNORM}) {
        Image image =
            device().create_image({7, 5, format, VK_IMAGE_USAGE_SAMPLED_BIT, "round trip"});
        EXPECT_EQ(image.extent().width, 7u);
        EXPECT_EQ(image.format(), format);
        EXPECT_EQ(image.aspect(), VkImageAspectFlags{VK_IMAGE_ASPECT_COLOR_BIT});
        EXPECT_TRUE(image.usage() & VK_IMAGE_USAGE_TRANSFER_SRC_BIT); // always added
        // Half floats: any 16-bit pattern that is not a NaN survives; keep the exponent low.
        std::vector<std::byte> texels = counting_bytes(7 * 5 * image_texel_size(format));
        if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
            for (std::size_t i = 1; i < texels.size(); i += 2) texels[i] &= std::byte{0x3b};
        }
        device().upload(image, texels, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        EXPECT_EQ(device().read_back(image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL), texels)
            << format;
    }
}

TEST_F(ImageTest, DestroyedWhileRecordedIsFreedAfterTheSubmission) {
    const std::size_t pending = device().pending_deletions();
    Image image = device().create_image(
        {4, 4, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "dropped"});
    Sampler sampler =
        device().create_sampler({VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, "dropped"});
    CommandList cmd = device().begin("clear");
    cmd.transition(image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    cmd.clear_color(image, {{1.0f, 0.0f, 0.0f, 1.0f}});
    image.reset();
    sampler.reset();
    EXPECT_FALSE(image);
    EXPECT_FALSE(sampler);
    EXPECT_EQ(device().pending_deletions(), pending + 2);
    device().collect(); // the list is still open: nothing may go
    EXPECT_EQ(device().pending_deletions(), pending + 2);
    device().wait(device().submit(std::move(cmd)));
    EXPECT_EQ(device().pending_deletions(), pending);
}

TEST_F(ImageTest, WrappedImageOwnsOnlyItsView) {
    Image owner = device().create_image(
        {4, 2, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "owner"});
    Image wrapped =
        device().wrap_image(owner.vk(), {4, 2, VK_FORMAT_R8G8B8A8_UNORM, owner.usage(), "wrapped"});
    EXPECT_EQ(wrapped.vk(), owner.vk());
    EXPECT_NE(wrapped.view(), owner.view());
    const std::vector<std::byte> texels = counting_bytes(4 * 2 * 4);
    device().upload(wrapped, texels, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    wrapped.reset();
    device().wait_idle();
    // The VkImage survived its wrapper (validation would report a use after free).
    EXPECT_EQ(device().read_back(owner, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL), texels);
}

TEST_F(ImageTest, FormatHelpers) {
    EXPECT_TRUE(device().supports_image_format(VK_FORMAT_R8G8B8A8_UNORM,
                                               VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                                   VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT |
                                                   VK_FORMAT_FEATURE_BLIT_DST_BIT));
    EXPECT_TRUE(device().supports_image_format(VK_FORMAT_D32_SFLOAT,
                                               VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT));
    EXPECT_FALSE(device().supports_image_format(VK_FORMAT_R8G8B8A8_UNORM,
                                                VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT));
    EXPECT_TRUE(is_depth_format(VK_FORMAT_D24_UNORM_S8_UINT));
    EXPECT_FALSE(is_depth_format(VK_FORMAT_B8G8R8A8_SRGB));
    EXPECT_EQ(format_aspects(VK_FORMAT_D32_SFLOAT), VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT});
    EXPECT_EQ(format_aspects(VK_FORMAT_D24_UNORM_S8_UINT),
              VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT});
    EXPECT_EQ(image_texel_size(VK_FORMAT_B8G8R8A8_UNORM), 4u);
    EXPECT_EQ(image_texel_size(VK_FORMAT_R16G16B16A16_SFLOAT), 8u);
    EXPECT_EQ(image_texel_size(VK_FORMAT_D32_SFLOAT), 4u);
    EXPECT_EQ(image_texel_size(VK_FORMAT_BC1_RGB_UNORM_BLOCK), 0u);
}

// Quads at known depths into a stored depth attachment, read back as floats (D32) or
// 24-bit values in 32-bit words (D24S8).
void expect_depth_values(Device& device, VkFormat depth_format) {
    Image color = device.create_image(
        {16, 8, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "color"});
    Image depth = device.create_image(
        {16, 8, depth_format, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "depth"});
    EXPECT_EQ(depth.aspect(), format_aspects(depth_format));
    render::QuadBatch batch =
        render::QuadBatch::create(device, {VK_FORMAT_R8G8B8A8_UNORM, depth_format});
    batch.add({{0, 0}, {8, 8}, 0.25f});
    batch.add({{4, 0}, {12, 4}, 0.75f}); // behind: the depth stays 0.25 where they overlap
    CommandList cmd = device.begin("depth");
    batch.upload(cmd);
    cmd.transition(color, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    cmd.transition(depth, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    cmd.begin_rendering({&color}, {&depth, VK_ATTACHMENT_LOAD_OP_CLEAR, 1.0f, true});
    batch.draw(cmd, color.extent());
    cmd.end_rendering();
    device.submit(std::move(cmd));
    const std::vector<std::byte> bytes =
        device.read_back(depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    ASSERT_EQ(bytes.size(), 16u * 8u * 4u);
    auto value = [&](std::uint32_t x, std::uint32_t y) {
        std::uint32_t word = 0;
        std::memcpy(&word, bytes.data() + (y * 16 + x) * 4, 4);
        if (depth_format == VK_FORMAT_D32_SFLOAT) return std::bit_cast<float>(word);
        return float(word & 0xffffff) / float(0xffffff);
    };
    const float tolerance = depth_format == VK_FORMAT_D32_SFLOAT ? 0.0f : 1.0f / 0xffffff;
    EXPECT_NEAR(value(1, 1), 0.25f, tolerance);
    EXPECT_NEAR(value(6, 2), 0.25f, tolerance);
    EXPECT_NEAR(value(10, 2), 0.75f, tolerance);
    EXPECT_NEAR(value(10, 6), 1.0f, tolerance);
    EXPECT_NEAR(value(15, 7), 1.0f, tolerance);
}

TEST_F(ImageTest, DepthAttachmentStoresAndReadsBackD32) {
    expect_depth_values(device(), VK_FORMAT_D32_SFLOAT);
}

TEST_F(ImageTest, DepthAttachmentStoresAndReadsBackD24S8) {
    if (!device().supports_image_format(VK_FORMAT_D24_UNORM_S8_UINT,
                                        VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT))
        GTEST_SKIP() << device().name() << " has no D24_UNORM_S8_UINT depth attachments";
    expect_depth_values(device(), VK_FORMAT_D24_UNORM_S8_UINT);
}

} // namespace
} // namespace lantern::gpu
