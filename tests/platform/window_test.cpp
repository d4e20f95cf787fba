// Real GLFW windows under Xvfb: size, resize events, close requests, GLFW's reference
// counting, Vulkan surfaces, focus loss.
#include "lantern/platform/window.hpp"

#include "lantern/gpu/device.hpp"
#include "platform/xvfb_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

namespace lantern::platform {
namespace {

class WindowTest : public ::testing::Test {
  protected:
    void SetUp() override { LANTERN_REQUIRE_XVFB(); }

    static Window open(const char* title, std::uint32_t width = 320, std::uint32_t height = 200) {
        auto window = Window::create({.title = title, .width = width, .height = height});
        EXPECT_TRUE(window) << (window ? "" : window.error().message);
        return std::move(window).value();
    }
};

bool has_event(const Window& window, WindowEventType type) {
    return std::any_of(window.events().begin(), window.events().end(),
                       [&](const WindowEvent& e) { return e.type == type; });
}

TEST_F(WindowTest, OpensAtTheRequestedSize) {
    Window window = open("size", 320, 200);
    window.poll();
    EXPECT_EQ(window.framebuffer_size(), (Extent{320, 200}));
    EXPECT_EQ(window.window_size(), (Extent{320, 200}));
    EXPECT_FALSE(window.minimised());
    EXPECT_FALSE(window.should_close());
    EXPECT_NE(window.glfw_handle(), nullptr);
    EXPECT_NE(test::x11_window(window), 0u);
}

TEST_F(WindowTest, SetSizeReportsAResizedEvent) {
    Window window = open("resize", 320, 200);
    window.set_size({400, 240});
    Extent reported{};
    ASSERT_TRUE(test::poll_until(window,
                                 [&] {
                                     for (const WindowEvent& e : window.events()) {
                                         if (e.type == WindowEventType::resized) reported = e.size;
                                     }
                                     return reported == Extent{400, 240};
                                 }))
        << "last resize reported " << reported.width << "x" << reported.height;
    EXPECT_EQ(window.framebuffer_size(), (Extent{400, 240}));
    window.poll(); // events belong to one frame
    EXPECT_FALSE(has_event(window, WindowEventType::resized));
}

TEST_F(WindowTest, RequestCloseSetsShouldClose) {
    Window window = open("close");
    EXPECT_FALSE(window.should_close());
    window.request_close();
    EXPECT_TRUE(window.should_close());
}

TEST_F(WindowTest, WindowsShareGlfwUntilTheLastIsDestroyed) {
    std::optional<Window> first(open("first"));
    Window second = open("second");
    first.reset();
    second.poll(); // GLFW is still initialised
    EXPECT_EQ(second.framebuffer_size(), (Extent{320, 200}));
    Window moved = std::move(second);
    moved.poll();
    EXPECT_EQ(moved.framebuffer_size(), (Extent{320, 200}));
}

TEST_F(WindowTest, SurfaceNeedsTheWindowsInstanceExtensions) {
    Window window = open("surface");
    auto plain = gpu::Device::create({.validation = true});
    if (!plain) LANTERN_SKIP_NO_GPU(plain.error().message); // no Vulkan driver
    auto extensions = window.vulkan_instance_extensions();
    ASSERT_TRUE(extensions) << extensions.error().message;
    ASSERT_FALSE(extensions->empty());
    EXPECT_TRUE(std::any_of(extensions->begin(), extensions->end(),
                            [](const char* e) { return std::strcmp(e, "VK_KHR_surface") == 0; }));

    auto refused = window.create_surface(**plain);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("vulkan_instance_extensions"), std::string::npos)
        << refused.error().message;

    gpu::DeviceOptions options{.validation = true};
    options.instance_extensions = *extensions;
    auto device = gpu::Device::create(options);
    ASSERT_TRUE(device) << device.error().message;
    {
        auto surface = window.create_surface(**device);
        ASSERT_TRUE(surface) << surface.error().message;
        EXPECT_NE(surface->vk(), VK_NULL_HANDLE);
        Surface moved = std::move(*surface);
        EXPECT_TRUE(moved);
        EXPECT_FALSE(*surface);
    }
    EXPECT_EQ((*device)->validation_message_count(), 0u);
}

TEST_F(WindowTest, FocusLossReleasesHeldKeys) {
    Window first = open("focus first");
    const std::uint64_t first_id = test::x11_window(first);
    ASSERT_TRUE(test::x_key(first_id, "a", true));
    ASSERT_TRUE(test::poll_until(first, [&] { return first.input().down(Key::a); }));
    EXPECT_TRUE(first.focused());

    Window second = open("focus second");
    ASSERT_TRUE(test::x_focus(test::x11_window(second)));
    bool lost = false, released = false;
    ASSERT_TRUE(test::poll_until(first, [&] {
        lost = lost || has_event(first, WindowEventType::focus_lost);
        released = released || first.input().released(Key::a);
        return lost && released;
    }));
    EXPECT_FALSE(first.focused());
    EXPECT_FALSE(first.input().down(Key::a));
    ASSERT_TRUE(test::x_key(test::x11_window(second), "a", false)); // leave the server clean
}

} // namespace
} // namespace lantern::platform
