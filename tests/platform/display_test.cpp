// The display probe and window creation without a display: clear errors, never a crash.
#include "lantern/platform/window.hpp"

#include "gpu/gpu_test_support.hpp"
#include "platform/xvfb_support.hpp"

#include <gtest/gtest.h>

namespace lantern::platform {
namespace {

using test::ScopedEnv;

TEST(Display, UnavailableWithoutDisplayVariables) {
    ScopedEnv display("DISPLAY", nullptr);
    ScopedEnv wayland("WAYLAND_DISPLAY", nullptr);
    const DisplayProbe probe = display_available();
    EXPECT_FALSE(probe);
    EXPECT_EQ(probe.reason, "no DISPLAY or WAYLAND_DISPLAY set");
}

TEST(Display, UnreachableServerGivesGlfwsReason) {
    ScopedEnv display("DISPLAY", ":979"); // nothing listens there
    ScopedEnv wayland("WAYLAND_DISPLAY", nullptr);
    const DisplayProbe probe = display_available();
    EXPECT_FALSE(probe);
    EXPECT_NE(probe.reason.find("glfwInit failed"), std::string::npos) << probe.reason;
}

TEST(Display, WindowWithoutDisplayIsAnError) {
    ScopedEnv display("DISPLAY", nullptr);
    ScopedEnv wayland("WAYLAND_DISPLAY", nullptr);
    auto window = Window::create({.title = "no display"});
    ASSERT_FALSE(window);
    EXPECT_NE(window.error().message.find("cannot open a window"), std::string::npos)
        << window.error().message;
    EXPECT_NE(window.error().message.find("DISPLAY"), std::string::npos) << window.error().message;
}

TEST(Display, AvailableUnderXvfb) {
    LANTERN_REQUIRE_XVFB();
    const DisplayProbe probe = display_available();
    EXPECT_TRUE(probe) << probe.reason;
    EXPECT_TRUE(probe.reason.empty());
    // The probe left GLFW terminated: a window still opens afterwards.
    EXPECT_TRUE(Window::create({.title = "after probe", .width = 64, .height = 48}));
}

} // namespace
} // namespace lantern::platform
