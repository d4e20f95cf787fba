// Keyboard and mouse state of one window, frame by frame.
//
// InputState holds what the game asks each frame: which keys and buttons are down, which
// went down or up since the previous Window::poll() (so a tap shorter than a frame is still
// seen as pressed and released), where the mouse is, how far it moved and scrolled. The
// Window feeds it from GLFW's callbacks during poll(); tests and input replays may feed it
// through the same *_event functions.
//
// Units: mouse positions are framebuffer pixels of the window, origin at the top-left
// corner, x to the right, y down (on X11 these equal window coordinates; on scaled
// displays GLFW's screen coordinates are converted). Scroll is in wheel steps, y > 0 away
// from the user.
//
// Threads: the main thread (GLFW's rule), like the Window.
#pragma once

#include <glm/vec2.hpp>

#include <bitset>
#include <cstdint>
#include <optional>
#include <string_view>

namespace lantern::platform {

// Physical keys, named after the US layout, with GLFW's key codes as values.
enum class Key : std::uint16_t {
    space = 32,
    apostrophe = 39,
    comma = 44,
    minus = 45,
    period = 46,
    slash = 47,
    digit_0 = 48,
    digit_1 = 49,
    digit_2 = 50,
    digit_3 = 51,
    digit_4 = 52,
    digit_5 = 53,
    digit_6 = 54,
    digit_7 = 55,
    digit_8 = 56,
    digit_9 = 57,
    semicolon = 59,
    equal = 61,
    a = 65,
    b = 66,
    c = 67,
    d = 68,
    e = 69,
    f = 70,
    g = 71,
    h = 72,
    i = 73,
    j = 74,
    k = 75,
    l = 76,
    m = 77,
    n = 78,
    o = 79,
    p = 80,
    q = 81,
    r = 82,
    s = 83,
    t = 84,
    u = 85,
    v = 86,
    w = 87,
    x = 88,
    y = 89,
    z = 90,
    left_bracket = 91,
    backslash = 92,
    right_bracket = 93,
    grave_accent = 96,
    world_1 = 161,
    world_2 = 162,
    escape = 256,
    enter = 257,
    tab = 258,
    backspace = 259,
    insert = 260,
    del = 261,
    right = 262,
    left = 263,
    down = 264,
    up = 265,
    page_up = 266,
    page_down = 267,
    home = 268,
    end = 269,
    caps_lock = 280,
    scroll_lock = 281,
    num_lock = 282,
    print_screen = 283,
    pause = 284,
    f1 = 290,
    f2 = 291,
    f3 = 292,
    f4 = 293,
    f5 = 294,
    f6 = 295,
    f7 = 296,
    f8 = 297,
    f9 = 298,
    f10 = 299,
    f11 = 300,
    f12 = 301,
    f13 = 302,
    f14 = 303,
    f15 = 304,
    f16 = 305,
    f17 = 306,
    f18 = 307,
    f19 = 308,
    f20 = 309,
    f21 = 310,
    f22 = 311,
    f23 = 312,
    f24 = 313,
    f25 = 314,
    kp_0 = 320,
    kp_1 = 321,
    kp_2 = 322,
    kp_3 = 323,
    kp_4 = 324,
    kp_5 = 325,
    kp_6 = 326,
    kp_7 = 327,
    kp_8 = 328,
    kp_9 = 329,
    kp_decimal = 330,
    kp_divide = 331,
    kp_multiply = 332,
    kp_subtract = 333,
    kp_add = 334,
    kp_enter = 335,
    kp_equal = 336,
    left_shift = 340,
    left_control = 341,
    left_alt = 342,
    left_super = 343,
    right_shift = 344,
    right_control = 345,
    right_alt = 346,
    right_super = 347,
    menu = 348,
};

// A key's name in settings files and menus: "a", "7", "space", "left_shift", "f5", "kp_0"
// (the enumerator's name; digits are "0"-"9"). Every Key above has one; any other value
// gives "". key_by_name is its inverse (exact, lower case).
std::string_view key_name(Key key);
std::optional<Key> key_by_name(std::string_view name);

// GLFW's button numbers.
enum class MouseButton : std::uint8_t {
    left = 0,
    right = 1,
    middle = 2,
    button_4,
    button_5,
    button_6,
    button_7,
    button_8,
};

class InputState {
  public:
    static constexpr std::size_t key_count = 349;  // GLFW_KEY_LAST + 1
    static constexpr std::size_t button_count = 8; // GLFW_MOUSE_BUTTON_LAST + 1

    // Held down now.
    bool down(Key key) const { return keys_down_[index(key)]; }
    // Went down since the previous frame (even if already released again).
    bool pressed(Key key) const { return keys_pressed_[index(key)]; }
    // Went down since the previous frame while a Control key was held at that moment (a
    // shortcut: Ctrl+S tapped within one slow frame, Control already up again at its end,
    // still counts).
    bool pressed_with_control(Key key) const { return keys_pressed_with_control_[index(key)]; }
    // Went up since the previous frame.
    bool released(Key key) const { return keys_released_[index(key)]; }
    bool down(MouseButton button) const { return buttons_down_[index(button)]; }
    bool pressed(MouseButton button) const { return buttons_pressed_[index(button)]; }
    bool released(MouseButton button) const { return buttons_released_[index(button)]; }

    glm::vec2 mouse_position() const { return mouse_; }
    glm::vec2 mouse_delta() const { return mouse_ - frame_start_mouse_; } // this frame
    glm::vec2 scroll() const { return scroll_; }                          // this frame

    // --- Feeding (the Window during poll(); tests; replays) ---------------------------------
    // Starts a frame: clears the pressed/released edges, the scroll and the mouse delta.
    void begin_frame();
    void key_event(Key key, bool is_down);
    void button_event(MouseButton button, bool is_down);
    void cursor_event(glm::vec2 position);
    void scroll_event(glm::vec2 steps);
    // Releases every key and button held (focus lost: their release events go elsewhere).
    void release_all();

  private:
    static std::size_t index(Key key) { return static_cast<std::size_t>(key); }
    static std::size_t index(MouseButton button) { return static_cast<std::size_t>(button); }

    std::bitset<key_count> keys_down_, keys_pressed_, keys_released_, keys_pressed_with_control_;
    std::bitset<button_count> buttons_down_, buttons_pressed_, buttons_released_;
    glm::vec2 mouse_{0.0f};
    glm::vec2 frame_start_mouse_{0.0f};
    glm::vec2 scroll_{0.0f};
};

} // namespace lantern::platform
