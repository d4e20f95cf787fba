#include "lantern/game/settings.hpp"

#include "lantern/core/file.hpp"
#include "lantern/core/json.hpp"
#include "lantern/core/json_writer.hpp"
#include "lantern/scene/json_reader.hpp"

#include <algorithm>
#include <filesystem>

namespace lantern::game {
namespace {

using platform::Key;
using scene::reading::EnumName;
using scene::reading::Fields;
using scene::reading::IntRange;
using scene::reading::Reader;

constexpr std::array<EnumName<GiPreset>, gi_preset_count> preset_names{{
    {"world", GiPreset::world},
    {"low", GiPreset::low},
    {"medium", GiPreset::medium},
    {"high", GiPreset::high},
}};

constexpr std::array<EnumName<int>, palette_count> palette_choices{{
    {"off", 0}, {"cave", 1}, {"gameboy", 2}, {"pico", 3}, {"dusk", 4},
}};

// Settings files are a few hundred bytes: anything much larger is not one.
constexpr std::uint64_t max_settings_file_bytes = 64 * 1024;

} // namespace

KeyBindings default_key_bindings() {
    return {Key::w, Key::s, Key::a, Key::d, Key::n, Key::f1, Key::f2, Key::f5, Key::f9, Key::f3};
}

bool bindable(Key key) {
    if (platform::key_name(key).empty()) return false;
    if (key == Key::escape || (key >= Key::digit_1 && key <= Key::digit_5)) return false;
    return key != Key::up && key != Key::down && key != Key::left && key != Key::right;
}

void bind(KeyBindings& keys, Action action, Key key) {
    Key& slot = keys[std::size_t(action)];
    for (Key& other : keys)
        if (other == key && &other != &slot) other = slot; // the other action takes the old key
    slot = key;
}

namespace {

struct Quality {
    int resolution;
    scene::HeatScale heat_scale;
    const char* heat_scale_name; // as scene files spell it
    int heat_rounds;
    int max_lights;
};
// In GiPreset order after `world` (which changes nothing).
constexpr Quality quality_presets[] = {
    {2, scene::HeatScale::half, "half", 12, 64},        // low
    {4, scene::HeatScale::half, "half", 20, 256},       // medium: the game's defaults until 2026-12-01
    {8, scene::HeatScale::quarter, "quarter", 20, 256}, // high: the seed's look, the game's defaults (default_game_gi)
};

} // namespace

void apply_gi_preset(GiPreset preset, scene::GiSettings& gi) {
    if (preset == GiPreset::world) return;
    const Quality& q = quality_presets[int(preset) - 1];
    gi.resolution = q.resolution;
    gi.heat_scale = q.heat_scale;
    gi.heat_rounds = q.heat_rounds;
    gi.max_lights = q.max_lights;
}

std::vector<std::string> gi_preset_overrides(GiPreset preset) {
    if (preset == GiPreset::world) return {};
    const Quality& q = quality_presets[int(preset) - 1];
    return {"gi.resolution=" + std::to_string(q.resolution), std::string("gi.heat_scale=") + q.heat_scale_name,
            "gi.heat_rounds=" + std::to_string(q.heat_rounds), "gi.max_lights=" + std::to_string(q.max_lights)};
}

std::string format_settings(const PlayerSettings& s) {
    json::Writer w;
    w.begin_object();
    w.field("lantern_settings", settings_format_version);
    w.field("gi_preset", gi_preset_names[int(s.gi_preset)]);
    w.field("vsync", s.vsync).field("pixel_scale", s.pixel_scale);
    w.field("posterize", s.posterize).field("dither", s.dither).field("palette", palette_names[s.palette]);
    w.field("autosave_seconds", s.autosave_seconds).field("volume", s.volume);
    w.field("world_self", s.world_self).field("world_bleed", s.world_bleed);
    w.field("character_self", s.character_self).field("character_bleed", s.character_bleed);
    w.key("keys").begin_object();
    for (int i = 0; i < action_count; ++i) w.field(action_keys[i], platform::key_name(s.keys[std::size_t(i)]));
    w.end();
    w.end();
    return w.take();
}

Result<PlayerSettings> parse_settings(std::string_view text, const std::string& file_name) {
    auto doc = json::parse(text, file_name);
    if (!doc) return doc.error();
    Reader r("the settings");
    PlayerSettings s;
    Fields top(r, *doc, "",
               {"lantern_settings", "gi_preset", "vsync", "pixel_scale", "posterize", "dither", "palette", "autosave_seconds", "volume",
                "world_self", "world_bleed", "character_self", "character_bleed", "keys"});
    int version = 0;
    top.required("lantern_settings", version, IntRange{1, 1 << 20});
    if (r.ok() && version != settings_format_version)
        top.fail("lantern_settings", "settings format " + std::to_string(version) + " is not supported (this build reads " +
                                         std::to_string(settings_format_version) + ")");
    top.optional("gi_preset", s.gi_preset, preset_names)
        .optional("vsync", s.vsync)
        .optional("pixel_scale", s.pixel_scale, IntRange{0, max_pixel_scale})
        .optional("posterize", s.posterize, IntRange{0, 64})
        .optional("dither", s.dither)
        .optional("palette", s.palette, palette_choices)
        .optional("autosave_seconds", s.autosave_seconds, IntRange{0, max_autosave_seconds})
        .optional("volume", s.volume, IntRange{0, 100})
        .optional("world_self", s.world_self, scene::reading::between(0.0, 1.0))
        .optional("world_bleed", s.world_bleed, scene::reading::between(0.0, 1.0))
        .optional("character_self", s.character_self, scene::reading::between(0.0, 1.0))
        .optional("character_bleed", s.character_bleed, scene::reading::between(0.0, 1.0));
    if (r.ok() && s.posterize == 1) top.fail("posterize", "must be 0 (off) or in [2, 64], got 1");
    if (const json::Value* keys = top.find("keys")) {
        Fields f(r, *keys, "keys",
                 {action_keys[0], action_keys[1], action_keys[2], action_keys[3], action_keys[4], action_keys[5],
                  action_keys[6], action_keys[7], action_keys[8], action_keys[9]});
        static_assert(action_count == 10, "list every action's key above");
        for (int i = 0; i < action_count && r.ok(); ++i) {
            const json::Value* v = f.find(action_keys[i]);
            if (!v) continue;
            std::string name;
            if (!r.read(*v, f.path_of(action_keys[i]), name)) break;
            const auto key = platform::key_by_name(name);
            if (!key || !bindable(*key)) {
                f.fail(action_keys[i], key ? "'" + scene::reading::shorten(name) +
                                                 "' cannot be bound (Escape, 1-5 and the arrow keys are the game's own)"
                                           : "unknown key '" + scene::reading::shorten(name) +
                                                 "' (key names: a-z, 0-9, f1-f25, space, enter, left_shift, kp_0 ... "
                                                 "docs/game.md, \"Settings\")");
                break;
            }
            s.keys[std::size_t(i)] = *key;
        }
        // An action added after version 1's first nine that the file does not name keeps its
        // default key, unless the file gave that key to another action (a file written before
        // the action existed): it then takes a free key. (The first nine stay strict: a file
        // that takes W for another action without rebinding walk_up is refused, below.)
        constexpr int first_added_action = int(Action::scene_editor);
        for (int i = first_added_action; i < action_count && r.ok(); ++i) {
            if (f.find(action_keys[i])) continue;
            const auto taken = [&](Key k) {
                for (int j = 0; j < action_count; ++j)
                    if (j != i && s.keys[std::size_t(j)] == k) return true;
                return false;
            };
            if (!taken(s.keys[std::size_t(i)])) continue;
            for (int k = int(Key::f1); k <= int(Key::f12); ++k)
                if (!taken(Key(k))) {
                    s.keys[std::size_t(i)] = Key(k);
                    break;
                }
        }
        // Each key at most once: a key bound twice would do two things at once.
        for (int i = 0; i < action_count && r.ok(); ++i)
            for (int j = 0; j < i; ++j)
                if (s.keys[std::size_t(i)] == s.keys[std::size_t(j)]) {
                    f.fail(f.find(action_keys[i]) ? action_keys[i] : action_keys[j],
                           "'" + std::string(platform::key_name(s.keys[std::size_t(i)])) + "' is bound to both " +
                               action_keys[j] + " and " + action_keys[i]);
                    break;
                }
    }
    if (!r.ok()) return scene::reading::issue_error(file_name, r.issue());
    return s;
}

Result<void> write_settings(const std::string& path, const PlayerSettings& settings) {
    return write_file_atomic(path, format_settings(settings));
}

Result<PlayerSettings> read_settings(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec) && !ec) return PlayerSettings{};
    auto text = read_text_file(path, max_settings_file_bytes);
    if (!text) return text.error();
    return parse_settings(*text, path);
}

} // namespace lantern::game
