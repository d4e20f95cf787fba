// The game application's private parts, shared by its files (game/src/app/):
//   app.cpp         start-up: the device, the renderers, sessions (a world, its GI frame and systems)
//   frame.cpp       the per-frame systems the application adds: input and render
//   loops.cpp       the window loop, the headless demo and its report
//   persistence.cpp saves, the status file and trace export
// Threads: everything here runs on the main thread (the systems are main-thread systems).
#pragma once

#include "lantern/game/app.hpp"

#include "app/draw_list.hpp"
#include "app/editor.hpp"
#include "app/hud.hpp"
#include "app/menu.hpp"
#include "app/sound.hpp"
#include "app/texel_world.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/file.hpp"
#include "lantern/core/json.hpp"
#include "lantern/core/log.hpp"
#include "lantern/core/machine.hpp"
#include "lantern/core/text.hpp"
#include "lantern/game/baking.hpp"
#include "lantern/game/demo.hpp"
#include "lantern/game/gameplay.hpp"
#include "lantern/game/save.hpp"
#include "lantern/game/settings.hpp"
#include "lantern/game/world_renderer.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/platform/window.hpp"
#include "lantern/profile/profiler.hpp"
#include "lantern/render/render.hpp"
#include "lantern/scene/loader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>


namespace lantern::game::app {


inline constexpr int warm_up_frames = 30; // left out of the headless percentiles (pipelines, first loads)
// Memory is compared from this frame on (or from half the run, if shorter): by then the demo has
// walked through its first chunks and every pipeline and GI texture exists.
inline constexpr int memory_warm_up_frames = 300;

// The headless demo's memory at one frame: the process's resident set and the device memory
// Lantern holds (gpu::Device::memory_allocated).
struct MemorySample {
    int frame = 0;
    std::uint64_t resident_bytes = 0;
    std::uint64_t device_bytes = 0;
};

// The draw list as a world resource (written by draw_list, read by render).
struct DrawListResource {
    DrawList list;
    DrawContext context;
    std::vector<texel::TexelLight> texel_lights; // gather_texel_lights (the suns are added in record_world)
};

struct Session {
    ecs::World world;
    GameWorld info;
    std::unique_ptr<WorldBaker> baker; // nullptr with --no-bake
    std::unique_ptr<systems::GiFrame> frame;
    std::optional<DemoScript> demo;
    ecs::ScheduleInfo schedule; // the frame's schedule, described once (the HUD's Schedule panel)
    ~Session() {
        frame.reset(); // the GI frame (and its jobs) before the world it uses
        baker.reset();
    }
};

// Where the player stands (x, z); the origin without a player.
glm::vec2 player_xz(ecs::World& w);

inline jobs::JobSystem::Config job_config(const GameOptions& o) {
    jobs::JobSystem::Config c;
    if (o.workers >= 0) c.worker_threads = o.workers;
    return c;
}



class Game {
  public:
    Game(const GameOptions& options, std::vector<GameExtension> extensions)
        : options_(options), extensions_(std::move(extensions)), jobs_(job_config(options)) {
        art_.posterize = options.posterize;
        art_.dither = options.dither;
        gi_view_ = options.gi_view;
    }
    ~Game() {
        if (device_) device_->wait_idle();
        session_.reset();
        overlay_.reset();
        swapchain_.reset();
        timer_.reset();
        texel_world_.reset();
        sound_.reset();
        world_renderer_.reset();
        gi_renderer_.reset();
        device_.reset();
        window_.reset();
    }

    int run();

  private:
    Result<void> init(bool windowed);
    Result<std::unique_ptr<Session>> make_session(const WorldSpec& spec, const SaveState* save,
                                                  const scene::Scene* scene = nullptr);
    // --watch: notices a change of the scene file (once a frame, by its FileStamp) and reads
    // it; a good scene waits in pending_scene_, a malformed one is reported and counted.
    void poll_watch();
    // --watch with --tables: a changed tables file is read and applied to the world in place;
    // a malformed one is reported and counted, the last good tables staying.
    void poll_tables();
    // Replaces the session with one built from pending_scene_, the player where it stood.
    Result<void> reload_scene();
    // The scene editor (F3): opens it on the scene file (scene worlds), or closes it.
    void toggle_editor(Session& s);
    // An edit into the running world, between frames (systems queue it: the world's
    // components are not theirs to write): an entry changed in place updates its entity;
    // entries added or removed rebuild the world from the editor's scene.
    void apply_edit(const EditResult& r);
    void apply_pending_edits(Session& s);
    void apply_edit_now(Session& s, const EditResult& r);
    // Writes the editor's edits to the scene file (false when it failed: said in message_).
    bool save_scene_edits();
    // The editor's entries as rings over the world (the selection brighter), in the overlay.
    void draw_editor_markers();
    void add_systems(ecs::Schedule& schedule, Session& session);
    void input_system(Session& s);
    void render_system(Session& s);
    // The pixel-art size that fills the window (GameOptions::internal_fixed off): sets
    // internal_, true when it changed. follow_window_size also resizes the world renderer's
    // target and the camera's aspect; it runs between frames.
    bool fit_internal_to_window();
    void follow_window_size();
    void record_world(gpu::CommandList& cmd, Session& s);
    void collect_raster_timings();
    // Saves to `path` ("slot 1", "autosave 2" in messages); false when it failed (said in
    // message_). `autosave`: the player's own saves keep their baseline (what the quit
    // question compares with).
    bool save(Session& s, const std::string& path, const std::string& name, bool autosave = false);
    // Something changed since the last save or load (edits, or the player walked a tile).
    bool unsaved(Session& s) const;
    // What "unsaved" compares with: the world as it is now (after a save, a load, a start).
    void mark_saved(Session& s, bool autosave);
    // Counts play time; writes the next autosave slot when due and something changed.
    void tick_autosave(Session& s);
    // The settings file's values into the running game (vsync, art; `gi`: the GI preset
    // too), the command line's own options winning. The pixel scale is read where the
    // target is fitted to the window.
    void apply_settings(Session* s, bool gi);
    // The GI settings of a session of `info`'s world: the world's own (a scene's, or the
    // game's defaults), the command line's --set over them, and in a window the menu's GI
    // preset (--set still over it). An error only for a --set a scene's settings refuse.
    Result<scene::GiSettings> session_gi(const GameWorld& info) const;
    void write_settings_file();
    std::vector<SlotView> slot_views(bool autosaves) const;
    void quit_or_ask(Session& s);
    void export_trace();
    void write_status(Session& s);
    int run_window();
    int run_headless();
    Result<void> write_headless_report(const std::vector<double>& frame_ms, const std::vector<bool>& walking,
                                       const std::vector<std::string>& screenshots,
                                       const std::vector<MemorySample>& memory, double seconds);

