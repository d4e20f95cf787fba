// Helpers shared by the scene suites: parsing scene text that must load or must fail.
#pragma once

#include "lantern/scene/loader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

namespace lantern::test {

inline scene::Scene parse_scene_ok(std::string_view text, const std::string& base_dir = "") {
    auto result = scene::parse_scene(text, "t.json", base_dir);
    EXPECT_TRUE(result.ok()) << result.error().message;
    return result.ok() ? *result : scene::Scene{};
}

// The error message, or "(loaded)" when the scene loaded; every failure must exit with 2.
inline std::string parse_scene_error(std::string_view text, const std::string& base_dir = "") {
    auto result = scene::parse_scene(text, "t.json", base_dir);
    if (result.ok()) return "(loaded)";
    EXPECT_EQ(result.error().exit_code, 2);
    return result.error().message;
}

// A minimal valid scene whose second line is `line2` (a member of the top-level object),
// so that cases can state line 2 columns by counting in `line2` alone.
inline std::string scene_with(std::string_view line2) {
    return "{\"lantern_scene\": 1, \"world\": {\"rows\": [\"#.\"]}, \"view\": {\"center\": [0, "
           "0]},\n" +
           std::string(line2) + "}";
}

} // namespace lantern::test
