// The ImGui overlay headless: it draws its windows over an image at full resolution,
// keeps what is under them, works frame after frame (its buffer ring), refuses a second
// overlay, all without validation messages.
#include "lantern/render/imgui_overlay.hpp"

#include "lantern/gpu/device.hpp"
#include "render/render_test_support.hpp"

#include <gtest/gtest.h>
#include <imgui.h>

#include <cstring>

namespace lantern::render {
namespace {

using ImGuiOverlayTest = test::RenderTest;

constexpr std::uint32_t width = 320, height = 180;

// A cleared target, an ImGui window at (20, 20) of 120x60, read back.
std::vector<std::uint32_t> draw_frame(gpu::Device& device, ImGuiOverlay& overlay,
                                      const gpu::Image& target, int frame) {
    overlay.new_frame({width, height});
    ImGui::SetNextWindowPos(ImVec2(20, 20));
    ImGui::SetNextWindowSize(ImVec2(120, 60));
    ImGui::Begin("HUD", nullptr, ImGuiWindowFlags_NoCollapse);
    ImGui::Text("frame %d", frame);
    ImGui::End();
    gpu::CommandList cmd = device.begin("overlay frame");
    cmd.transition(target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    cmd.clear_color(target, {{0.0f, 0.0f, 1.0f, 1.0f}}); // blue "scene"
    cmd.transition(target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    overlay.record(cmd, target);
    device.submit(std::move(cmd));
    const std::vector<std::byte> bytes =
        device.read_back(target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    std::vector<std::uint32_t> pixels(width * height);
    std::memcpy(pixels.data(), bytes.data(), bytes.size());
    return pixels;
}

TEST_F(ImGuiOverlayTest, DrawsItsWindowOverTheImage) {
    auto overlay =
        ImGuiOverlay::create(device(), {.format = VK_FORMAT_R8G8B8A8_UNORM,
                                        .final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL});
    ASSERT_TRUE(overlay) << overlay.error().message;
    gpu::Image target =
        device().create_image({width, height, VK_FORMAT_R8G8B8A8_UNORM,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "overlay target"});
    constexpr std::uint32_t blue = 0xffff0000u;
    for (int frame = 0; frame < 5; ++frame) { // more frames than ImGui's buffer ring
        const std::vector<std::uint32_t> pixels = draw_frame(device(), *overlay, target, frame);
        EXPECT_EQ(pixels[5 * width + 5], blue) << "outside the ImGui window";
        EXPECT_EQ(pixels[170 * width + 300], blue);
        EXPECT_NE(pixels[60 * width + 80], blue) << "inside the ImGui window";
        int changed = 0;
        for (std::uint32_t y = 20; y < 80; ++y)
            for (std::uint32_t x = 20; x < 140; ++x) changed += pixels[y * width + x] != blue;
        EXPECT_GT(changed, 120 * 60 * 9 / 10) << "the window covers its rectangle";
    }
    EXPECT_FALSE(overlay->wants_keyboard());
}

TEST_F(ImGuiOverlayTest, OnlyOneOverlayAtATime) {
    auto first = ImGuiOverlay::create(device(), {.format = VK_FORMAT_R8G8B8A8_UNORM});
    ASSERT_TRUE(first) << first.error().message;
    auto second = ImGuiOverlay::create(device(), {.format = VK_FORMAT_R8G8B8A8_UNORM});
    ASSERT_FALSE(second);
    EXPECT_NE(second.error().message.find("one overlay"), std::string::npos);
}

TEST_F(ImGuiOverlayTest, ANewOverlayAfterTheFirstWasDestroyed) {
    {
        auto first = ImGuiOverlay::create(device(), {.format = VK_FORMAT_R8G8B8A8_UNORM});
        ASSERT_TRUE(first) << first.error().message;
    }
    auto second = ImGuiOverlay::create(device(), {.format = VK_FORMAT_B8G8R8A8_UNORM});
    EXPECT_TRUE(second) << second.error().message;
}

} // namespace
} // namespace lantern::render
