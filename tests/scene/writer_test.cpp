// Writing a scene back (lantern/scene/writer.hpp): what is rewritten reads back as the edited
// scene, and what was not edited stays as the file wrote it.
#include "lantern/scene/writer.hpp"

#include "lantern/core/file.hpp"
#include "lantern/scene/loader.hpp"

#include "common/test_support.hpp"
#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace {

using namespace lantern;
using namespace lantern::scene;

struct SceneFile {
    std::string path, text;
    Scene scene;
};

std::vector<SceneFile> repository_scenes() {
    std::vector<SceneFile> out;
    const auto root = test::source_dir();
    for (const char* dir : {"tests/golden", "tests/fuzz/corpus/scene", "examples/headless_tool"}) {
        for (const auto& entry : std::filesystem::directory_iterator(root / dir)) {
            if (entry.path().extension() != ".json") continue;
            auto text = read_text_file(entry.path().string(), 1 << 24);
            if (!text) continue;
            auto scene = parse_scene(*text, entry.path().string(), entry.path().parent_path().string());
            if (!scene) continue; // the fuzz corpus holds malformed scenes too
            out.push_back({entry.path().string(), *text, *scene});
        }
    }
    return out;
}

Scene reparse(const std::string& text, const SceneFile& f) {
    auto scene = parse_scene(text, f.path, std::filesystem::path(f.path).parent_path().string());
    EXPECT_TRUE(scene.ok()) << f.path << ": " << (scene ? "" : scene.error().message) << "\n" << text;
    return scene ? *scene : Scene{};
}

TEST(SceneWriter, UneditedListsReadBackAsTheSameScene) {
    const auto files = repository_scenes();
    ASSERT_GE(files.size(), 8u);
    for (const SceneFile& f : files) {
        auto lists = scene_lists(f.text, f.path, f.scene);
        ASSERT_TRUE(lists.ok()) << lists.error().message;
        auto text = rewrite_scene_lists(f.text, f.path, *lists);
        ASSERT_TRUE(text.ok()) << text.error().message;
        Scene back = reparse(*text, f);
        back.source = f.scene.source;
        EXPECT_EQ(back, f.scene) << f.path;
        // Written again, the text is a fixed point.
        auto again = rewrite_scene_lists(*text, f.path, *lists);
        ASSERT_TRUE(again.ok());
        EXPECT_EQ(*again, *text) << f.path;
    }
}

TEST(SceneWriter, EveryEntryWrittenInFullReadsBackExactly) {
    for (const SceneFile& f : repository_scenes()) {
        auto lists = scene_lists(f.text, f.path, f.scene);
        ASSERT_TRUE(lists.ok());
        for (auto& e : lists->point_lights) e.original = -1;
        for (auto& e : lists->emissive_lights) e.original = -1;
        for (auto& e : lists->shadow_proxies) e.original = -1;
        auto text = rewrite_scene_lists(f.text, f.path, *lists);
        ASSERT_TRUE(text.ok()) << text.error().message;
        Scene back = reparse(*text, f);
        back.source = f.scene.source;
        EXPECT_EQ(back, f.scene) << f.path; // temperatures became their colours, bit for bit
    }
}

