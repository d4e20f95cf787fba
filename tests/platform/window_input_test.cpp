// Real X input (xdotool through XTEST) reaching a GLFW window's InputState under Xvfb.
#include "lantern/platform/window.hpp"

#include "platform/xvfb_support.hpp"

#include <gtest/gtest.h>

namespace lantern::platform {
namespace {

class WindowInput : public ::testing::Test {
  protected:
    void SetUp() override {
        LANTERN_REQUIRE_XVFB();
        auto created = Window::create({.title = "input", .width = 320, .height = 200});
        ASSERT_TRUE(created) << created.error().message;
        window_.emplace(std::move(created).value());
        id_ = test::x11_window(*window_);
    }

    Window& window() { return *window_; }
    std::optional<Window> window_;
    std::uint64_t id_ = 0;
};

TEST_F(WindowInput, KeyPressAndReleaseReachTheInputState) {
    ASSERT_TRUE(test::x_key(id_, "d", true));
    ASSERT_TRUE(test::poll_until(window(), [&] { return window().input().pressed(Key::d); }));
    EXPECT_TRUE(window().input().down(Key::d));
    EXPECT_FALSE(window().input().down(Key::a));

    window().poll();
    EXPECT_TRUE(window().input().down(Key::d));
    EXPECT_FALSE(window().input().pressed(Key::d));

    ASSERT_TRUE(test::x_key(id_, "d", false));
    ASSERT_TRUE(test::poll_until(window(), [&] { return window().input().released(Key::d); }));
    EXPECT_FALSE(window().input().down(Key::d));
}

TEST_F(WindowInput, SpecialKeysMapToTheirKeys) {
    ASSERT_TRUE(test::x_key(id_, "Escape", true));
    ASSERT_TRUE(test::poll_until(window(), [&] { return window().input().pressed(Key::escape); }));
    ASSERT_TRUE(test::x_key(id_, "Escape", false));
    ASSERT_TRUE(test::x_key(id_, "Shift_L", true));
    ASSERT_TRUE(test::poll_until(window(), [&] { return window().input().down(Key::left_shift); }));
    ASSERT_TRUE(test::x_key(id_, "Shift_L", false));
    ASSERT_TRUE(
        test::poll_until(window(), [&] { return !window().input().down(Key::left_shift); }));
}

TEST_F(WindowInput, MouseMoveAndClickReachTheInputState) {
    ASSERT_TRUE(test::x_mouse_move(id_, 123, 45));
    ASSERT_TRUE(test::poll_until(
        window(), [&] { return window().input().mouse_position() == glm::vec2(123.0f, 45.0f); }))
        << "mouse at " << window().input().mouse_position().x << ", "
        << window().input().mouse_position().y;

    ASSERT_TRUE(test::x_button(1, true));
    ASSERT_TRUE(
        test::poll_until(window(), [&] { return window().input().pressed(MouseButton::left); }));
    EXPECT_TRUE(window().input().down(MouseButton::left));
    EXPECT_FALSE(window().input().down(MouseButton::right));
    ASSERT_TRUE(test::x_button(1, false));
    ASSERT_TRUE(
        test::poll_until(window(), [&] { return window().input().released(MouseButton::left); }));

    ASSERT_TRUE(test::x_button(3, true));
    ASSERT_TRUE(
        test::poll_until(window(), [&] { return window().input().down(MouseButton::right); }));
    ASSERT_TRUE(test::x_button(3, false));
    ASSERT_TRUE(
        test::poll_until(window(), [&] { return !window().input().down(MouseButton::right); }));
}

TEST_F(WindowInput, WheelScrollReachesTheInputState) {
    ASSERT_TRUE(test::x_mouse_move(id_, 50, 50));
    ASSERT_TRUE(test::x_button(4, true)); // wheel up: X buttons 4/5
    ASSERT_TRUE(test::x_button(4, false));
    ASSERT_TRUE(test::poll_until(window(), [&] { return window().input().scroll().y > 0.0f; }));
    EXPECT_EQ(window().input().scroll(), glm::vec2(0.0f, 1.0f));
    window().poll();
    EXPECT_EQ(window().input().scroll(), glm::vec2(0.0f));
}

} // namespace
} // namespace lantern::platform
