#include "lantern/scene/loader.hpp"

#include "common/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

using namespace lantern::scene;
using lantern::test::TempDir;

namespace {

using Cells = std::vector<std::uint8_t>;
using Trees = std::vector<glm::ivec2>;

// Every Moving AI character once; 'T' at (1, 1) and (3, 1).
constexpr std::string_view all_chars_map = "type octile\nheight 2\nwidth 4\nmap\n.GSW\n@TOT\n";

ImportedMap parse_ok(std::string_view text, const MapImportOptions& options = {}) {
    auto result = parse_moving_ai_map(text, "m.map", options);
    EXPECT_TRUE(result.ok()) << result.error().message;
    return result.ok() ? *result : ImportedMap{};
}

std::string parse_error(std::string_view text, const MapImportOptions& options = {}) {
    auto result = parse_moving_ai_map(text, "m.map", options);
    if (result.ok()) return "(imported)";
    EXPECT_EQ(result.error().exit_code, 2);
    return result.error().message;
}

std::string map_text(int width, int height, const std::string& rows) {
    return "type octile\nheight " + std::to_string(height) + "\nwidth " + std::to_string(width) +
           "\nmap\n" + rows;
}

} // namespace

TEST(MovingAiMap, FloorWallAndTreesAsWalls) {
    const ImportedMap map = parse_ok(all_chars_map);
    EXPECT_EQ(map.walls.width, 4);
    EXPECT_EQ(map.walls.height, 2);
    EXPECT_EQ(map.walls.origin, glm::ivec2(0, 0));
    EXPECT_EQ(map.walls.cells, (Cells{0, 0, 0, 0, 1, 1, 1, 1}));
    EXPECT_TRUE(map.trees.empty()); // walls: nothing kept per tree
}

// Trees as proxies cost memory each (a proxy, and a prop entity in the game): past the
// limit the map is refused at the first tree too many, whatever the file's size.
TEST(MovingAiMap, TreesAsProxiesAreBounded) {
    constexpr int width = 2048;
    const int height = int(max_map_tree_proxies / width) + 1;
    std::string rows;
    rows.reserve(std::size_t(width + 1) * std::size_t(height));
    for (int r = 0; r < height; ++r) rows.append(std::size_t(width), 'T').push_back('\n');
    const std::string text = map_text(width, height, rows);
    EXPECT_EQ(parse_error(text, {.trees = TreeMode::proxy, .extra_floor_chars = ""}),
              "m.map:" + std::to_string(4 + height) +
                  ":1: more than " + std::to_string(max_map_tree_proxies) +
                  " trees ('T' cells), the limit for trees as shadow proxies (each costs memory; docs/scenes.md, "
                  "\"Size limits\")");
    // As walls, the same map is fine.
    EXPECT_EQ(parse_ok(text).walls.cells.size(), std::size_t(width) * std::size_t(height));
}

TEST(MovingAiMap, TreesAsProxiesAreFloor) {
    const ImportedMap map =
        parse_ok(all_chars_map, {.trees = TreeMode::proxy, .extra_floor_chars = ""});
    EXPECT_EQ(map.walls.cells, (Cells{0, 0, 0, 0, 1, 0, 1, 0}));
    EXPECT_EQ(map.trees, (Trees{{1, 1}, {3, 1}}));
}

TEST(MovingAiMap, RowIsZAndColumnIsX) {
    const ImportedMap map = parse_ok(map_text(3, 2, "@..\n..@\n"));
    EXPECT_TRUE(map.walls.is_wall_tile(0, 0));
    EXPECT_FALSE(map.walls.is_wall_tile(2, 0));
    EXPECT_TRUE(map.walls.is_wall_tile(2, 1));
    EXPECT_FALSE(map.walls.is_wall_tile(0, 1));
}

TEST(MovingAiMap, AcceptsCrLfAndAMissingFinalNewlineAndTrailingBlankLines) {
    const Cells expected{0, 1, 1, 0};
    EXPECT_EQ(parse_ok("type octile\r\nheight 2\r\nwidth 2\r\nmap\r\n.@\r\n@.\r\n").walls.cells,
              expected);
    EXPECT_EQ(parse_ok(map_text(2, 2, ".@\n@.")).walls.cells, expected);
    EXPECT_EQ(parse_ok(map_text(2, 2, ".@\n@.\n\n\r\n")).walls.cells, expected);
}

