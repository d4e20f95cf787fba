// The pause menu's settings file, key bindings, GI presets and save slots (issue 19).
#include "lantern/core/file.hpp"
#include "lantern/game/options.hpp"
#include "lantern/game/save.hpp"
#include "lantern/game/settings.hpp"
#include "lantern/render/upscale.hpp"
#include "common/test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <thread>

using namespace lantern;
using namespace lantern::game;
using platform::Key;

TEST(Settings, EveryKeyHasANameThatReadsBack) {
    std::set<std::string_view> names;
    int keys = 0;
    for (std::size_t k = 0; k < platform::InputState::key_count; ++k) {
        const std::string_view name = platform::key_name(Key(k));
        if (name.empty()) {
            EXPECT_FALSE(platform::key_by_name(name)) << k;
            continue;
        }
        ++keys;
        EXPECT_TRUE(names.insert(name).second) << "two keys named " << name;
        const auto back = platform::key_by_name(name);
        ASSERT_TRUE(back) << name;
        EXPECT_EQ(int(*back), int(k)) << name;
    }
    EXPECT_EQ(keys, 120);
    EXPECT_EQ(platform::key_name(Key::digit_7), "7");
    EXPECT_EQ(platform::key_name(Key::f5), "f5");
    EXPECT_FALSE(platform::key_by_name("F5")) << "names are exact, lower case";
}

TEST(Settings, RoundTripIsExactAndAMissingFileGivesTheDefaults) {
    test::TempDir dir;
    const std::string path = dir.file("settings.json");
    auto missing = read_settings(path);
    ASSERT_TRUE(missing) << missing.error().message;
    EXPECT_EQ(*missing, PlayerSettings{});

    PlayerSettings s;
    s.gi_preset = GiPreset::high;
    s.vsync = false;
    s.pixel_scale = 3;
    s.posterize = 8;
    s.dither = true;
    s.palette = 3; // pico
    s.autosave_seconds = 0;
    s.volume = 35;
    s.world_self = 0.25f;
    s.world_bleed = 0.1f;
    s.character_self = 0.7f;
    s.character_bleed = 1.0f / 3.0f; // not a short decimal: the file keeps every float exactly
    bind(s.keys, Action::walk_right, Key::l);
    bind(s.keys, Action::quick_save, Key::f6);
    ASSERT_TRUE(write_settings(path, s));
    auto back = read_settings(path);
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(*back, s);
    EXPECT_NE(test::read_file(path).find("\"walk_right\": \"l\""), std::string::npos) << test::read_file(path);

    // Keys left out keep their defaults.
    auto partial = parse_settings(R"({"lantern_settings": 1, "keys": {"trace": "t"}})", "p.json");
    ASSERT_TRUE(partial) << partial.error().message;
    KeyBindings expected = default_key_bindings();
    expected[std::size_t(Action::trace)] = Key::t;
    EXPECT_EQ(partial->keys, expected);
}

TEST(Settings, BindingATakenKeySwapsTheTwoActions) {
    KeyBindings keys = default_key_bindings();
    bind(keys, Action::walk_up, Key::s); // walk_down had S
    EXPECT_EQ(keys[std::size_t(Action::walk_up)], Key::s);
    EXPECT_EQ(keys[std::size_t(Action::walk_down)], Key::w);
    bind(keys, Action::walk_up, Key::s); // already its key: nothing changes
    EXPECT_EQ(keys[std::size_t(Action::walk_down)], Key::w);
    std::set<Key> distinct(keys.begin(), keys.end());
    EXPECT_EQ(distinct.size(), keys.size());
    EXPECT_FALSE(bindable(Key::escape));
    EXPECT_FALSE(bindable(Key::digit_3));
    EXPECT_FALSE(bindable(Key::left));
    EXPECT_TRUE(bindable(Key::digit_6));
    EXPECT_TRUE(bindable(Key::space));
    EXPECT_FALSE(bindable(Key(7))) << "not a key";
}

