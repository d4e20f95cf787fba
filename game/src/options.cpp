#include "lantern/game/options.hpp"

#include "lantern/bake/bake.hpp"
#include "lantern/game/baking.hpp"
#include "lantern/game/settings.hpp"
#include "lantern/core/cli.hpp"
#include "lantern/core/file.hpp"
#include "lantern/core/text.hpp"
#include "lantern/scene/loader.hpp"

#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace lantern::game {
namespace {

bool parse_int(std::string_view s, int& out, int min, int max) {
    int v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || v < min || v > max) return false;
    out = v;
    return true;
}

// A WxH size, each side in [min, max].
cli::Parser::Check size_option(glm::ivec2& out, int min, int max) {
    return [&out, min, max](std::string_view s) -> std::optional<std::string> {
        const auto x = s.find('x');
        glm::ivec2 v;
        if (x == std::string_view::npos || !parse_int(s.substr(0, x), v.x, min, max) ||
            !parse_int(s.substr(x + 1), v.y, min, max))
            return "must be WxH, each in [" + std::to_string(min) + ", " + std::to_string(max) + "], got '" +
                   printable(s) + "'";
        out = v;
        return std::nullopt;
    };
}

} // namespace

scene::GiSettings default_game_gi() {
    scene::GiSettings gi;
    // The seed's look (docs/game.md, "Performance": the whole frame within 33 ms at p95 on a
    // 2-core machine's lavapipe); `--quality medium` halves the resolution, for slower machines.
    gi.resolution = 8;
    gi.heat_scale = scene::HeatScale::quarter;
    gi.heat_rounds = 20; // the seed's
    gi.padding = 1.25f;
    gi.max_lights = 256; // light caps are what users of 2D lighting hit first

    gi.max_shadow_proxies = 32;
    // The camera looks towards -z from behind the player (CameraRig): a -z face always faces
    // away from it, so the GI neither traces nor stores those faces (docs/gi.md).
    gi.wall_faces.nz = false;
    // docs/accuracy.md: about 0.25-0.5 matches an albedo-0.5 world in level; 1.0 (the seed's)
    // washes a torch-lit cave out.
    gi.emission_strength = 0.5f;
    // Live light probes (docs/baked.md, "Live probes"): the walls' light on the things that
    // move, from the side it comes from. 16 rays: 0.6-0.9 ms a frame on lavapipe (32: 1.5 ms).
    gi.probe_rays = 16;
    return gi;
}

