// InputState: per-frame edges over held keys and buttons.
#include "lantern/platform/input.hpp"

namespace lantern::platform {
namespace {

struct KeyName {
    Key key;
    std::string_view name;
};

// Every Key, in the enumeration's order.
constexpr KeyName key_names[] = {
    {Key::space, "space"},
    {Key::apostrophe, "apostrophe"},
    {Key::comma, "comma"},
    {Key::minus, "minus"},
    {Key::period, "period"},
    {Key::slash, "slash"},
    {Key::digit_0, "0"},
    {Key::digit_1, "1"},
    {Key::digit_2, "2"},
    {Key::digit_3, "3"},
    {Key::digit_4, "4"},
    {Key::digit_5, "5"},
    {Key::digit_6, "6"},
    {Key::digit_7, "7"},
    {Key::digit_8, "8"},
    {Key::digit_9, "9"},
    {Key::semicolon, "semicolon"},
    {Key::equal, "equal"},
    {Key::a, "a"},
    {Key::b, "b"},
    {Key::c, "c"},
    {Key::d, "d"},
    {Key::e, "e"},
    {Key::f, "f"},
    {Key::g, "g"},
    {Key::h, "h"},
    {Key::i, "i"},
    {Key::j, "j"},
    {Key::k, "k"},
    {Key::l, "l"},
    {Key::m, "m"},
    {Key::n, "n"},
    {Key::o, "o"},
    {Key::p, "p"},
    {Key::q, "q"},
    {Key::r, "r"},
    {Key::s, "s"},
    {Key::t, "t"},
    {Key::u, "u"},
    {Key::v, "v"},
    {Key::w, "w"},
    {Key::x, "x"},
    {Key::y, "y"},
    {Key::z, "z"},
    {Key::left_bracket, "left_bracket"},
    {Key::backslash, "backslash"},
    {Key::right_bracket, "right_bracket"},
    {Key::grave_accent, "grave_accent"},
    {Key::world_1, "world_1"},
    {Key::world_2, "world_2"},
    {Key::escape, "escape"},
    {Key::enter, "enter"},
    {Key::tab, "tab"},
    {Key::backspace, "backspace"},
    {Key::insert, "insert"},
    {Key::del, "delete"},
    {Key::right, "right"},
    {Key::left, "left"},
    {Key::down, "down"},
    {Key::up, "up"},
    {Key::page_up, "page_up"},
    {Key::page_down, "page_down"},
    {Key::home, "home"},
    {Key::end, "end"},
    {Key::caps_lock, "caps_lock"},
    {Key::scroll_lock, "scroll_lock"},
    {Key::num_lock, "num_lock"},
    {Key::print_screen, "print_screen"},
    {Key::pause, "pause"},
    {Key::f1, "f1"},
    {Key::f2, "f2"},
    {Key::f3, "f3"},
    {Key::f4, "f4"},
    {Key::f5, "f5"},
    {Key::f6, "f6"},
    {Key::f7, "f7"},
    {Key::f8, "f8"},
    {Key::f9, "f9"},
    {Key::f10, "f10"},
    {Key::f11, "f11"},
    {Key::f12, "f12"},
    {Key::f13, "f13"},
    {Key::f14, "f14"},
    {Key::f15, "f15"},
    {Key::f16, "f16"},
    {Key::f17, "f17"},
    {Key::f18, "f18"},
    {Key::f19, "f19"},
    {Key::f20, "f20"},
    {Key::f21, "f21"},
    {Key::f22, "f22"},
    {Key::f23, "f23"},
    {Key::f24, "f24"},
    {Key::f25, "f25"},
    {Key::kp_0, "kp_0"},
    {Key::kp_1, "kp_1"},
    {Key::kp_2, "kp_2"},
    {Key::kp_3, "kp_3"},
    {Key::kp_4, "kp_4"},
    {Key::kp_5, "kp_5"},
    {Key::kp_6, "kp_6"},
    {Key::kp_7, "kp_7"},
    {Key::kp_8, "kp_8"},
    {Key::kp_9, "kp_9"},
    {Key::kp_decimal, "kp_decimal"},
    {Key::kp_divide, "kp_divide"},
    {Key::kp_multiply, "kp_multiply"},
    {Key::kp_subtract, "kp_subtract"},
    {Key::kp_add, "kp_add"},
    {Key::kp_enter, "kp_enter"},
    {Key::kp_equal, "kp_equal"},
    {Key::left_shift, "left_shift"},
    {Key::left_control, "left_control"},
    {Key::left_alt, "left_alt"},
    {Key::left_super, "left_super"},
    {Key::right_shift, "right_shift"},
    {Key::right_control, "right_control"},
    {Key::right_alt, "right_alt"},
    {Key::right_super, "right_super"},
    {Key::menu, "menu"},
};

} // namespace

std::string_view key_name(Key key) {
    for (const KeyName& k : key_names)
        if (k.key == key) return k.name;
    return {};
}

std::optional<Key> key_by_name(std::string_view name) {
    for (const KeyName& k : key_names)
        if (k.name == name) return k.key;
    return std::nullopt;
}

void InputState::begin_frame() {
    keys_pressed_.reset();
    keys_released_.reset();
    keys_pressed_with_control_.reset();
    buttons_pressed_.reset();
    buttons_released_.reset();
    frame_start_mouse_ = mouse_;
    scroll_ = glm::vec2(0.0f);
}

void InputState::key_event(Key key, bool is_down) {
    const std::size_t i = index(key);
    if (is_down == keys_down_[i]) return; // repeats and duplicate releases carry no edge
    keys_down_[i] = is_down;
    (is_down ? keys_pressed_ : keys_released_).set(i);
    if (is_down && (keys_down_[index(Key::left_control)] || keys_down_[index(Key::right_control)]))
        keys_pressed_with_control_.set(i);
}

void InputState::button_event(MouseButton button, bool is_down) {
    const std::size_t i = index(button);
    if (is_down == buttons_down_[i]) return;
    buttons_down_[i] = is_down;
    (is_down ? buttons_pressed_ : buttons_released_).set(i);
}

void InputState::cursor_event(glm::vec2 position) {
    mouse_ = position;
}

void InputState::scroll_event(glm::vec2 steps) {
    scroll_ += steps;
}

void InputState::release_all() {
    keys_released_ |= keys_down_;
    keys_down_.reset();
    buttons_released_ |= buttons_down_;
    buttons_down_.reset();
}

} // namespace lantern::platform