// A file written before an action existed may have given that action's default key to another
// one: the new action then takes a free key instead of the file being refused.
TEST(Settings, AnActionTheFileDoesNotNameGivesWayToTheFilesKeys) {
    auto s = parse_settings(R"({"lantern_settings": 1, "keys": {"trace": "f3"}})", "s.json");
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_EQ(s->keys[std::size_t(Action::trace)], Key::f3);
    const Key editor = s->keys[std::size_t(Action::scene_editor)];
    EXPECT_NE(editor, Key::f3);
    EXPECT_TRUE(bindable(editor));
    std::set<Key> distinct(s->keys.begin(), s->keys.end());
    EXPECT_EQ(distinct.size(), s->keys.size());
    // Named twice by the file itself is still an error.
    EXPECT_FALSE(parse_settings(R"({"lantern_settings": 1, "keys": {"trace": "f3", "scene_editor": "f3"}})", "s.json").ok());
}

TEST(Settings, MalformedFilesAreRejectedWithPositions) {
    struct Case {
        const char* text;
        const char* message;
    };
    const Case cases[] = {
        {R"({"lantern_settings": 1, "vsnyc": true})", "s.json:1:25: vsnyc: unknown key 'vsnyc' in the settings (did you mean 'vsync'?)"},
        {R"({"lantern_settings": 2})", "s.json:1:22: lantern_settings: settings format 2 is not supported (this build reads 1)"},
        {R"({"vsync": true})", "s.json:1:1: lantern_settings: required key is missing"},
        {R"({"lantern_settings": 1, "gi_preset": "ultra"})", "s.json:1:38: gi_preset: expected one of \"world\", \"low\", \"medium\", \"high\", got \"ultra\""},
        {R"({"lantern_settings": 1, "pixel_scale": 9})", "s.json:1:40: pixel_scale:"},
        {R"({"lantern_settings": 1, "posterize": 1})", "s.json:1:38: posterize: must be 0 (off) or in [2, 64], got 1"},
        {R"({"lantern_settings": 1, "volume": 101})", "s.json:1:35: volume:"},
        {R"({"lantern_settings": 1, "world_bleed": 1.5})", "s.json:1:40: world_bleed:"},
        {R"({"lantern_settings": 1, "character_self": -0.1})", "s.json:1:43: character_self:"},
        {R"({"lantern_settings": 1, "palette": "neon"})", "s.json:1:36: palette: expected one of \"off\", \"cave\", \"gameboy\", \"pico\", \"dusk\", got \"neon\""},
        {R"({"lantern_settings": 1,
  "keys": {"walk_up": "w", "trace": "blorp"}})", "s.json:2:37: keys.trace: unknown key 'blorp'"},
        {R"({"lantern_settings": 1, "keys": {"trace": "escape"}})", "s.json:1:43: keys.trace: 'escape' cannot be bound"},
        {R"({"lantern_settings": 1, "keys": {"trace": "w"}})", "s.json:1:43: keys.trace: 'w' is bound to both walk_up and trace"},
        {R"({"lantern_settings": 1, "keys": {"trace": 5}})", "s.json:1:43: keys.trace: expected a string, got a number"},
        {R"({"lantern_settings": 1,)", "s.json:1:24:"},
    };
    for (const Case& c : cases) {
        auto s = parse_settings(c.text, "s.json");
        ASSERT_FALSE(s) << c.text;
        EXPECT_EQ(s.error().exit_code, 2) << c.text;
        EXPECT_EQ(s.error().message.rfind(c.message, 0), 0u) << c.text << "\n  got: " << s.error().message;
    }
}

