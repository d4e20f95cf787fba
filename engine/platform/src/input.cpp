// InputState: per-frame edges over held keys and buttons.
#include "lantern/platform/input.hpp"

namespace lantern::platform {

void InputState::begin_frame() {
    keys_pressed_.reset();
    keys_released_.reset();
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
