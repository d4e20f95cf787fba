// Helpers for engine::render tests.
//
// RenderTest: one Device per test process with DeviceOptions::graphics and validation (no
// presentation: offscreen tests need no display); skipped, with the reason, where there is
// none; any validation message during a test fails it (printed).
//
// WindowedTest: a real window under Xvfb with a Device made by render::add_presentation
// (validation on), its surface and a Swapchain; skipped where Xvfb, the X tools or a
// Vulkan device are missing. Validation messages fail the test too.
#pragma once

#include "common/test_support.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/platform/window.hpp"
#include "lantern/render/render_target.hpp"
#include "lantern/render/swapchain.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lantern::test {

// "n validation messages:\n  ..." for a failure message.
std::string describe_validation(const gpu::Device& device);

class RenderTest : public ::testing::Test {
  protected:
    void SetUp() override;
    void TearDown() override;
    gpu::Device& device() { return *device_; }

  private:
    gpu::Device* device_ = nullptr;
};

class WindowedTest : public ::testing::Test {
  protected:
    // Opens a window of `size` with a Device, surface and Swapchain (vsync as given). False
    // when the test was skipped (no Xvfb, X tools or device) or failed: return at once.
    bool open(platform::Extent size, bool vsync = true);
    void TearDown() override;

    gpu::Device& device() { return *device_; }
    platform::Window& window() { return *window_; }
    render::Swapchain& swapchain() { return *swapchain_; }

  private:
    void open_or_skip(platform::Extent size, bool vsync);

  protected:
    // Destroyed in reverse: the swapchain (and its surface), the device, the window.
    std::optional<platform::Window> window_;
    std::unique_ptr<gpu::Device> device_;
    std::optional<render::Swapchain> swapchain_;
};

// Pixels of an Rgba8Image as 0xRRGGBB (alpha dropped), for comparisons with X captures.
std::uint32_t rgb_at(const render::Rgba8Image& image, std::uint32_t x, std::uint32_t y);

} // namespace lantern::test
