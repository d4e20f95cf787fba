// The swapchain's choices as pure functions: present mode, surface format, extent, image count.
#include "lantern/render/swapchain.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace lantern::render {
namespace {

TEST(SwapchainChoice, VsyncIsFifo) {
    const std::vector<VkPresentModeKHR> all = {
        VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_FIFO_KHR};
    EXPECT_EQ(choose_present_mode(all, true), VK_PRESENT_MODE_FIFO_KHR);
}

TEST(SwapchainChoice, NoVsyncPrefersMailboxThenImmediateThenFifo) {
    EXPECT_EQ(
        choose_present_mode(std::vector{VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR,
                                        VK_PRESENT_MODE_FIFO_KHR},
                            false),
        VK_PRESENT_MODE_MAILBOX_KHR);
    EXPECT_EQ(choose_present_mode(
                  std::vector{VK_PRESENT_MODE_FIFO_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR}, false),
              VK_PRESENT_MODE_IMMEDIATE_KHR);
    EXPECT_EQ(choose_present_mode(
                  std::vector{VK_PRESENT_MODE_FIFO_KHR, VK_PRESENT_MODE_FIFO_RELAXED_KHR}, false),
              VK_PRESENT_MODE_FIFO_KHR);
}

TEST(SwapchainChoice, SurfaceFormatPrefersTheWantedEncoding) {
    const std::vector<VkSurfaceFormatKHR> both = {
        {VK_FORMAT_B8G8R8A8_UNORM, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR},
        {VK_FORMAT_B8G8R8A8_SRGB, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR}};
    EXPECT_EQ(choose_surface_format(both, true).format, VK_FORMAT_B8G8R8A8_SRGB);
    EXPECT_EQ(choose_surface_format(both, false).format, VK_FORMAT_B8G8R8A8_UNORM);
    // Only the other encoding: take it.
    const std::vector<VkSurfaceFormatKHR> unorm = {
        {VK_FORMAT_R8G8B8A8_UNORM, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR}};
    EXPECT_EQ(choose_surface_format(unorm, true).format, VK_FORMAT_R8G8B8A8_UNORM);
    // Nothing known: the first.
    const std::vector<VkSurfaceFormatKHR> odd = {
        {VK_FORMAT_A2B10G10R10_UNORM_PACK32, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR},
        {VK_FORMAT_R16G16B16A16_SFLOAT, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR}};
    EXPECT_EQ(choose_surface_format(odd, true).format, VK_FORMAT_A2B10G10R10_UNORM_PACK32);
}

TEST(SwapchainChoice, ExtentIsTheSurfacesOrTheClampedFramebuffer) {
    VkSurfaceCapabilitiesKHR caps{};
    caps.currentExtent = {800, 600};
    caps.minImageExtent = {1, 1};
    caps.maxImageExtent = {4096, 4096};
    EXPECT_EQ(choose_extent(caps, {1024, 768}).width, 800u); // the surface decides
    caps.currentExtent = {UINT32_MAX, UINT32_MAX};           // the swapchain decides
    const VkExtent2D chosen = choose_extent(caps, {1024, 768});
    EXPECT_EQ(chosen.width, 1024u);
    EXPECT_EQ(chosen.height, 768u);
    caps.maxImageExtent = {640, 480};
    EXPECT_EQ(choose_extent(caps, {1024, 768}).width, 640u);
    EXPECT_EQ(choose_extent(caps, {1024, 768}).height, 480u);
}

TEST(SwapchainChoice, ImageCountIsOneAboveTheMinimumWithinTheMaximum) {
    VkSurfaceCapabilitiesKHR caps{};
    caps.minImageCount = 2;
    caps.maxImageCount = 0; // no limit
    EXPECT_EQ(choose_image_count(caps), 3u);
    caps.maxImageCount = 2;
    EXPECT_EQ(choose_image_count(caps), 2u);
}

} // namespace
} // namespace lantern::render
