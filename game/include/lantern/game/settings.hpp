// The player's settings: what the pause menu changes and keeps between runs (GI quality
// preset, vsync, pixel scale, art, autosave interval, volume, key bindings), in a small JSON file
// (docs/game.md, "Settings").
//
// write_settings() replaces the file atomically; read_settings() gives the defaults for a
// missing file and rejects anything malformed with "<file>:<line>:<col>: <path>: <what>"
// (exit status 2). Options given on the command line win over the file for that run.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/platform/input.hpp"
#include "lantern/scene/scene.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::game {

inline constexpr int settings_format_version = 1;

// What a key can be bound to.
enum class Action : std::uint8_t {
    walk_up,
    walk_down,
    walk_left,
    walk_right,
    day_cycle,   // start or stop the day/night cycle
    toggle_hud,  // the timer HUD
    trace,       // export a Chrome trace
    quick_save,  // save to slot 1
    quick_load,  // load slot 1
    scene_editor, // the scene editor (scene worlds)
};
inline constexpr int action_count = 10;
// Their keys in the settings file, and their labels in the menu, in Action order.
inline constexpr const char* action_keys[action_count] = {"walk_up",   "walk_down", "walk_left",  "walk_right", "day_cycle",
                                                          "toggle_hud", "trace",     "quick_save", "quick_load", "scene_editor"};
inline constexpr const char* action_labels[action_count] = {
    "walk up", "walk down", "walk left", "walk right", "day/night cycle", "timer HUD", "export trace", "quick save",
    "quick load", "scene editor"};

// One key per action, each key bound at most once. The arrow keys always walk as well, and
// Escape (the menu) and the item keys 1-5 cannot be bound.
using KeyBindings = std::array<platform::Key, action_count>;
KeyBindings default_key_bindings(); // W S A D, N, F1, F2, F5, F9, F3
// Whether `key` can be bound to an action (not Escape, not 1-5, not an arrow key).
bool bindable(platform::Key key);
// Binds `action` to `key`; an action that had `key` takes the action's old key (a swap), so
// every key stays bound at most once.
void bind(KeyBindings& keys, Action action, platform::Key key);

// GI quality presets: `world` keeps the world's own settings (the game's defaults, or a
// scene file's); the others set resolution, heat and the light cap over them.
enum class GiPreset : std::uint8_t { world, low, medium, high };
inline constexpr const char* gi_preset_names[] = {"world", "low", "medium", "high"};
inline constexpr int gi_preset_count = 4;
// `world`: the world's own settings, unchanged. low: GI resolution 2, heat at half, 12 rounds,
// 64 lights; medium: resolution 4, half, 20 rounds, 256 lights (for machines slower than the
// 2-core one the defaults are measured on); high: the seed's look and the game's defaults
// (resolution 8, heat at quarter, 20 rounds, 256 lights).
void apply_gi_preset(GiPreset preset, scene::GiSettings& gi);
// The same preset as scene-file overrides ("gi.KEY=VALUE", what --set takes); none for `world`.
std::vector<std::string> gi_preset_overrides(GiPreset preset);

// The built-in palette swaps, by index (game_render's builtin_palettes() has their colours):
// 0 "off" keeps the colours.
inline constexpr const char* palette_names[] = {"off", "cave", "gameboy", "pico", "dusk"};
inline constexpr int palette_count = 5;

struct PlayerSettings {
    GiPreset gi_preset = GiPreset::world;
    bool vsync = true;
    int pixel_scale = 0;          // the pixel-art scale in the window: 0 automatic (fills it), else 1-8
    int posterize = 0;            // 0 off, else 2-64 levels per channel
    bool dither = false;
    int palette = 0;              // index into palette_names (0: off)
    int autosave_seconds = 180;   // of play (not paused, not minimised); 0: no autosave
    int volume = 80;              // sound, percent (0: silent)
    // Seed 002's runtime knobs on the bounce light (game::BounceStyle, world_renderer.hpp):
    // self and bleed for the world (ground, walls) and for characters and decorations.
    float world_self = 1.0f, world_bleed = 0.0f;
    float character_self = 1.0f, character_bleed = 0.0f;
    KeyBindings keys = default_key_bindings();
    friend bool operator==(const PlayerSettings&, const PlayerSettings&) = default;
};
inline constexpr int max_pixel_scale = 8;
inline constexpr int max_autosave_seconds = 24 * 3600;

std::string format_settings(const PlayerSettings& settings);
Result<PlayerSettings> parse_settings(std::string_view text, const std::string& file_name);
Result<void> write_settings(const std::string& path, const PlayerSettings& settings);
// The defaults when `path` does not exist.
Result<PlayerSettings> read_settings(const std::string& path);

} // namespace lantern::game
