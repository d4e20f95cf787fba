#include "lantern/core/json.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

using lantern::json::Position;
using lantern::json::Type;
using lantern::json::Value;

namespace {

Value parse_ok(std::string_view text) {
    auto result = lantern::json::parse(text, "t.json");
    EXPECT_TRUE(result.ok()) << result.error().message;
    return result.ok() ? *result : Value();
}

std::string parse_error(std::string_view text) {
    auto result = lantern::json::parse(text, "t.json");
    if (result.ok()) return "(parsed)";
    EXPECT_EQ(result.error().exit_code, 2);
    return result.error().message;
}

} // namespace

TEST(Json, ParsesEveryTypeWithPositions) {
    const Value root = parse_ok("{\n"
                                "  \"n\": null, \"t\": true, \"f\": false,\n"
                                "  \"num\": -12.5e1,\n"
                                "  \"s\": \"hi\",\n"
                                "  \"a\": [1, [], {}]\n"
                                "}");
    ASSERT_TRUE(root.is_object());
    EXPECT_EQ(root.position(), (Position{1, 1}));
    const Value::Object& members = root.as_object();
    ASSERT_EQ(members.size(), 6u);
    const char* keys[] = {"n", "t", "f", "num", "s", "a"};
    for (std::size_t i = 0; i < members.size(); ++i) EXPECT_EQ(members[i].key, keys[i]);
    EXPECT_EQ(members[0].key_position, (Position{2, 3}));
    EXPECT_EQ(members[2].key_position, (Position{2, 25}));

    EXPECT_TRUE(members[0].value.is_null());
    EXPECT_EQ(members[0].value.position(), (Position{2, 8}));
    EXPECT_TRUE(members[1].value.as_bool());
    EXPECT_FALSE(members[2].value.as_bool());
    EXPECT_EQ(members[3].value.as_number(), -125.0);
    EXPECT_EQ(members[3].value.position(), (Position{3, 10}));
    EXPECT_EQ(members[4].value.as_string(), "hi");
    EXPECT_EQ(members[4].value.position(), (Position{4, 8}));

    const Value::Array& items = members[5].value.as_array();
    ASSERT_EQ(items.size(), 3u);
    EXPECT_EQ(items[0].as_number(), 1.0);
    EXPECT_EQ(items[0].position(), (Position{5, 9}));
    EXPECT_TRUE(items[1].is_array());
    EXPECT_TRUE(items[1].as_array().empty());
    EXPECT_EQ(items[1].position(), (Position{5, 12}));
    EXPECT_TRUE(items[2].is_object());
    EXPECT_EQ(items[2].position(), (Position{5, 16}));
}

TEST(Json, FindReturnsMembersByKey) {
    const Value root = parse_ok(R"({"b": 1, "a": 2})");
    ASSERT_NE(root.find("a"), nullptr);
    EXPECT_EQ(root.find("a")->as_number(), 2.0);
    EXPECT_EQ(root.find("b")->as_number(), 1.0);
    EXPECT_EQ(root.find("c"), nullptr);
    EXPECT_EQ(root.as_object()[0].key, "b"); // insertion order, not sorted
}

TEST(Json, RemembersIntegerLiterals) {
    const Value root = parse_ok("[12, -3, 0, -0, 12.0, 1e3, 1.5]");
    const bool expected[] = {true, true, true, true, false, false, false};
    const Value::Array& items = root.as_array();
    ASSERT_EQ(items.size(), std::size(expected));
    for (std::size_t i = 0; i < items.size(); ++i)
        EXPECT_EQ(items[i].is_integer_literal(), expected[i]) << i;
    EXPECT_EQ(items[5].as_number(), 1000.0);
}

TEST(Json, NumbersAtTheLimitsOfDouble) {
    EXPECT_EQ(parse_ok("1.7976931348623157e308").as_number(), 1.7976931348623157e308);
    EXPECT_EQ(parse_ok("-1.7976931348623157e308").as_number(), -1.7976931348623157e308);
    EXPECT_EQ(parse_ok("4e-320").as_number(), 4e-320); // subnormal
    EXPECT_EQ(parse_ok("1e-400").as_number(), 0.0);    // underflow becomes 0
    EXPECT_EQ(parse_ok("0.0000000001e-395").as_number(), 0.0);
}

TEST(Json, NumbersAboveDoubleAreErrors) {
    EXPECT_EQ(parse_error("1e309"), "t.json:1:1: number out of range");
    EXPECT_EQ(parse_error("[0, -1e400]"), "t.json:1:5: number out of range");
    EXPECT_EQ(parse_error("1e99999999999999999999"), "t.json:1:1: number out of range");
    EXPECT_EQ(parse_error("0.001e312"), "t.json:1:1: number out of range");
}

