// The scene editor's model (game/src/app/editor.hpp) without a window: picking, snapping, how
// an edit reaches the world, adding and removing, and saving (atomically, refused over a file
// changed on disk). GameWindow.SceneEditorEditsTheRunningWorldAndWritesTheFile drives the
// panel through real X input.
#include "app/editor.hpp"

#include "common/test_support.hpp"
#include "lantern/core/file.hpp"
#include "lantern/scene/loader.hpp"

#include <gtest/gtest.h>

namespace {

using namespace lantern;
using namespace lantern::game;

constexpr const char* level = R"({"lantern_scene": 1,
  "world": {"rows": ["........", "...#....", "........"]},
  "view": {"center": [4, 1.5], "size": [8, 4.5]},
  "point_lights": [{"position": [1.5, 1.5], "temperature": 3000, "radius": 6},
                   {"position": [6.5, 0.5], "mode": "mixed"}],
  "emissive_lights": [{"position": [4.5, 2.5], "color": [0.2, 1, 0.2]}],
  "shadow_proxies": [{"position": [3, 0.5]}]})";

struct EditorTest : ::testing::Test {
    test::TempDir dir;
    std::string path = dir.file("level.json");
    SceneEditor editor;
    void SetUp() override {
        ASSERT_TRUE(write_file_atomic(path, std::string(level)));
        auto ok = editor.open(path);
        ASSERT_TRUE(ok.ok()) << ok.error().message;
    }
};

TEST_F(EditorTest, AClickSelectsTheNearestEntryWithinATile) {
    EXPECT_EQ(target_name(editor.select_near({1.9f, 1.2f})), "point 0");
    EXPECT_EQ(target_name(editor.select_near({4.4f, 2.0f})), "emissive 0");
    EXPECT_EQ(target_name(editor.select_near({3.0f, 1.0f})), "proxy 0");
    EXPECT_FALSE(editor.select_near({0.0f, 2.9f}).valid()) << "nothing within a tile";
    EXPECT_FALSE(editor.selected().valid());
}

TEST_F(EditorTest, MovesSnapAndRealtimeLightsChangeInPlace) {
    editor.select({EditKind::point_light, 0});
    EditResult r = editor.move_selected({2.61f, 0.13f});
    EXPECT_EQ(r.changed, (EditTarget{EditKind::point_light, 0}));
    EXPECT_FALSE(r.rebuild);
    EXPECT_EQ(*editor.position_of(editor.selected()), glm::vec2(2.5f, 0.25f));
    EXPECT_TRUE(editor.unsaved());
    // A mixed light's bounce is baked, and every proxy is in the bake: the world is rebuilt.
    editor.select({EditKind::point_light, 1});
    EXPECT_TRUE(editor.move_selected({5.0f, 1.0f}).rebuild);
    editor.select({EditKind::proxy, 0});
    EXPECT_TRUE(editor.move_selected({2.0f, 2.0f}).rebuild);
    editor.select({EditKind::emissive_light, 0});
    r = editor.recolor_selected({1.0f, 0.0f, 0.0f});
    EXPECT_TRUE(r.changed.valid());
    EXPECT_EQ(editor.scene().emissive_lights[0].color, glm::vec3(1.0f, 0.0f, 0.0f));
}

TEST_F(EditorTest, AddingAndRemovingRebuildsAndKeepsTheSelectionMeaningful) {
    EditResult r = editor.add(EditKind::proxy, {5.1f, 2.4f});
    EXPECT_TRUE(r.rebuild);
    EXPECT_EQ(target_name(editor.selected()), "proxy 1");
    EXPECT_EQ(editor.scene().shadow_proxies.size(), 2u);
    EXPECT_EQ(editor.scene().shadow_proxies[1].position, glm::vec2(5.0f, 2.5f));
    editor.select({EditKind::point_light, 0});
    EXPECT_TRUE(editor.remove_selected().rebuild);
    EXPECT_FALSE(editor.selected().valid());
    ASSERT_EQ(editor.scene().point_lights.size(), 1u);
    EXPECT_EQ(editor.scene().point_lights[0].mode, scene::LightMode::mixed);
    EXPECT_FALSE(editor.remove_selected().rebuild) << "nothing selected: nothing removed";
    editor.select({EditKind::point_light, 5});
    EXPECT_FALSE(editor.selected().valid()) << "no such entry";
}

TEST_F(EditorTest, SaveWritesTheEditedSceneAndKeepsWhatWasNotEdited) {
    editor.select({EditKind::emissive_light, 0});
    editor.move_selected({7.0f, 2.0f});
    editor.add(EditKind::point_light, {0.5f, 0.5f});
    auto ok = editor.save();
    ASSERT_TRUE(ok.ok()) << ok.error().message;
    EXPECT_FALSE(editor.unsaved());
    EXPECT_EQ(editor.saves(), 1);
    auto back = scene::load_scene(path);
    ASSERT_TRUE(back.ok()) << back.error().message;
    scene::Scene expected = editor.scene();
    expected.source = back->source;
    EXPECT_EQ(*back, expected);
    const std::string text = test::read_file(path);
    EXPECT_NE(text.find("\"temperature\": 3000"), std::string::npos) << "the unedited light as written\n" << text;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator()), 1)
        << "no temporary file left";
    // A second edit after the save starts from the file as written.
    editor.select({EditKind::point_light, 2});
    editor.remove_selected();
    ASSERT_TRUE(editor.save().ok());
    EXPECT_EQ(scene::load_scene(path)->point_lights.size(), 2u);
}

TEST_F(EditorTest, AFileChangedOnDiskIsNotOverwritten) {
    editor.select({EditKind::point_light, 0});
    editor.move_selected({3.0f, 2.0f});
    const std::string theirs = std::string(level) + "\n";
    ASSERT_TRUE(write_file_atomic(path, theirs));
    auto ok = editor.save();
    ASSERT_FALSE(ok.ok());
    EXPECT_NE(ok.error().message.find("changed on disk"), std::string::npos) << ok.error().message;
    EXPECT_EQ(test::read_file(path), theirs);
    EXPECT_TRUE(editor.unsaved());
}

TEST(Editor, AMalformedFileDoesNotOpenAndSaysWhere) {
    test::TempDir dir;
    const std::string path = dir.file("bad.json");
    ASSERT_TRUE(write_file_atomic(path, std::string(R"({"lantern_scene": 1, "world": {"rows": ["."]},
 "view": {"center": [0, 0]}, "point_lights": [{"position": [0.5]}]})")));
    SceneEditor editor;
    auto ok = editor.open(path);
    ASSERT_FALSE(ok.ok());
    EXPECT_EQ(ok.error().message.rfind(path + ":2:", 0), 0u) << ok.error().message;
    EXPECT_FALSE(editor.is_open());
}

} // namespace