TEST(SceneWriter, EditsAddAndRemoveEntriesAndKeepTheRest) {
    const std::string text = R"({"lantern_scene": 1,
  "world": {"rows": ["#....", ".....", "....#"]},
  "view": {"center": [2.5, 1.5], "size": [8, 4.5]},
  "gi": {"resolution": 3, "ao": {"radius": 1.5}},
  "point_lights": [
    {"position": [1.5, 1.5], "temperature": 2700, "radius": 6},
    {"position": [3.5, 0.5], "color": [0.2, 0.4, 1], "mode": "mixed"}
  ],
  "shadow_proxies": [{"position": [2, 2], "shape": "box", "size": [0.25, 0.5]}]
})";
    const Scene scene = test::parse_scene_ok(text);
    auto lists = scene_lists(text, "t.json", scene);
    ASSERT_TRUE(lists.ok()) << lists.error().message;
    // Move the second light, drop the proxy, add an emissive and a proxy.
    lists->point_lights[1].value.position = {4.25f, 2.75f};
    lists->point_lights[1].value.color = {1.0f, 0.1f, 0.05f};
    lists->point_lights[1].original = -1;
    lists->shadow_proxies.clear();
    EmissiveLight glow;
    glow.position = {0.5f, 2.5f};
    glow.color = {0.3f, 1.0f, 0.3f};
    lists->emissive_lights.push_back({glow, -1});
    ShadowProxy post;
    post.position = {1.25f, 0.75f};
    post.size = {0.2f, 0.2f};
    lists->shadow_proxies.push_back({post, -1});
    auto out = rewrite_scene_lists(text, "t.json", *lists);
    ASSERT_TRUE(out.ok()) << out.error().message;
    const Scene back = test::parse_scene_ok(*out);
    const Scene expected = with_lists(scene, scene.shadow_proxies.size(), *lists);
    EXPECT_EQ(back.point_lights, expected.point_lights);
    EXPECT_EQ(back.emissive_lights, expected.emissive_lights);
    EXPECT_EQ(back.shadow_proxies, expected.shadow_proxies);
    EXPECT_EQ(back.gi, scene.gi);
    EXPECT_EQ(back.walls, scene.walls);
    EXPECT_EQ(back.view, scene.view);
    // The unedited light keeps its temperature as written; the order of the members stays.
    EXPECT_NE(out->find("\"temperature\": 2700"), std::string::npos) << *out;
    EXPECT_LT(out->find("\"gi\""), out->find("\"point_lights\""));
    EXPECT_LT(out->find("\"shadow_proxies\""), out->find("\"emissive_lights\"")) << "a new list goes at the end";
}

TEST(SceneWriter, AMapsTreesStayInTheMapAndOutOfTheFile) {
    const test::TempDir tmp;
    const auto& dir = tmp.path();
    ASSERT_TRUE(write_file_atomic((dir / "w.map").string(),
                                  std::string("type octile\nheight 3\nwidth 4\nmap\n..T.\n....\n.T..\n")).ok());
    const std::string text = R"({"lantern_scene": 1, "world": {"map": "w.map", "trees": "proxy"},
 "view": {"center": [2, 1.5]}, "shadow_proxies": [{"position": [0.5, 0.5]}]})";
    const Scene scene = test::parse_scene_ok(text, dir.string());
    ASSERT_EQ(scene.shadow_proxies.size(), 3u);
    auto lists = scene_lists(text, "t.json", scene);
    ASSERT_TRUE(lists.ok());
    ASSERT_EQ(lists->shadow_proxies.size(), 1u) << "only the file's own proxy";
    lists->shadow_proxies[0].value.position = {3.5f, 2.5f};
    lists->shadow_proxies[0].original = -1;
    auto out = rewrite_scene_lists(text, "t.json", *lists);
    ASSERT_TRUE(out.ok());
    const Scene back = test::parse_scene_ok(*out, dir.string());
    EXPECT_EQ(back.shadow_proxies, with_lists(scene, 1, *lists).shadow_proxies);
    EXPECT_EQ(back.shadow_proxies.size(), 3u);
}

TEST(SceneWriter, RefusesTextThatIsNotTheScenes) {
    const std::string text = R"({"lantern_scene": 1, "world": {"rows": ["."]}, "view": {"center": [0, 0]},
 "point_lights": [{"position": [0.5, 0.5]}]})";
    const Scene scene = test::parse_scene_ok(text);
    auto lists = scene_lists(text, "t.json", scene);
    ASSERT_TRUE(lists.ok());
    // The file lost its light since it was read: an original beyond its list is refused.
    const std::string shorter = R"({"lantern_scene": 1, "world": {"rows": ["."]}, "view": {"center": [0, 0]}})";
    auto out = rewrite_scene_lists(shorter, "t.json", *lists);
    ASSERT_FALSE(out.ok());
    EXPECT_NE(out.error().message.find("point_lights[0]"), std::string::npos) << out.error().message;
    EXPECT_FALSE(scene_lists(shorter, "t.json", scene).ok());
    auto bad = rewrite_scene_lists("[1, 2", "t.json", *lists);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message.rfind("t.json:1:", 0), 0u) << bad.error().message;
    EXPECT_FALSE(rewrite_scene_lists("[]", "t.json", *lists).ok());
}

} // namespace