TEST(Json, DecodesEscapes) {
    EXPECT_EQ(parse_ok(R"("\"\\\/\b\f\n\r\t")").as_string(), "\"\\/\b\f\n\r\t");
    EXPECT_EQ(parse_ok(R"("\u0041\u00e9\u20AC")").as_string(), "A\xC3\xA9\xE2\x82\xAC");
    EXPECT_EQ(parse_ok(R"("\ud83d\ude00")").as_string(), "\xF0\x9F\x98\x80"); // surrogate pair
    EXPECT_EQ(parse_ok(R"("\u0000")").as_string(), std::string(1, '\0'));
}

TEST(Json, KeepsRawUtf8AndCountsColumnsInCodePoints) {
    const Value root = parse_ok("[\"\xC3\xA9\xF0\x9F\x98\x80\", 1]");
    EXPECT_EQ(root.as_array()[0].as_string(), "\xC3\xA9\xF0\x9F\x98\x80");
    EXPECT_EQ(root.as_array()[1].position(), (Position{1, 8}));
    EXPECT_EQ(parse_error("[\"\xC3\xA9\", x]"), "t.json:1:7: expected a value, found 'x'");
}

TEST(Json, SkipsLeadingByteOrderMark) {
    EXPECT_EQ(parse_ok("\xEF\xBB\xBF[1]").as_array().size(), 1u);
    EXPECT_EQ(parse_error("\xEF\xBB\xBF[x]"), "t.json:1:2: expected a value, found 'x'");
}

TEST(Json, AcceptsAllJsonWhitespaceOnly) {
    EXPECT_TRUE(parse_ok(" \t\r\n[ \t\r\n1 \t\r\n] \t\r\n").is_array());
    EXPECT_EQ(parse_error("\v1"), "t.json:1:1: expected a value, found U+000B");
    EXPECT_EQ(parse_error("\f1"), "t.json:1:1: expected a value, found U+000C");
}

struct ErrorCase {
    const char* text;
    const char* message;
};

class JsonErrors : public testing::TestWithParam<ErrorCase> {};

TEST_P(JsonErrors, ReportFileLineColumnAndWhat) {
    EXPECT_EQ(parse_error(GetParam().text), GetParam().message) << "input: " << GetParam().text;
}

INSTANTIATE_TEST_SUITE_P(
    Json, JsonErrors,
    testing::Values(
        ErrorCase{"", "t.json:1:1: unexpected end of input, expected a value"},
        ErrorCase{"\n\n  [", "t.json:3:4: unexpected end of input, expected a value"},
        ErrorCase{"[1,]", "t.json:1:4: expected a value, found ']'"},
        ErrorCase{"{\"a\": 1,}", "t.json:1:9: expected a string key, found '}'"},
        ErrorCase{"{1: 2}", "t.json:1:2: expected a string key, found '1'"},
        ErrorCase{"{'a': 2}", "t.json:1:2: expected a string key, found '''"},
        ErrorCase{"{\"a\" 1}", "t.json:1:6: expected ':' after the key, found '1'"},
        ErrorCase{"{\"a\": 1 \"b\": 2}",
                  "t.json:1:9: expected ',' or '}' after an object member, found '\"'"},
        ErrorCase{"[1 2]", "t.json:1:4: expected ',' or ']' after an array element, found '2'"},
        ErrorCase{
            "[1",
            "t.json:1:3: unexpected end of input, expected ',' or ']' after an array element"},
        ErrorCase{"{\"a\": 1, \"a\": 2}", "t.json:1:10: duplicate key 'a'"},
        ErrorCase{"// comment\n1", "t.json:1:1: expected a value, found '/'"},
        ErrorCase{"[1] /* c */", "t.json:1:5: unexpected '/' after the JSON value"},
        ErrorCase{"1 2", "t.json:1:3: unexpected '2' after the JSON value"},
        ErrorCase{"01", "t.json:1:2: leading zeros are not allowed in numbers"},
        ErrorCase{"-", "t.json:1:2: unexpected end of input, expected a digit"},
        ErrorCase{"-a", "t.json:1:2: expected a digit, found 'a'"},
        ErrorCase{"+1", "t.json:1:1: expected a value, found '+'"},
        ErrorCase{".5", "t.json:1:1: expected a value, found '.'"},
        ErrorCase{"1.",
                  "t.json:1:3: unexpected end of input, expected a digit after the decimal point"},
        ErrorCase{"1.e5", "t.json:1:3: expected a digit after the decimal point, found 'e'"},
        ErrorCase{"1e", "t.json:1:3: unexpected end of input, expected a digit in the exponent"},
        ErrorCase{"1e+", "t.json:1:4: unexpected end of input, expected a digit in the exponent"},
        ErrorCase{"NaN", "t.json:1:1: expected a value, found 'N'"},
        ErrorCase{"-Infinity", "t.json:1:2: expected a digit, found 'I'"},
        ErrorCase{"tru", "t.json:1:1: invalid literal, expected 'true'"},
        ErrorCase{"nul", "t.json:1:1: invalid literal, expected 'null'"},
        ErrorCase{"True", "t.json:1:1: expected a value, found 'T'"},
        ErrorCase{"\"abc", "t.json:1:1: unterminated string"},
        ErrorCase{"\"a\nb\"",
                  "t.json:1:3: U+000A (a control character) inside a string; escape it"},
        ErrorCase{"\"a\tb\"",
                  "t.json:1:3: U+0009 (a control character) inside a string; escape it"},
        ErrorCase{"\"\\x\"", "t.json:1:2: invalid escape sequence '\\x'"},
        ErrorCase{"\"\\", "t.json:1:3: unexpected end of input, expected an escape character"},
        ErrorCase{"\"\\u12\"", "t.json:1:6: expected 4 hex digits after \\u, found '\"'"},
        ErrorCase{"\"\\u12",
                  "t.json:1:6: unexpected end of input, expected 4 hex digits after \\u"},
        ErrorCase{"\"\\ud800\"", "t.json:1:2: unpaired high surrogate in a \\u escape"},
        ErrorCase{"\"\\ud800\\u0041\"", "t.json:1:2: unpaired high surrogate in a \\u escape"},
        ErrorCase{"\"\\udc00\"", "t.json:1:2: unpaired low surrogate in a \\u escape"},
        ErrorCase{"\"\xFF\"", "t.json:1:2: invalid UTF-8 (byte 0xFF) in a string"},
        ErrorCase{"\"\xC0\xAF\"", "t.json:1:2: invalid UTF-8 (byte 0xC0) in a string"}, // overlong
        ErrorCase{"\"\xED\xA0\x80\"",
                  "t.json:1:2: invalid UTF-8 (byte 0xED) in a string"}, // surrogate
        ErrorCase{"\"\xF4\x90\x80\x80\"",
                  "t.json:1:2: invalid UTF-8 (byte 0xF4) in a string"}, // > U+10FFFF
        ErrorCase{"\"\xE2\x82\"", "t.json:1:2: invalid UTF-8 (byte 0xE2) in a string"}, // truncated
        ErrorCase{"\xC3\xA9", "t.json:1:1: expected a value, found byte 0xC3"}));