std::optional<int> parse_options(int argc, const char* const* argv, GameOptions& o) {
    o = GameOptions{};
    o.gi = default_game_gi();
    scene::Scene overrides;
    overrides.gi = o.gi;
    bool world_given = false;
    bool out_given = false;
    std::string vsync = "on";
    auto world = [&](WorldKind kind) {
        return [&, kind](std::string_view value) -> std::optional<std::string> {
            if (world_given) return "give one world (--caves, --map or --scene)";
            world_given = true;
            o.world.kind = kind;
            if (kind != WorldKind::caves) {
                if (value.empty()) return "must not be empty";
                o.world.path = std::string(value);
            } else if (!value.empty()) {
                int seed = 0;
                if (!parse_int(value, seed, 0, 0x7FFFFFFF))
                    return "must be a seed in [0, 2147483647], got '" + printable(value) + "'";
                o.world.seed = std::uint32_t(seed);
            }
            return std::nullopt;
        };
    };

    cli::Parser p("lantern", "[world] [options]", "The Lantern sandbox game (docs/game.md).");
    p.section("world (default: --caves 1)");
    p.custom("--caves", "SEED", "seeded procedural caves", world(WorldKind::caves), false, true);
    p.custom("--map", "FILE.map", "a Moving AI map; 'T' cells become trees with proxy shadows", world(WorldKind::map));
    p.custom("--scene", "FILE.json", "a Lantern scene file (its lights, proxies and GI settings)",
             world(WorldKind::scene));
    p.text("--load", "SAVE.json", "continue a saved game (its world, edits, lights, player)", o.load);
    p.text("--save-file", "PATH",
           "save slot 1: where F5 saves and F9 loads (default lantern-save.json;\n"
           "slots 2-3 and the autosaves sit beside it)",
           o.save_file);
    p.text("--settings", "PATH",
           "the pause menu's settings (default lantern-settings.json beside\n"
           "the save file); the options below win over it for this run",
           o.settings_file);
    p.text("--tables", "FILE.json",
           "the caves' materials and the lights of torches, crystals, lamp posts\n"
           "and the player's lantern (docs/game.md, \"Game tables\"; default built in)",
           o.tables_file);
    p.integer("--autosave", "SECONDS", "autosave every SECONDS of play (0: never; default: the settings', 180)",
              o.autosave_seconds, 0, 24 * 3600);
    p.section("mode (default: a window when a display can open, else the headless demo)");
    p.flag("--window", "a window or an error", [&] { o.mode = RunMode::window; });
    p.flag("--headless", "the scripted demo without a window: PNG screenshots, profiler report",
           [&] { o.mode = RunMode::headless; });
    p.integer("--frames", "N", "headless frames (default 900)", o.frames, 1, 10000000);
    p.custom("--out", "DIR", "headless output folder (default lantern-demo)",
             [&](std::string_view v) -> std::optional<std::string> {
                 if (v.empty()) return "must not be empty";
                 o.out_dir = std::string(v);
                 out_given = true;
                 return std::nullopt;
             });
    p.integer("--screenshots", "N", "screenshots over the run (default 6, 0 for none)", o.screenshots, 0, 1000);
    p.flag("--bench", "print per-system and per-pass percentiles (headless benchmark)", o.bench);
    p.text("--status-file", "PATH",
           "after each frame, write the frame number, player position, mouse,\n"
           "buttons, saves, lights, --watch reloads and waits while minimised\n"
           "as one JSON line (for scripts and tests)",
           o.status_file);
    p.flag("--watch",
           "reload the --scene file and the --tables file when they change (a\n"
           "malformed edit is reported and the last good one keeps running)",
           o.watch);
    p.text("--schedule", "FILE.dot",
           "write the frame's system schedule as Graphviz DOT at start-up\n"
           "(systems, declared access, the edges they imply, ambiguities)",
           o.schedule_dot);
    p.section("presentation");
    p.custom("--size", "WxH", "window size (default 1280x720)", size_option(o.window_size, 64, 16384));
    p.custom("--internal", "WxH",
             "pixel-art resolution, fixed (default: 480x270 headless; in a window, the size near 480x270 that "
             "fills it at a whole-number scale)",
             [&o, check = size_option(o.internal, 32, 4096)](std::string_view s) {
                 auto error = check(s);
                 if (!error) o.internal_fixed = true;
                 return error;
             });
    p.custom("--vsync", "on|off", "(default on)", [&](std::string_view v) -> std::optional<std::string> {
        if (v != "on" && v != "off") return "must be one of on, off, got '" + printable(v) + "'";
        vsync = std::string(v);
        o.given.vsync = true;
        return std::nullopt;
    });
    p.flag("--no-hud", "start with the timer HUD hidden (F1 toggles)", [&] { o.hud = false; });
    p.custom("--posterize", "N", "posterize to N levels per channel", [&](std::string_view v) -> std::optional<std::string> {
        if (!parse_int(v, o.posterize, 2, 64)) return "must be an integer in [2, 64], got '" + printable(v) + "'";
        o.given.posterize = true;
        return std::nullopt;
    });
    p.flag("--dither", "ordered 4x4 dithering", [&] { o.dither = o.given.dither = true; });
    p.text("--palette", "NAME", "palette swap (names in docs/game.md)", o.palette);
    std::string view_list;
    for (const char* name : gi_debug_view_names()) view_list += std::string(view_list.empty() ? "" : ", ") + name;
    p.custom("--gi-view", "NAME",
             "draw a GI texture over the world instead of the lit scene:\n" + view_list +
                 " (the last five: gi.method=radiosity)",
             [&](std::string_view v) -> std::optional<std::string> {
                 const auto view = gi_debug_view_by_name(v);
                 if (!view) return "must be one of " + view_list + ", got '" + printable(v) + "'";
                 o.gi_view = *view;
                 return std::nullopt;
             });
    p.section("simulation");
    p.custom(
        "--set", "gi.KEY=VALUE", "a GI setting, as in scene files, e.g. --set gi.resolution=8",
        [&](std::string_view v) -> std::optional<std::string> {
            if (auto ok = scene::apply_override(overrides, v); !ok) return ok.error().message;
            o.gi_overrides.emplace_back(v);
            o.given.gi = true;
            return std::nullopt;
        },
        true);
    p.custom("--quality", "low|medium|high",
             "the GI quality preset (default high: the seed's look, 30 fps at p95 on a 2-core CPU's lavapipe;\n"
             "medium: half its resolution, for slower machines); like --set, a later option wins",
             [&](std::string_view v) -> std::optional<std::string> {
                 for (int k = 1; k < gi_preset_count; ++k)
                     if (v == gi_preset_names[k]) {
                         for (const std::string& kv : gi_preset_overrides(GiPreset(k))) {
                             if (auto ok = scene::apply_override(overrides, kv); !ok) return ok.error().message;
                             o.gi_overrides.push_back(kv);
                         }
                         o.given.gi = true;
                         return std::nullopt;
                     }
                 return "must be low, medium or high, got '" + printable(v) + "'";
             },
             true);
    p.integer("--min-fps", "N",
              "in a window, on the game's own GI settings: a frame rate clearly below N at p95 lowers the GI\n"
              "quality a step, saved in the settings file (default 30; 0: never)",
              o.min_fps, 0, 1000);
    p.flag("--no-player-light", "the player carries no light", [&] { o.player_light = false; });
    p.number("--time-of-day", "T",
             "the time of day a new game starts at: 0 midnight, 0.25 sunrise, 0.5 noon, 0.75 sunset\n"
             "(default 0.85: night, the caves lit by torches and crystals; a save keeps its own)",
             o.time_of_day, 0.0f, 0.999f);
    p.flag("--no-sound", "no sound (without an audio device the game runs silent anyway)", [&] { o.sound = false; });
    p.flag("--no-texel-lighting", "light props and the player per pixel by the GI, not per texel of their art",
           [&] { o.texel_lighting = false; });
    p.flag("--no-bake", "light everything live: no baked light (the modes of lights are ignored)", [&] { o.bake = false; });
    p.text("--bake-dir", "DIR",
           "where the baked light of the world's chunks is kept (default: lantern-bake beside the save file;\n"
           "the headless demo: in its --out folder)", o.bake_dir);
    // The baker's settings (defaults: the game's, BakerOptions; a scene world's "bake" block
    // first): the options given replace them.
    o.bake_values = BakerOptions{}.settings;
    bake::add_settings_options(p, o.bake_values, "--bake-", o.bake_values);
    p.integer("--workers", "N", "job-system worker threads (default: cores - 1)", o.workers, 0, 256);
    p.flag("--fixed-step", "advance 1/60 s per frame whatever the frame took", o.fixed_step);
    p.flag("--validation", "enable the Vulkan validation layers", o.validation);
    p.epilog("controls: WASD/arrows walk, left mouse mines, right mouse places the selected item\n"
             "(1 wall, 2 torch, 3 crystal, 4 lamp post, 5 tree), N day/night cycle, F1 HUD,\n"
             "F2 export a Chrome trace, F5 save, F9 load, Esc the pause menu (settings,\n"
             "key bindings, save slots, quit).\n"
             "exit status: 0 ok, 1 runtime failure (e.g. no Vulkan device), 2 bad input.");
    if (auto exit = p.parse(argc, argv)) return exit;
    o.bake_given = bake::given_settings(p, o.bake_values, "--bake-").given;
    o.vsync = vsync == "on";
    o.gi = overrides.gi;
    // Outputs are checked before the game starts (a folder, FIFO or device named as a file,
    // a file named as the output folder): one line, exit 2, nothing written.
    auto refuse = [](const std::string& what) {
        std::fprintf(stderr, "lantern: %s\n", what.c_str());
        return 2;
    };
    if (out_given)
        if (auto ok = check_output_folder(o.out_dir); !ok) return refuse("--out " + ok.error().message);
    if (!o.status_file.empty())
        if (auto ok = check_output_file(o.status_file); !ok) return refuse("--status-file " + ok.error().message);
    if (o.watch && o.world.kind != WorldKind::scene && o.tables_file.empty())
        return refuse("--watch needs a --scene FILE or a --tables FILE to watch");
    if (!o.schedule_dot.empty())
        if (auto ok = check_output_file(o.schedule_dot); !ok) return refuse("--schedule " + ok.error().message);
    if (!o.settings_file.empty())
        if (auto ok = check_output_file(o.settings_file); !ok) return refuse("--settings " + ok.error().message);
    return std::nullopt;
}

std::string settings_path(const GameOptions& options) {
    if (!options.settings_file.empty()) return options.settings_file;
    return (std::filesystem::path(options.save_file).parent_path() / "lantern-settings.json").string();
}

} // namespace lantern::game
