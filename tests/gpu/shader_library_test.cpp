// lantern_add_shader_library: the embedded words are the compiled .spv files.
#include "lantern_test_shaders.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

namespace {

std::vector<std::uint32_t> read_spv(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::uint32_t> words(bytes.size() / 4);
    std::memcpy(words.data(), bytes.data(), words.size() * 4);
    return words;
}

} // namespace

TEST(ShaderLibrary, EmbeddedWordsEqualTheCompiledFiles) {
    const auto names = lantern_test_shaders_names();
    ASSERT_GE(names.size(), 3u);
    for (std::string_view name : names) {
        SCOPED_TRACE(std::string(name));
        const auto words = lantern_test_shaders_spirv(name);
        ASSERT_GT(words.size(), 5u);
        EXPECT_EQ(words[0], 0x07230203u);
        const auto file = read_spv(std::string(LANTERN_TEST_SHADER_DIR) + "/" + std::string(name) + ".spv");
        EXPECT_TRUE(std::equal(words.begin(), words.end(), file.begin(), file.end()));
    }
}

TEST(ShaderLibrary, NamesAreFileNamesWithoutGlslAndUnknownNamesAreEmpty) {
    const auto names = lantern_test_shaders_names();
    EXPECT_NE(std::find(names.begin(), names.end(), "test_fill.comp"), names.end());
    EXPECT_FALSE(lantern_test_shaders_spirv("test_fill.comp").empty());
    EXPECT_TRUE(lantern_test_shaders_spirv("test_fill").empty());
    EXPECT_TRUE(lantern_test_shaders_spirv("").empty());
    EXPECT_TRUE(lantern_test_shaders_spirv("no_such_shader.comp").empty());
}