// What editors write: a UTF-8 byte order mark, CRLF or lone-CR line ends (as the JSON
// reader accepts them). Messages name characters, not bytes, and quote hostile bytes
// escaped so the message stays one line.
TEST(MovingAiMap, ByteOrderMarkLineEndsAndQuotedCharacters) {
    for (const char* text : {"\xEF\xBB\xBFtype octile\nheight 1\nwidth 2\nmap\n.@\n",
                             "type octile\r\nheight 1\r\nwidth 2\r\nmap\r\n.@\r\n",
                             "type octile\rheight 1\rwidth 2\rmap\r.@\r"}) {
        const ImportedMap map = parse_ok(text);
        EXPECT_EQ(map.walls.cells, (Cells{0, 1})) << text;
    }
    EXPECT_EQ(parse_error(map_text(3, 1, ".\xC3\xA9.\n")),
              "m.map:5:2: unknown map character '\xC3\xA9' (U+00E9) (the Moving AI format has . G S W @ O T; list it in "
              "the scene's world.extra_floor_chars to read it as floor)");
    EXPECT_EQ(parse_error(map_text(3, 1, ".\x01.\n")).substr(0, 43), "m.map:5:2: unknown map character byte 0x01 ");
    const std::string header = parse_error("type oct\x01ile\xFF\nheight 1\nwidth 1\nmap\n.\n");
    EXPECT_NE(header.find("got 'type oct\\x01ile\\xFF'"), std::string::npos) << header;
    for (char c : header) EXPECT_TRUE(static_cast<unsigned char>(c) >= 0x20 && c != 0x7F) << header;
}

TEST(MovingAiMap, ExtraFloorCharsReadAsFloor) {
    const std::string text = map_text(3, 1, "s.t\n");
    EXPECT_EQ(parse_error(text), "m.map:5:1: unknown map character 's' (the Moving AI format has . "
                                 "G S W @ O T; list it in the "
                                 "scene's world.extra_floor_chars to read it as floor)");
    EXPECT_EQ(parse_ok(text, {.trees = TreeMode::wall, .extra_floor_chars = "st"}).walls.cells,
              (Cells{0, 0, 0}));
}

TEST(MovingAiMap, RejectsExtraFloorCharsThatAreNotExtra) {
    EXPECT_EQ(parse_error(all_chars_map, {.trees = TreeMode::wall, .extra_floor_chars = "@"}),
              "extra_floor_chars: '@' already has a meaning in Moving AI maps (. G S W @ O T)");
    EXPECT_EQ(parse_error(all_chars_map, {.trees = TreeMode::wall, .extra_floor_chars = "\n"}),
              "extra_floor_chars: byte 0x0A is not a printable ASCII character");
}

struct MapErrorCase {
    std::string text;
    std::string message;
};

void PrintTo(const MapErrorCase& c, std::ostream* os) {
    *os << c.text;
}

class MovingAiMapErrors : public testing::TestWithParam<MapErrorCase> {};

TEST_P(MovingAiMapErrors, NameTheFileLineAndColumn) {
    EXPECT_EQ(parse_error(GetParam().text), GetParam().message);
}

