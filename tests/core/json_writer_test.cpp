// json::Writer: what it writes reads back with json::parse, whatever the strings hold.
#include "lantern/core/json.hpp"
#include "lantern/core/json_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace lantern {
namespace {

TEST(JsonWriter, LinesAndOneLineLayouts) {
    json::Writer w;
    w.begin_object().field("name", "cave").field("frames", 600).field("on", true);
    w.key("p").begin_array(json::Layout::one_line).value(1.5).value(-2).end();
    w.key("rows").begin_array();
    w.begin_object(json::Layout::one_line).field("a", 1).key("b").begin_array().value(2).end().end();
    w.end();
    w.key("empty").begin_object().end();
    w.end();
    EXPECT_EQ(w.take(), "{\n"
                        "  \"name\": \"cave\",\n"
                        "  \"frames\": 600,\n"
                        "  \"on\": true,\n"
                        "  \"p\": [1.5, -2],\n"
                        "  \"rows\": [\n"
                        "    {\"a\": 1, \"b\": [2]}\n"
                        "  ],\n"
                        "  \"empty\": {}\n"
                        "}\n");
}

TEST(JsonWriter, StringsAreEscapedAndReadBack) {
    // Quotes, backslashes, every control character, UTF-8 kept, bytes that are not UTF-8.
    std::string hostile = "q\"b\\ n\n t\t r\r b\b f\f x\x01 y\x1f é € 😀";
    const std::string invalid = "a\xff" "b\xc3" "c\xed\xa0\x80";
    json::Writer w;
    w.begin_array().value(hostile).value(invalid).end();
    const std::string text = w.take();
    EXPECT_NE(text.find("\\u0001"), std::string::npos) << text;
    EXPECT_NE(text.find("\\n"), std::string::npos) << text;
    auto parsed = json::parse(text, "test");
    ASSERT_TRUE(parsed) << parsed.error().message << "\n" << text;
    EXPECT_EQ(parsed->as_array()[0].as_string(), hostile);
    // Each byte that starts no UTF-8 character becomes U+FFFD (EF BF BD).
    EXPECT_EQ(parsed->as_array()[1].as_string(),
              "a\xef\xbf\xbd" "b\xef\xbf\xbd" "c\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd");
    EXPECT_EQ(json::quoted("a\"b"), "\"a\\\"b\"");
}

TEST(JsonWriter, NumbersAreShortestExactOrFixedAndNeverNaN) {
    json::Writer w;
    w.begin_array(json::Layout::one_line)
        .value(0.1f)
        .value(0.1)
        .value(1e300)
        .value(std::numeric_limits<double>::quiet_NaN())
        .value(std::numeric_limits<float>::infinity())
        .value(12.34567, 3)
        .value(std::int64_t(-9007199254740993))
        .value(std::uint8_t(7))
        .end();
    const std::string text = w.take();
    EXPECT_EQ(text, "[0.1, 0.1, 1e+300, null, null, 12.346, -9007199254740993, 7]\n");
    auto parsed = json::parse(text, "test");
    ASSERT_TRUE(parsed) << parsed.error().message;
    EXPECT_EQ(float(parsed->as_array()[0].as_number()), 0.1f); // reads back as the same float
    EXPECT_EQ(parsed->as_array()[1].as_number(), 0.1);
}

TEST(JsonWriterDeathTest, MisuseAsserts) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            json::Writer w;
            w.begin_object().value(1);
        },
        "without a key");
    EXPECT_DEATH(
        {
            json::Writer w;
            w.begin_array();
            (void)w.take();
        },
        "containers open");
    EXPECT_DEATH(
        {
            json::Writer w;
            w.end();
        },
        "nothing open");
}

} // namespace
} // namespace lantern
