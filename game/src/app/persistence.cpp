// What the game writes besides frames: saves (between frames), the --status-file line, the
// Chrome trace.
#include "app/game.hpp"

#include "lantern/core/json_writer.hpp"

#include <ctime>

namespace lantern::game::app {

glm::vec2 player_xz(ecs::World& w) {
    glm::vec2 player(0.0f);
    w.view<Player, Transform>().each([&](const Player&, const Transform& t) { player = {t.position.x, t.position.z}; });
    return player;
}

namespace {

std::uint64_t edits_of(ecs::World& w) {
    return w.has_resource<WorldEdits>() ? w.resource<WorldEdits>().count : 0;
}

// A walk of more than a tile counts as progress worth saving.
constexpr float moved_tiles = 1.0f;

} // namespace

bool Game::save(Session& s, const std::string& path, const std::string& name, bool autosave) {
    SaveState state = capture_save(s.world, s.frame->streaming(), s.info.spec);
    state.extensions = capture_extensions(extensions_, s.world);
    if (auto ok = write_save(path, state); !ok) {
        message_ = name + ": save failed: " + ok.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return false;
    }
    ++saves_done_;
    if (autosave) ++autosaves_done_;
    mark_saved(s, autosave);
    message_ = (autosave ? "autosaved to " : "saved to ") + path + " (" + name + ": " +
               std::to_string(state.entities.size()) + " lights and props, " + std::to_string(state.edits.size()) +
               " edited chunks)";
    LANTERN_LOG_INFO("%s", message_.c_str());
    return true;
}

bool Game::unsaved(Session& s) const {
    return edits_of(s.world) != saved_edits_ || glm::distance(player_xz(s.world), saved_player_) > moved_tiles;
}

void Game::mark_saved(Session& s, bool autosave) {
    autosaved_edits_ = edits_of(s.world);
    autosaved_player_ = player_xz(s.world);
    play_since_autosave_ = 0.0;
    if (autosave) return;
    saved_edits_ = autosaved_edits_;
    saved_player_ = autosaved_player_;
}

void Game::tick_autosave(Session& s) {
    const int every = options_.autosave_seconds >= 0 ? options_.autosave_seconds : settings_.autosave_seconds;
    if (every <= 0 || menu_.is_open()) return;
    play_since_autosave_ += double(s.world.resource<GameClock>().dt);
    if (play_since_autosave_ < double(every)) return;
    play_since_autosave_ = 0.0;
    const bool changed = edits_of(s.world) != autosaved_edits_ ||
                         glm::distance(player_xz(s.world), autosaved_player_) > moved_tiles;
    if (!changed) return; // nothing new: the last save holds it
    if (next_autosave_ == 0) next_autosave_ = next_autosave_slot(options_.save_file);
    const int slot = next_autosave_;
    next_autosave_ = slot % autosave_slot_count + 1;
    save(s, autosave_slot_path(options_.save_file, slot), "autosave " + std::to_string(slot), true);
}

void Game::write_settings_file() {
    settings_dirty_ = false;
    if (auto ok = write_settings(settings_path(options_), settings_); !ok) {
        message_ = "settings not saved: " + ok.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return;
    }
    ++settings_writes_;
}

std::vector<SlotView> Game::slot_views(bool autosaves) const {
    std::vector<SlotView> out;
    const auto add = [&](std::string name, std::string path) {
        SlotView v;
        v.name = std::move(name);
        v.path = std::move(path);
        if (const auto stamp = file_stamp(v.path)) {
            v.exists = true;
            const std::time_t t = std::time_t(stamp->modified_ns / 1000000000);
            std::tm local{};
            localtime_r(&t, &local);
            char when[32];
            std::strftime(when, sizeof(when), "%Y-%m-%d %H:%M:%S", &local);
            v.when = when;
        }
        out.push_back(std::move(v));
    };
    for (int k = 1; k <= save_slot_count; ++k) add("slot " + std::to_string(k), save_slot_path(options_.save_file, k));
    if (autosaves)
        for (int k = 1; k <= autosave_slot_count; ++k)
            add("autosave " + std::to_string(k), autosave_slot_path(options_.save_file, k));
    return out;
}

Result<void> Game::check_extension_data(const SaveState& state) const {
    ecs::World scratch;
    for (const GameExtension& e : extensions_)
        if (e.setup) e.setup(scratch);
    return load_extensions(extensions_, state.extensions, scratch, state.file);
}

// One JSON line, replaced atomically after each frame (windowed or headless): what a script driving the game
// through real input waits on (the frame that saw its input, where the player is) instead of
// sleeping for a guessed time.
void Game::write_status(Session& s) {
    const glm::vec2 player = player_xz(s.world);
    json::Writer w;
    w.begin_object(json::Layout::one_line).field("frame", window_ ? window_frames_ : std::uint64_t(headless_frame_ + 1));
    w.key("player").begin_array().value(double(player.x), 4).value(double(player.y), 4).end();
    if (window_) {
        const platform::InputState& in = window_->input();
        w.key("mouse").begin_array().value(double(in.mouse_position().x), 1).value(double(in.mouse_position().y), 1).end();
        w.key("buttons").begin_array().value(int(in.down(platform::MouseButton::left)));
        w.value(int(in.down(platform::MouseButton::right))).end();
    }
    w.field("item", selected_item_ + 1).field("saves", saves_done_);
    int lights = 0; // the world's lights besides the player's own (what a reload changed)
    s.world.view<PointLight>().each([&](ecs::Entity e, const PointLight&) { lights += s.world.try_get<Player>(e) ? 0 : 1; });
    s.world.view<EmissiveLight>().each([&](const EmissiveLight&) { ++lights; });
    w.field("lights", lights).field("reloads", reloads_).field("reload_errors", reload_errors_);
    w.field("hidden_waits", hidden_waits_);
    if (s.world.has_resource<Inventory>()) {
        w.key("inventory").begin_array(); // wall, torch, crystal, lamp post, tree
        for (int count : s.world.resource<Inventory>().counts) w.value(count);
        w.end();
    }
    if (window_) {
        // The pixel-art target and where it lands in the window (the last presented frame).
        w.key("internal").begin_array().value(internal_.x).value(internal_.y).end();
        w.key("present").begin_array().value(present_rect_.x).value(present_rect_.y);
        w.value(present_rect_.width).value(present_rect_.height).value(present_rect_.scale).end();
        // The pause menu: its page, what it would ask, and its buttons this frame (window
        // pixels: x, y, width, height), so a script clicks them as a player would.
        w.field("menu", menu_page_names[int(menu_.page())]).field("unsaved", unsaved(s));
        w.field("autosaves", autosaves_done_).field("settings_writes", settings_writes_);
        w.field("vsync", swapchain_ && swapchain_->vsync());
        w.field("sound", sound_ ? sound_->mixer().device_name() : std::string("off"));
        w.field("sounds_played", sound_ ? sound_->sounds_played() : std::uint64_t(0));
        w.field("gi_resolution", s.world.resource<systems::GiConfig>().settings.resolution);
        // The scene editor: whether it is open, its selection and where it stands, the file's
        // state, and how many entries each list has; the ground point under the cursor.
        w.key("editor").begin_object().field("open", editor_.is_open());
        w.field("selected", target_name(editor_.selected()));
        if (auto at = editor_.position_of(editor_.selected()))
            w.key("selected_at").begin_array().value(double(at->x), 4).value(double(at->y), 4).end();
        w.field("unsaved", editor_.unsaved()).field("saves", editor_.saves()).field("rebuilds", editor_rebuilds_);
        const scene::SceneLists& lists = editor_.lists();
        w.key("entries").begin_array().value(lists.point_lights.size()).value(lists.emissive_lights.size());
        w.value(lists.shadow_proxies.size()).end().end();
        if (cursor_world_)
            w.key("cursor_world").begin_array().value(double(cursor_world_->x), 4).value(double(cursor_world_->y), 4).end();
        // The menu's and the editor's buttons (labels are distinct: the editor's are not the menu's).
        w.key("buttons_drawn").begin_object(json::Layout::one_line);
        for (std::span<const MenuButton> list : {menu_.settled_buttons(), editor_.settled_buttons()})
            for (const MenuButton& b : list) {
                w.key(b.label).begin_array().value(double(b.x), 1).value(double(b.y), 1);
                w.value(double(b.width), 1).value(double(b.height), 1).end();
            }
        w.end();
    }
    w.end();
    if (auto ok = write_file_atomic(options_.status_file, w.take()); !ok && !status_failed_) {
        status_failed_ = true;
        LANTERN_LOG_ERROR("status file: %s", ok.error().message.c_str());
    }
}

void Game::export_trace() {
    const std::string path = (window_ ? std::string("lantern-trace.json") : options_.out_dir + "/trace.json");
    if (auto ok = profile::write_chrome_trace(path, std::uint32_t(hud_.graph_frames)); !ok) {
        message_ = "trace export failed: " + ok.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return;
    }
    message_ = "Chrome trace of the last " + std::to_string(hud_.graph_frames) + " frames written to " + path +
               " (open in chrome://tracing or ui.perfetto.dev)";
    LANTERN_LOG_INFO("%s", message_.c_str());
}


} // namespace lantern::game::app