INSTANTIATE_TEST_SUITE_P(
    MovingAiMap, MovingAiMapErrors,
    testing::Values(
        MapErrorCase{
            "",
            "m.map:1:1: expected 'type octile' (Moving AI map header), found the end of the file"},
        MapErrorCase{"type hex\n",
                     "m.map:1:1: expected 'type octile' (Moving AI map header), got 'type hex'"},
        MapErrorCase{"type octile\nheight\n",
                     "m.map:2:1: expected 'height N' with N in 1..65536, got 'height'"},
        MapErrorCase{"type octile\nheight x\n",
                     "m.map:2:1: expected 'height N' with N in 1..65536, got 'height x'"},
        MapErrorCase{"type octile\nheight 0\n",
                     "m.map:2:1: expected 'height N' with N in 1..65536, got 'height 0'"},
        MapErrorCase{"type octile\nheight -2\n",
                     "m.map:2:1: expected 'height N' with N in 1..65536, got 'height -2'"},
        MapErrorCase{"type octile\nheight 2 \n",
                     "m.map:2:1: expected 'height N' with N in 1..65536, got 'height 2 '"},
        MapErrorCase{"type octile\nheight 65537\n",
                     "m.map:2:1: expected 'height N' with N in 1..65536, got 'height 65537'"},
        MapErrorCase{
            "type octile\nheight 99999999999999999999\n",
            "m.map:2:1: expected 'height N' with N in 1..65536, got 'height 99999999999999999999'"},
        MapErrorCase{"type octile\nwidth 2\nheight 2\n",
                     "m.map:2:1: expected 'height N' with N in 1..65536, got 'width 2'"},
        MapErrorCase{"type octile\nheight 2\n",
                     "m.map:3:1: expected 'width N' with N in 1..65536, found the end of the file"},
        MapErrorCase{"type octile\nheight 2\nwidth 2\n.@\n",
                     "m.map:4:1: expected 'map' (Moving AI map header), got '.@'"},
        MapErrorCase{
            "type octile\nheight 65536\nwidth 4097\nmap\n",
            "m.map:3:1: a map of 4097 x 65536 cells is above the limit of 268435456 cells"},
        MapErrorCase{map_text(2, 3, ".@\n@.\n"),
                     "m.map:7:1: expected 3 rows (the header's height), found 2"},
        MapErrorCase{map_text(2, 1, ".@\n@.\n"),
                     "m.map:6:1: more than 1 rows (the header's height)"},
        MapErrorCase{map_text(3, 2, "...\n..\n"),
                     "m.map:6:3: row has 2 characters, expected 3 (the header's width)"},
        MapErrorCase{map_text(3, 2, "...\n....\n"),
                     "m.map:6:4: row has 4 characters, expected 3 (the header's width)"},
        MapErrorCase{map_text(3, 2, "...\n.#.\n"),
                     "m.map:6:2: unknown map character '#' (the Moving AI format has . G S W @ O "
                     "T; list it in "
                     "the scene's world.extra_floor_chars to read it as floor)"},
        // A lone CR ends a line (old Mac line ends), so this row is two rows.
        MapErrorCase{map_text(3, 1, "..\r.\n"), "m.map:5:3: row has 2 characters, expected 3 (the header's width)"},
        MapErrorCase{std::string("type octile\nheight ") + std::string(100, '1') + "\n",
                     "m.map:2:1: expected 'height N' with N in 1..65536, got 'height "
                     "111111111111111111111111111111111...'"}));

TEST(MovingAiMap, EveryTruncationFailsUnlessAllRowsAreThere) {
    const std::string text = map_text(3, 3, "@.T\n.G.\nS.@\n");
    const std::size_t last_row_complete = text.size() - 1; // all but the final newline
    for (std::size_t length = 0; length < text.size(); ++length) {
        auto result = parse_moving_ai_map(std::string_view(text).substr(0, length), "m.map", {});
        EXPECT_EQ(result.ok(), length >= last_row_complete) << "length " << length;
        if (!result.ok()) {
            EXPECT_TRUE(result.error().message.starts_with("m.map:")) << result.error().message;
        }
    }
}

TEST(MovingAiMap, ImportsAFileAndNamesItInErrors) {
    TempDir dir;
    std::ofstream(dir.file("good.map"), std::ios::binary) << all_chars_map;
    auto map = import_moving_ai_map(dir.file("good.map"));
    ASSERT_TRUE(map.ok()) << map.error().message;
    EXPECT_EQ(map->walls.cells, (Cells{0, 0, 0, 0, 1, 1, 1, 1}));

    std::ofstream(dir.file("bad.map"), std::ios::binary) << map_text(2, 1, ".x\n");
    auto bad = import_moving_ai_map(dir.file("bad.map"));
    ASSERT_FALSE(bad.ok());
    EXPECT_TRUE(
        bad.error().message.starts_with(dir.file("bad.map") + ":5:2: unknown map character 'x'"));

    auto missing = import_moving_ai_map(dir.file("missing.map"));
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().message,
              dir.file("missing.map") + ": cannot open: No such file or directory");
    EXPECT_EQ(missing.error().exit_code, 2);
}