TEST(Settings, GiPresetsSetTheQualityKnobsAndHighIsTheGamesDefault) {
    const scene::GiSettings game = default_game_gi();
    EXPECT_EQ(game.resolution, 8); // the seed's look
    EXPECT_EQ(game.heat_scale, scene::HeatScale::quarter);
    EXPECT_EQ(game.heat_rounds, 20);
    scene::GiSettings g = game;
    apply_gi_preset(GiPreset::world, g);
    EXPECT_EQ(g.resolution, game.resolution);
    apply_gi_preset(GiPreset::medium, g);
    EXPECT_EQ(g.resolution, 4);
    EXPECT_EQ(g.heat_scale, scene::HeatScale::half);
    apply_gi_preset(GiPreset::low, g);
    EXPECT_LT(g.resolution, 4);
    apply_gi_preset(GiPreset::high, g);
    EXPECT_EQ(g.resolution, game.resolution);
    EXPECT_EQ(g.heat_scale, game.heat_scale);
    EXPECT_EQ(g.heat_rounds, game.heat_rounds);
    EXPECT_EQ(g.max_lights, game.max_lights);
    EXPECT_EQ(g.emission_strength, game.emission_strength) << "a preset leaves the rest alone";
}

TEST(Settings, AChosenPixelScaleFillsTheWindowAtThatScale) {
    const platform::Extent design{480, 270};
    EXPECT_EQ(render::fill_at_scale(design, {1280, 720}, 2), (platform::Extent{640, 360}));
    EXPECT_EQ(render::fill_at_scale(design, {1280, 720}, 3), render::fill_integer_scale(design, {1280, 720}));
    EXPECT_EQ(render::fill_at_scale(design, {1280, 720}, 1), (platform::Extent{1280, 720}));
    EXPECT_EQ(render::fill_at_scale(design, {4000, 300}, 1), (platform::Extent{1920, 300})) << "clamped to 4x the design";
    EXPECT_EQ(render::fill_at_scale(design, {0, 720}, 2), (platform::Extent{}));
}

TEST(SaveSlots, SlotsSitBesideTheSaveFileAndAutosavesRotateOldestFirst) {
    test::TempDir dir;
    const std::string save = dir.file("world.json");
    EXPECT_EQ(save_slot_path(save, 1), save);
    EXPECT_EQ(save_slot_path(save, 2), dir.file("world-2.json"));
    EXPECT_EQ(autosave_slot_path(save, 3), dir.file("world-autosave-3.json"));
    EXPECT_EQ(save_slot_path("lantern-save", 2), "lantern-save-2.json");

    EXPECT_EQ(next_autosave_slot(save), 1) << "none written";
    ASSERT_TRUE(write_file_atomic(autosave_slot_path(save, 1), std::string("{}")));
    ASSERT_TRUE(write_file_atomic(autosave_slot_path(save, 3), std::string("{}")));
    EXPECT_EQ(next_autosave_slot(save), 2) << "the first missing";
    ASSERT_TRUE(write_file_atomic(autosave_slot_path(save, 2), std::string("{}")));
    // All three exist: the one written longest ago. Set the times outright (a file system's
    // clock may not tell writes a moment apart).
    namespace fs = std::filesystem;
    const auto now = fs::file_time_type::clock::now();
    fs::last_write_time(autosave_slot_path(save, 1), now - std::chrono::seconds(10));
    fs::last_write_time(autosave_slot_path(save, 2), now - std::chrono::seconds(30));
    fs::last_write_time(autosave_slot_path(save, 3), now - std::chrono::seconds(20));
    EXPECT_EQ(next_autosave_slot(save), 2);
    fs::last_write_time(autosave_slot_path(save, 2), now);
    EXPECT_EQ(next_autosave_slot(save), 3);
}

TEST(SaveSlots, TheSettingsFileSitsBesideTheSaveFileUnlessGiven) {
    GameOptions o;
    o.save_file = "saves/world.json";
    EXPECT_EQ(settings_path(o), "saves/lantern-settings.json");
    o.save_file = "world.json";
    EXPECT_EQ(settings_path(o), "lantern-settings.json");
    o.settings_file = "/tmp/mine.json";
    EXPECT_EQ(settings_path(o), "/tmp/mine.json");
}
