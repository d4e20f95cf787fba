#include "app/menu.hpp"

#include <imgui.h>

#include <cstdio>

namespace lantern::game {
namespace {

constexpr float menu_width = 380.0f;
constexpr float row_height = 30.0f;

// A button across the menu (not GetContentRegionAvail: a new window's first frame has none).
float full_width() {
    return menu_width - 2.0f * ImGui::GetStyle().WindowPadding.x;
}

// A choice drawn as a highlighted button.
void push_chosen(bool chosen) {
    ImGui::PushStyleColor(ImGuiCol_Button, chosen ? ImVec4(0.85f, 0.6f, 0.2f, 0.9f) : ImGui::GetStyle().Colors[ImGuiCol_Button]);
}

} // namespace

void PauseMenu::back() {
    if (capture_ >= 0) {
        capture_ = -1;
        return;
    }
    switch (page_) {
    case MenuPage::closed: return;
    case MenuPage::main: page_ = MenuPage::closed; return;
    case MenuPage::keys: page_ = MenuPage::settings; return;
    case MenuPage::settings:
    case MenuPage::save:
    case MenuPage::load:
    case MenuPage::confirm_quit: page_ = MenuPage::main; return;
    }
}

bool PauseMenu::button(const char* label, float width) {
    const bool clicked = ImGui::Button(label, ImVec2(width > 0.0f ? width : full_width(), row_height));
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    buttons_.push_back({label, lo.x, lo.y, hi.x - lo.x, hi.y - lo.y});
    return clicked;
}

MenuActions PauseMenu::draw(const MenuInputs& in) {
    buttons_.clear();
    MenuActions out;
    frames_on_page_ = page_ == drawn_page_ ? frames_on_page_ + 1 : 1;
    drawn_page_ = page_;
    if (page_ == MenuPage::closed) return out;
    // A fixed place and width, the height fitting the page: a button stays where it was drawn
    // from one frame to the next (an auto-sized window settles over a frame or two).
    const ImGuiViewport* view = ImGui::GetMainViewport();
    // The key bindings (a row per action) start near the top, so the page fits a 540 px window.
    const float top = page_ == MenuPage::keys ? 0.02f : 0.18f;
    ImGui::SetNextWindowPos(ImVec2(view->WorkPos.x + view->WorkSize.x * 0.5f, view->WorkPos.y + view->WorkSize.y * top),
                            ImGuiCond_Always, ImVec2(0.5f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(menu_width, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.92f);
    constexpr ImGuiWindowFlags flags =
        ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings;
    const char* titles[] = {"", "Paused", "Settings", "Key bindings", "Save", "Load", "Quit?"};
    char title[64];
    std::snprintf(title, sizeof(title), "%s###pause_menu", titles[int(page_)]);
    ImGui::SetNextWindowFocus();
    if (ImGui::Begin(title, nullptr, flags)) {
        switch (page_) {
        case MenuPage::closed: break;
        case MenuPage::main: draw_main(in, out); break;
        case MenuPage::settings: draw_settings(in); break;
        case MenuPage::keys: draw_keys(in); break;
        case MenuPage::save: draw_slots(in, out, true); break;
        case MenuPage::load: draw_slots(in, out, false); break;
        case MenuPage::confirm_quit: draw_confirm(in, out); break;
        }
        if (!in.message.empty() && page_ != MenuPage::closed) {
            ImGui::Separator();
            ImGui::TextWrapped("%s", in.message.c_str());
        }
    }
    ImGui::End();
    return out;
}

void PauseMenu::draw_main(const MenuInputs& in, MenuActions& out) {
    const float w = full_width();
    if (button("Resume", w)) page_ = MenuPage::closed;
    if (button("Settings", w)) page_ = MenuPage::settings;
    if (button("Save", w)) page_ = MenuPage::save;
    if (button("Load", w)) page_ = MenuPage::load;
    if (button("Quit", w)) {
        if (in.unsaved) page_ = MenuPage::confirm_quit;
        else out.quit = true;
    }
    ImGui::TextDisabled(in.unsaved ? "unsaved changes since the last save" : "everything is saved");
}

void PauseMenu::draw_settings(const MenuInputs& in) {
    PlayerSettings& s = *in.settings;
    ImGui::TextUnformatted("GI quality");
    for (int p = 0; p < gi_preset_count; ++p) {
        if (p) ImGui::SameLine();
        push_chosen(int(s.gi_preset) == p);
        if (button(gi_preset_names[p], 80.0f)) s.gi_preset = GiPreset(p);
        ImGui::PopStyleColor();
    }
    ImGui::TextDisabled("world: the world's own; high: the seed's look (slow on lavapipe)");
    if (button(s.vsync ? "vsync: on" : "vsync: off", 160.0f)) s.vsync = !s.vsync;
    ImGui::SameLine();
    if (button(s.dither ? "dither: on" : "dither: off", 160.0f)) s.dither = !s.dither;
    char scale[48];
    if (s.pixel_scale == 0) std::snprintf(scale, sizeof(scale), "pixel scale: automatic");
    else std::snprintf(scale, sizeof(scale), "pixel scale: %dx", s.pixel_scale);
    if (button("-##pixel_scale", 30.0f) && s.pixel_scale > 0) --s.pixel_scale;
    ImGui::SameLine();
    if (button("+##pixel_scale", 30.0f) && s.pixel_scale < max_pixel_scale) ++s.pixel_scale;
    ImGui::SameLine();
    ImGui::TextUnformatted(scale);
    ImGui::TextUnformatted("palette");
    for (int p = 0; p < palette_count; ++p) {
        ImGui::SameLine();
        push_chosen(s.palette == p);
        char label[32];
        std::snprintf(label, sizeof(label), "%s##palette", palette_names[p]);
        if (button(label, 54.0f)) s.palette = p;
        ImGui::PopStyleColor();
    }
    int posterize = s.posterize;
    if (ImGui::SliderInt("posterize (0 off)", &posterize, 0, 32)) s.posterize = posterize == 1 ? 2 : posterize;
    ImGui::SliderInt("volume (%)", &s.volume, 0, 100);
    // Seed 002's bounce knobs: how much a colour reinforces itself, how much dark surfaces
    // take their neighbours' colour (world, then characters).
    ImGui::SliderFloat("bounce self (world)", &s.world_self, 0.0f, 1.0f);
    ImGui::SliderFloat("bounce bleed (world)", &s.world_bleed, 0.0f, 1.0f);
    ImGui::SliderFloat("bounce self (characters)", &s.character_self, 0.0f, 1.0f);
    ImGui::SliderFloat("bounce bleed (characters)", &s.character_bleed, 0.0f, 1.0f);
    int minutes = s.autosave_seconds / 60;
    if (ImGui::SliderInt("autosave (minutes, 0 off)", &minutes, 0, 30)) s.autosave_seconds = minutes * 60;
    const float w = full_width();
    if (button("Key bindings", w)) page_ = MenuPage::keys;
    if (button("Back##settings", w)) page_ = MenuPage::main;
}

void PauseMenu::draw_keys(const MenuInputs& in) {
    PlayerSettings& s = *in.settings;
    if (capture_ >= 0 && in.input) {
        // The next bindable key pressed takes the action (Escape cancels: back()).
        for (std::size_t k = 0; k < platform::InputState::key_count; ++k) {
            const auto key = platform::Key(k);
            if (bindable(key) && in.input->pressed(key)) {
                bind(s.keys, Action(capture_), key);
                capture_ = -1;
                break;
            }
        }
    }
    ImGui::TextDisabled("click an action, then press its new key (Escape cancels)");
    for (int a = 0; a < action_count; ++a) {
        char label[64];
        if (capture_ == a) std::snprintf(label, sizeof(label), "press a key...##%s", action_keys[a]);
        else
            std::snprintf(label, sizeof(label), "%s##%s", std::string(platform::key_name(s.keys[std::size_t(a)])).c_str(),
                          action_keys[a]);
        push_chosen(capture_ == a);
        if (button(label, 140.0f)) capture_ = a;
        ImGui::PopStyleColor();
        ImGui::SameLine();
        ImGui::TextUnformatted(action_labels[a]);
    }
    ImGui::TextDisabled("arrow keys walk too; 1-5 pick items; Escape opens this menu");
    const float w = full_width();
    if (button("Defaults##keys", w)) s.keys = default_key_bindings();
    if (button("Back##keys", w)) {
        capture_ = -1;
        page_ = MenuPage::settings;
    }
}

void PauseMenu::draw_slots(const MenuInputs& in, MenuActions& out, bool saving) {
    const std::vector<SlotView>& slots = saving ? in.save_slots : in.load_slots;
    for (const SlotView& slot : slots) {
        char label[96];
        std::snprintf(label, sizeof(label), "%s %s", saving ? "Save to" : "Load", slot.name.c_str());
        ImGui::BeginDisabled(!saving && !slot.exists);
        if (button(label, 170.0f)) {
            if (saving) out.save_slot = int(&slot - slots.data()) + 1;
            else out.load_path = slot.path;
        }
        ImGui::EndDisabled();
        ImGui::SameLine();
        ImGui::TextDisabled("%s", slot.exists ? slot.when.c_str() : "empty");
    }
    if (button(saving ? "Back##save" : "Back##load", full_width())) page_ = MenuPage::main;
}

void PauseMenu::draw_confirm(const MenuInputs& in, MenuActions& out) {
    ImGui::TextWrapped("There are unsaved changes since the last save. Quit anyway?");
    if (!in.unsaved_scene.empty())
        ImGui::TextWrapped("The scene editor's edits of %s are not saved either.", in.unsaved_scene.c_str());
    const float w = full_width();
    if (button(in.unsaved_scene.empty() ? "Save to slot 1 and quit" : "Save the scene and slot 1, and quit", w))
        out.save_and_quit = true;
    if (button("Quit without saving", w)) out.quit = true;
    if (button("Cancel", w)) page_ = MenuPage::main;
}

} // namespace lantern::game