TEST(Json, LongKeysAreCutShortInMessages) {
    const std::string key(100, 'k');
    EXPECT_EQ(parse_error("{\"" + key + "\": 1, \"" + key + "\": 2}"),
              "t.json:1:109: duplicate key '" + std::string(40, 'k') + "...'");
}

TEST(Json, NestingUpToTheLimitParses) {
    const std::string text =
        std::string(lantern::json::max_depth, '[') + std::string(lantern::json::max_depth, ']');
    EXPECT_TRUE(parse_ok(text).is_array());
}

TEST(Json, NestingBeyondTheLimitIsAnError) {
    const int depth = lantern::json::max_depth + 1;
    EXPECT_EQ(parse_error(std::string(depth, '[') + std::string(depth, ']')),
              "t.json:1:257: nesting deeper than 256 levels");
    EXPECT_EQ(parse_error(std::string(1'000'000, '[')),
              "t.json:1:257: nesting deeper than 256 levels");
    std::string objects;
    for (int i = 0; i < depth; ++i) objects += "{\"a\":";
    EXPECT_EQ(parse_error(objects), "t.json:1:1281: nesting deeper than 256 levels");
}

TEST(Json, EveryTruncationFailsWithoutCrashing) {
    const std::string text =
        R"({"a": [1, -2.5e-3, true, false, null], "b": {"c": "\u00e9\ud83d\ude00\n"}})";
    ASSERT_TRUE(lantern::json::parse(text, "t.json").ok());
    for (std::size_t length = 0; length < text.size(); ++length) {
        auto result = lantern::json::parse(std::string_view(text).substr(0, length), "t.json");
        EXPECT_FALSE(result.ok()) << "prefix of length " << length;
        if (!result.ok()) {
            EXPECT_TRUE(result.error().message.starts_with("t.json:1:")) << result.error().message;
        }
    }
}

TEST(Json, DescribeNamesEveryType) {
    EXPECT_STREQ(lantern::json::describe(Type::null), "null");
    EXPECT_STREQ(lantern::json::describe(Type::boolean), "a boolean");
    EXPECT_STREQ(lantern::json::describe(Type::number), "a number");
    EXPECT_STREQ(lantern::json::describe(Type::string), "a string");
    EXPECT_STREQ(lantern::json::describe(Type::array), "an array");
    EXPECT_STREQ(lantern::json::describe(Type::object), "an object");
}
