// The pause menu (Escape; Dear ImGui): resume, settings (GI quality preset, vsync, pixel
// scale, art, autosave, key bindings), save to a slot, load a slot or an autosave, quit
// (asking first when something is unsaved). While it is open the world is paused.
// Threads: the main thread, inside an ImGui frame.
#pragma once

#include "lantern/game/settings.hpp"
#include "lantern/platform/input.hpp"

#include <span>
#include <string>
#include <vector>

namespace lantern::game {

enum class MenuPage : std::uint8_t { closed, main, settings, keys, save, load, confirm_quit };
inline constexpr const char* menu_page_names[] = {"closed", "main", "settings", "keys", "save", "load", "confirm_quit"};

// One save slot as the menu lists it.
struct SlotView {
    std::string name;  // "slot 1", "autosave 2"
    std::string path;
    bool exists = false;
    std::string when;  // local time of its last write ("2026-11-27 01:02:03"), "" when empty
};

struct MenuInputs {
    PlayerSettings* settings = nullptr;        // edited live
    const platform::InputState* input = nullptr; // a key binding waits for the next key
    bool unsaved = false;                      // changes since the last save or load
    std::string unsaved_scene;                 // the scene file the editor has unsaved edits of
    std::vector<SlotView> save_slots;          // the slots the player saves to
    std::vector<SlotView> load_slots;          // those and the autosaves
    std::string message;                       // the last action's result
};

struct MenuActions {
    bool quit = false;          // quit now (nothing unsaved, or confirmed)
    bool save_and_quit = false; // save to slot 1, then quit if that worked
    int save_slot = 0;          // 1..save_slot_count: save there
    std::string load_path;      // load this save
};

// A button the menu drew this frame, in window pixels (the --status-file lists them, so a
// script can click them through real mouse input).
struct MenuButton {
    std::string label;
    float x = 0, y = 0, width = 0, height = 0;
};

class PauseMenu {
  public:
    bool is_open() const { return page_ != MenuPage::closed; }
    MenuPage page() const { return page_; }
    bool capturing_key() const { return capture_ >= 0; }
    void open() { page_ = MenuPage::main; }
    void close() {
        page_ = MenuPage::closed;
        capture_ = -1;
    }
    // The quit question (a close request with something unsaved).
    void ask_quit() { page_ = MenuPage::confirm_quit; }
    // Escape: cancels a key capture, else goes back a page; from the main page it closes.
    void back();

    MenuActions draw(const MenuInputs& in);
    const std::vector<MenuButton>& buttons() const { return buttons_; }
    // The buttons once the page has been drawn twice (its layout settled), else none.
    std::span<const MenuButton> settled_buttons() const {
        return frames_on_page_ >= 2 ? std::span<const MenuButton>(buttons_) : std::span<const MenuButton>();
    }

  private:
    bool button(const char* label, float width = 0.0f);
    void draw_main(const MenuInputs& in, MenuActions& out);
    void draw_settings(const MenuInputs& in);
    void draw_keys(const MenuInputs& in);
    void draw_slots(const MenuInputs& in, MenuActions& out, bool saving);
    void draw_confirm(const MenuInputs& in, MenuActions& out);

    MenuPage page_ = MenuPage::closed;
    int capture_ = -1; // the action waiting for its new key
    std::vector<MenuButton> buttons_;
    MenuPage drawn_page_ = MenuPage::closed; // the page the last draw() drew
    int frames_on_page_ = 0;
};

} // namespace lantern::game
