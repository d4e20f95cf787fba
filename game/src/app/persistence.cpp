// What the game writes besides frames: saves (between frames), the --status-file line, the
// Chrome trace.
#include "app/game.hpp"

#include "lantern/core/json_writer.hpp"

namespace lantern::game::app {

void Game::save(Session& s) {
    SaveState state = capture_save(s.world, s.frame->streaming(), s.info.spec);
    state.extensions = capture_extensions(extensions_, s.world);
    if (auto ok = write_save(options_.save_file, state); !ok) {
        message_ = "save failed: " + ok.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return;
    }
    ++saves_done_;
    message_ = "saved to " + options_.save_file + " (" + std::to_string(state.entities.size()) + " lights and props, " +
               std::to_string(state.edits.size()) + " edited chunks)";
    LANTERN_LOG_INFO("%s", message_.c_str());
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
    glm::vec2 player(0.0f);
    s.world.view<Player, Transform>().each([&](const Player&, const Transform& t) { player = {t.position.x, t.position.z}; });
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
