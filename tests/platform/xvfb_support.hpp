// Windowed tests without a desktop: a private Xvfb server, real X input through xdotool
// (XTEST: the server sees device events, exactly as from a user), and screen capture
// through xwd.
//
//   TEST(Window, Something) {
//       LANTERN_REQUIRE_XVFB();                        // GTEST_SKIP with the reason if missing
//       auto window = platform::Window::create({...});
//       test::x_key(test::x11_window(*window), "a", true);   // key down
//       ...
//       auto pixels = test::capture_window(test::x11_window(*window));
//   }
//
// The server is per test process (CTest runs every test in its own process): started on
// first use with `-screen 0 1280x720x24`, on a display number Xvfb picks itself
// (-displayfd, so parallel test processes never collide) and reports once it accepts
// connections. DISPLAY is set for this process and its children; the server is stopped at
// exit. Tests skip, reported as skipped with the reason, when Xvfb, xdotool or xwd is not
// installed (scripts/setup.sh installs them), never pass silently.
//
// There is no window manager: windows are not decorated and not moved, and keyboard focus
// is given explicitly (x_focus).
#pragma once

#include "common/test_support.hpp"
#include "lantern/core/result.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

struct GLFWwindow;

namespace lantern::platform {
class Window;
}

namespace lantern::test {

// The shared Xvfb server's display (":N"), started on first call; an error with the
// reason when it cannot run.
Result<std::string> xvfb_display();

// Empty when the X tools the tests use (xdotool, xwd) are on PATH, else which are missing.
std::string missing_x_tools();

// The X11 window id of a GLFW window.
std::uint64_t x11_window(const platform::Window& window);

// Polls `window` (Window::poll) until `done()` holds after a poll; false after `timeout`.
// X events arrive asynchronously: tests wait for the state they expect, with a deadline.
bool poll_until(platform::Window& window, const std::function<bool()>& done,
                std::chrono::milliseconds timeout = std::chrono::seconds(60));

// --- Input (xdotool; each call returns once the server processed it) ---------------------------
// Gives `window` the keyboard focus (XSetInputFocus: no window manager needed).
Result<void> x_focus(std::uint64_t window);
// Presses (down = true) or releases a key by X keysym name: "a", "Escape", "space", ...
Result<void> x_key(std::uint64_t window, const std::string& keysym, bool down);
// Moves the pointer to (x, y) pixels inside `window`.
Result<void> x_mouse_move(std::uint64_t window, int x, int y);
// Presses or releases X button `button` (1 left, 2 middle, 3 right, 4/5 wheel up/down).
Result<void> x_button(int button, bool down);

// --- Capture -----------------------------------------------------------------------------------
// 8-bit RGB pixels, rows top to bottom.
struct RgbImage {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::uint8_t> rgb;                            // width * height * 3
    std::uint32_t at(std::uint32_t x, std::uint32_t y) const; // 0xRRGGBB
};

// The window's current contents as the X server has them (xwd -id).
Result<RgbImage> capture_window(std::uint64_t window);

// Parses an XWD file (X Window Dump, what xwd writes): ZPixmap, TrueColor or DirectColor,
// 16, 24 or 32 bits per pixel, either byte order. Safe for untrusted input: every size is
// checked against the data, so a malformed or truncated file is an error, never a crash.
Result<RgbImage> parse_xwd(std::span<const std::uint8_t> bytes);

// Runs `argv` (argv[0] looked up on PATH), returns its standard output; an error with its
// exit status and standard error when it fails.
Result<std::string> run_tool(const std::vector<std::string>& argv);

} // namespace lantern::test

// Skips the current test (reported as skipped, with the reason) unless the shared Xvfb
// server runs and the X tools are installed.
#define LANTERN_REQUIRE_XVFB()                                                                     \
    do {                                                                                           \
        if (auto lantern_xvfb_ = ::lantern::test::xvfb_display(); !lantern_xvfb_)                  \
            LANTERN_SKIP_NO_GPU(lantern_xvfb_.error().message);                                         \
        if (auto lantern_missing_ = ::lantern::test::missing_x_tools(); !lantern_missing_.empty()) \
            LANTERN_SKIP_NO_GPU("missing X tools: " << lantern_missing_ << " (run scripts/setup.sh)");  \
    } while (false)
