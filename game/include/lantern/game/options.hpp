// The game's command line (docs/game.md): which world, windowed or headless, GI and art
// settings, parsed by core's cli::Parser like every Lantern executable.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/game/gi_view.hpp"
#include "lantern/game/world_setup.hpp"
#include "lantern/scene/scene.hpp"

#include <glm/vec2.hpp>

#include <optional>
#include <string>
#include <vector>

namespace lantern::game {

enum class RunMode : std::uint8_t { automatic, window, headless };

struct GameOptions {
    WorldSpec world;                 // --caves [SEED] (default), --map FILE, --scene FILE
    std::string load;                // --load SAVE: start from a save (its world)
    std::string save_file = "lantern-save.json"; // where F5 saves and F9 loads (slot 1; settings.hpp)
    std::string settings_file;       // --settings FILE (default: lantern-settings.json beside the save file)
    int autosave_seconds = -1;       // --autosave SECONDS (0: none; -1: the settings file's, 180 by default)
    RunMode mode = RunMode::automatic; // --window / --headless; automatic: window if a display can open
    std::string status_file;         // --status-file PATH: each frame's state, for scripted play
    std::string schedule_dot;        // --schedule FILE.dot: the frame schedule as Graphviz DOT
    std::string tables_file;         // --tables FILE: the game's materials and lights (tables.hpp)
    bool watch = false;              // --watch: reload the --scene file (and --tables) when it changes
    // --min-fps N: in a window on the game's own GI settings, a frame rate clearly below N at
    // p95 lowers the GI preset a step (docs/game.md, "Performance"); 0: never.
    int min_fps = 30;

    // Headless demo.
    int frames = 900;                // --frames N
    std::string out_dir = "lantern-demo"; // --out DIR: screenshots, report, trace
    int screenshots = 6;             // --screenshots N, evenly spaced (0: none)
    bool bench = false;              // --bench: print the per-system and per-pass percentiles

    // Presentation.
    glm::ivec2 window_size{1280, 720}; // --size WxH
    glm::ivec2 internal{480, 270};   // --internal WxH (the pixel-art resolution)
    // In a window without --internal, `internal` is the design size: the pixel-art target
    // follows the window, filling it at the whole-number scale nearest window / internal
    // (render::fill_integer_scale). --internal fixes it (letterboxed at the largest scale).
    bool internal_fixed = false;
    bool vsync = true;               // --vsync on|off
    bool hud = true;                 // --no-hud hides it at start (F1 toggles)
    int posterize = 0;               // --posterize N
    bool dither = false;             // --dither
    std::string palette;             // --palette NAME
    GiDebugView gi_view = GiDebugView::lit; // --gi-view NAME: a GI texture over the world (HUD: GI views)

    // Simulation.
    scene::GiSettings gi;            // the game's defaults, then --set gi.KEY=VALUE overrides
    std::vector<std::string> gi_overrides; // the --set assignments (applied again to a scene's own settings)
    bool player_light = true;        // --no-player-light
    float time_of_day = 0.85f;       // --time-of-day T: a new game's start (0 midnight, 0.5 noon; a save keeps its own)
    bool sound = true;               // --no-sound (a window without an audio device runs silent anyway)
    bool bake = true;                // --no-bake: no baked light (docs/baked.md, "In the game")
    bool texel_lighting = true;      // --no-texel-lighting: props and the player lit per pixel by
                                     // the GI, not per texel (docs/texel.md, "In the game")
    std::string bake_dir;            // --bake-dir DIR (default: lantern-bake beside the save file; headless: in --out)
    // --bake-resolution, --bake-rays ... (lantern-bake's options, prefixed): given ones replace
    // the world's own (a scene's "bake") or the game's defaults (BakerOptions::settings).
    scene::BakeSettings bake_values;
    std::vector<std::string> bake_given; // which of them were given (bake::GivenSettings::given)
    int workers = -1;                // --workers N (-1: hardware threads - 1)
    bool fixed_step = false;         // --fixed-step: dt = 1/60 whatever the frame took (headless always)
    bool validation = false;         // --validation: Vulkan validation layers

    // Which of the settings file's values the command line gave (they win for this run).
    struct Given {
        bool vsync = false, posterize = false, dither = false, gi = false;
    } given;
};

// The settings file a game with these options reads and writes.
std::string settings_path(const GameOptions& options);

// The GI settings the game plays with by default, chosen from the headless benchmark on a
// 2-core machine with lavapipe (docs/game.md, "Performance").
scene::GiSettings default_game_gi();

// Parses argv[1..] into `out` (which starts from the defaults). Returns nullopt to go on, or
// the exit status when the game should stop: 0 after --help or --version (printed on
// stdout), 2 after bad input (one line on stderr; outputs are checked too, nothing written).
std::optional<int> parse_options(int argc, const char* const* argv, GameOptions& out);

} // namespace lantern::game