// The eight Dragon Age: Origins maps of ../shared/maps/dao, with their published sizes and
// the 'T' count from the files (counted independently with `tail -n +5 | fold -w1 | sort | uniq
// -c`).
struct RealMap {
    const char* file;
    int width;
    int height;
    std::size_t trees;
    std::size_t walls_without_trees; // '@' and 'O'
};

class RealMaps : public testing::TestWithParam<RealMap> {};

TEST_P(RealMaps, ImportWithTheirDocumentedSizes) {
    const auto shared = lantern::test::shared_dir();
    if (shared.empty()) GTEST_SKIP() << "../shared is absent";
    const RealMap& expected = GetParam();
    const MapImportOptions options{.trees = TreeMode::proxy, .extra_floor_chars = "st"};
    auto map = import_moving_ai_map((shared / "maps/dao" / expected.file).string(), options);
    ASSERT_TRUE(map.ok()) << map.error().message;
    EXPECT_EQ(map->walls.width, expected.width);
    EXPECT_EQ(map->walls.height, expected.height);
    ASSERT_EQ(map->walls.cells.size(), std::size_t(expected.width) * std::size_t(expected.height));
    EXPECT_EQ(map->trees.size(), expected.trees);
    const auto walls = std::size_t(std::count(map->walls.cells.begin(), map->walls.cells.end(), 1));
    EXPECT_EQ(walls, expected.walls_without_trees);
}

INSTANTIATE_TEST_SUITE_P(Dao, RealMaps,
                         testing::Values(RealMap{"lak102d.map", 38, 30, 428, 193},
                                         RealMap{"den101d.map", 73, 41, 1071, 562},
                                         RealMap{"arena.map", 49, 49, 347, 0},
                                         RealMap{"den312d.map", 65, 81, 2565, 255},
                                         RealMap{"lak303d.map", 194, 194, 8687, 14165},
                                         RealMap{"den520d.map", 256, 257, 29707, 7907},
                                         RealMap{"brc202d.map", 530, 481, 17883, 193896},
                                         RealMap{"orz700d.map", 1104, 1260, 36401, 1259039}),
                         [](const testing::TestParamInfo<RealMap>& test) {
                             std::string name = test.param.file;
                             return name.substr(0, name.find('.'));
                         });

TEST(MovingAiMap, ArenaNeedsExtraFloorCharsAndSaysWhere) {
    const auto shared = lantern::test::shared_dir();
    if (shared.empty()) GTEST_SKIP() << "../shared is absent";
    const std::string path = (shared / "maps/dao/arena.map").string();
    auto map = import_moving_ai_map(path);
    ASSERT_FALSE(map.ok());
    // Line 6 (the first row) starts "TTTs".
    EXPECT_EQ(map.error().message,
              path + ":6:4: unknown map character 's' (the Moving AI format has . G S W @ O "
                     "T; list it in the scene's world.extra_floor_chars to read it as floor)");
}

// The example maps every clone has (game/maps/, made by scripts/make-example-maps.py).
TEST(MovingAiMap, ShippedExampleMapsImport) {
    struct Shipped {
        const char* file;
        int width, height;
    };
    for (const Shipped& m : {Shipped{"keep.map", 64, 48}, Shipped{"caverns.map", 192, 192}}) {
        auto map = import_moving_ai_map(std::string(LANTERN_SOURCE_DIR) + "/game/maps/" + m.file,
                                        {.trees = TreeMode::proxy, .extra_floor_chars = ""});
        ASSERT_TRUE(map.ok()) << map.error().message;
        EXPECT_EQ(map->walls.width, m.width) << m.file;
        EXPECT_EQ(map->walls.height, m.height) << m.file;
        EXPECT_FALSE(map->trees.empty()) << m.file;
        const auto floor = std::count(map->walls.cells.begin(), map->walls.cells.end(), 0);
        EXPECT_GT(floor, m.width * m.height / 4) << m.file << ": mostly walls";
    }
}