    // Checks a save's extension data before the running world is dropped for it (the load
    // hooks on a scratch world holding what their setup made).
    Result<void> check_extension_data(const SaveState& state) const;

    GameOptions options_;
    std::vector<GameExtension> extensions_;
    jobs::JobSystem jobs_;
    std::optional<platform::Window> window_;
    std::unique_ptr<gpu::Device> device_;
    std::optional<render::Swapchain> swapchain_;
    std::optional<render::ImGuiOverlay> overlay_;
    std::optional<render::PassTimer> timer_;
    std::unique_ptr<gi::vk::Renderer> gi_renderer_;
    std::unique_ptr<WorldRenderer> world_renderer_;
    std::unique_ptr<TexelWorld> texel_world_; // nullptr with --no-texel-lighting
    std::unique_ptr<GameSound> sound_;        // nullptr headless, with --no-sound, or without an audio device
    std::vector<texel::TexelLight> texel_lights_; // this frame's (reused)
    std::unique_ptr<Session> session_;
    std::uint32_t raster_lane_ = 0;
    ArtSettings art_;
    BounceStyle world_bounce_, character_bounce_; // the settings' knobs; the HUD edits them live
    GiDebugView gi_view_ = GiDebugView::lit; // the HUD's GI views
    Hud hud_;
    render::PresentRect present_rect_;
    glm::ivec2 internal_ = options_.internal; // the world renderer's target size now
    std::int64_t last_frame_ns_ = 0;
    double last_mine_time_ = -1.0;
    int selected_item_ = 1; // torch
    int headless_frame_ = 0;
    std::uint64_t window_frames_ = 0; // windowed frames stepped (--status-file)
    std::uint64_t hidden_waits_ = 0;  // waits for events while minimised or unmapped (--status-file)
    int saves_done_ = 0;              // successful saves (--status-file), autosaves included
    int autosaves_done_ = 0;          // of those, autosaves
    int save_slot_requested_ = 0;     // F5, the HUD or the menu: saved between frames, outside the systems
    bool quit_after_save_ = false;    // the quit question's "save and quit"
    PauseMenu menu_;
    PlayerSettings settings_;         // the settings file's (the menu edits them)
    bool settings_dirty_ = false;     // changed in the menu, not yet written
    int settings_writes_ = 0;         // (--status-file)
    std::uint64_t saved_edits_ = 0, autosaved_edits_ = 0;   // WorldEdits at the last save / any save
    glm::vec2 saved_player_{0.0f}, autosaved_player_{0.0f}; // the player there
    double play_since_autosave_ = 0.0; // seconds of play
    int next_autosave_ = 0;           // 0: ask the files (next_autosave_slot)
    bool status_failed_ = false;      // the status file could not be written (said once)
    bool quit_ = false;
    std::optional<SaveState> pending_load_;
    FilesWatch watched_;                        // --watch: the scene file and the files it reads
    GameTables tables_ = default_tables();      // --tables: the last good ones
    FilesWatch tables_watch_;                   // --watch: the --tables file
    std::optional<scene::Scene> pending_scene_; // --watch: checked, applied between frames
    std::int64_t change_seen_ns_ = 0;           // when the pending change was noticed
    bool pending_from_editor_ = false;          // pending_scene_ is the editor's (not a file change)
    SceneEditor editor_;                        // F3 in a scene world
    int editor_rebuilds_ = 0;                   // worlds rebuilt for the editor's edits (--status-file)
    std::optional<glm::vec2> cursor_world_;     // the ground point under the cursor (windowed)
    std::optional<scene::PerspectiveCamera> input_camera_; // the camera the input system saw (the markers)
    std::vector<EditResult> pending_edits_;     // applied between frames
    int reloads_ = 0, reload_errors_ = 0;       // --watch (--status-file reports them)
    std::string message_;
    std::uint64_t raster_serials_[2] = {0, 0};
    // The automatic GI quality (--min-fps): on while the GI is the game's own (the settings'
    // `world` preset, no --set or --quality, not a scene's) and the player has not picked a
    // preset; the frames measured since the last start or change.
    bool auto_quality_ = false;
    std::int64_t rate_last_ns_ = 0;
    int rate_skipped_ = 0;
    std::vector<double> rate_frames_;
    void watch_frame_rate(Session& s);
};

} // namespace lantern::game::app
