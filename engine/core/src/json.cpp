#include "lantern/core/json.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <optional>
#include <unordered_set>

namespace lantern::json {
namespace {

bool is_digit(char c) {
    return c >= '0' && c <= '9';
}

bool is_whitespace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// UTF-8 continuation bytes do not start a new column.
bool is_continuation_byte(char c) {
    return (static_cast<unsigned char>(c) & 0xC0) == 0x80;
}

// Length of the valid UTF-8 sequence at the start of `s`, or 0 when it is not one
// (overlong forms, encoded surrogates and code points above U+10FFFF are invalid).
std::size_t utf8_sequence_length(std::string_view s) {
    auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
    auto in = [](unsigned char b, unsigned lo, unsigned hi) { return b >= lo && b <= hi; };
    const unsigned char b0 = byte(0);
    if (b0 < 0x80) return 1;
    std::size_t length = b0 >= 0xF0 ? 4 : b0 >= 0xE0 ? 3 : 2;
    if (s.size() < length) return 0;
    // The second byte's allowed range depends on the lead byte (Unicode table 3-7).
    unsigned lo = 0x80, hi = 0xBF;
    if (b0 == 0xE0)
        lo = 0xA0;
    else if (b0 == 0xED)
        hi = 0x9F;
    else if (b0 == 0xF0)
        lo = 0x90;
    else if (b0 == 0xF4)
        hi = 0x8F;
    else if (b0 < 0xC2 || b0 > 0xF4)
        return 0;
    if (!in(byte(1), lo, hi)) return 0;
    for (std::size_t i = 2; i < length; ++i)
        if (!in(byte(i), 0x80, 0xBF)) return 0;
    return length;
}

void append_utf8(std::string& out, std::uint32_t code_point) {
    auto put = [&](std::uint32_t bits) { out.push_back(static_cast<char>(bits)); };
    if (code_point < 0x80) {
        put(code_point);
    } else if (code_point < 0x800) {
        put(0xC0 | (code_point >> 6));
        put(0x80 | (code_point & 0x3F));
    } else if (code_point < 0x10000) {
        put(0xE0 | (code_point >> 12));
        put(0x80 | ((code_point >> 6) & 0x3F));
        put(0x80 | (code_point & 0x3F));
    } else {
        put(0xF0 | (code_point >> 18));
        put(0x80 | ((code_point >> 12) & 0x3F));
        put(0x80 | ((code_point >> 6) & 0x3F));
        put(0x80 | (code_point & 0x3F));
    }
}

// The character at the start of `rest` as messages quote it: 'x' when printable ASCII,
// U+XXXX for other ASCII, byte 0xNN for the first byte of anything else.
std::string quote_char(std::string_view rest) {
    char buffer[16];
    const unsigned char c = static_cast<unsigned char>(rest[0]);
    if (c >= 0x20 && c < 0x7F)
        std::snprintf(buffer, sizeof(buffer), "'%c'", c);
    else if (c < 0x80)
        std::snprintf(buffer, sizeof(buffer), "U+%04X", c);
    else
        std::snprintf(buffer, sizeof(buffer), "byte 0x%02X", c);
    return buffer;
}

// A key as messages quote it, cut short so that hostile input cannot flood the terminal.
std::string quote_key(std::string_view key) {
    constexpr std::size_t max_quoted = 40;
    if (key.size() <= max_quoted) return "'" + std::string(key) + "'";
    std::size_t cut = max_quoted;
    while (cut > 0 && is_continuation_byte(key[cut])) --cut; // keep whole UTF-8 sequences
    return "'" + std::string(key.substr(0, cut)) + "...'";
}

// Digit counts of a number literal, kept so that an out-of-range result can be classified
// as overflow (an error) or underflow (becomes 0) without a second parse.
struct NumberShape {
    int integer_digits = 0; // significant digits before the point (leading zeros skipped)
    int fraction_zeros = 0; // zeros after the point before the first non-zero digit
    bool fraction_nonzero = false;
    long exponent = 0; // saturated at +-1e9
    bool integer_literal = true;
};

// Decimal exponent of the leading significant digit; >= 0 means |value| >= 1.
long magnitude(const NumberShape& shape) {
    if (shape.integer_digits > 0) return shape.exponent + shape.integer_digits - 1;
    return shape.exponent - shape.fraction_zeros - 1;
}

class Parser {
  public:
    Parser(std::string_view text, const std::string& file_name) : text_(text), file_(file_name) {}

    Result<Value> run() {
        if (text_.starts_with("\xEF\xBB\xBF")) pos_ = 3;
        Value root;
        if (!parse_value(root, 0)) return *error_;
        skip_whitespace();
        if (!at_end()) {
            fail("unexpected " + quote_char(rest()) + " after the JSON value");
            return *error_;
        }
        return root;
    }

  private:
    bool at_end() const { return pos_ >= text_.size(); }
    char peek() const { return text_[pos_]; }
    std::string_view rest() const { return text_.substr(pos_); }
    Position here() const { return {line_, column_}; }

    void advance(std::size_t bytes = 1) {
        for (std::size_t end = pos_ + bytes; pos_ < end; ++pos_) {
            if (text_[pos_] == '\n') {
                ++line_;
                column_ = 1;
            } else if (!is_continuation_byte(text_[pos_])) {
                ++column_;
            }
        }
    }

    bool fail_at(Position at, const std::string& what) {
        if (!error_)
            error_ = make_error(file_ + ":" + std::to_string(at.line) + ":" +
                                std::to_string(at.column) + ": " + what);
        return false;
    }
    bool fail(const std::string& what) { return fail_at(here(), what); }
    bool fail_unexpected(const char* expected) {
        if (at_end()) return fail(std::string("unexpected end of input, expected ") + expected);
        return fail("expected " + std::string(expected) + ", found " + quote_char(rest()));
    }

    void skip_whitespace() {
        while (!at_end() && is_whitespace(peek())) advance();
    }

    bool consume(char c) {
        if (at_end() || peek() != c) return false;
        advance();
        return true;
    }

    bool parse_value(Value& out, int depth) {
        skip_whitespace();
        if (at_end()) return fail_unexpected("a value");
        switch (peek()) {
        case '{':
            return parse_object(out, depth + 1);
        case '[':
            return parse_array(out, depth + 1);
        case '"':
            return parse_string_value(out);
        case 't':
            return parse_literal("true", Value(true, here()), out);
        case 'f':
            return parse_literal("false", Value(false, here()), out);
        case 'n':
            return parse_literal("null", Value(nullptr, here()), out);
        default:
            if (peek() == '-' || is_digit(peek())) return parse_number(out);
            return fail_unexpected("a value");
        }
    }

    bool parse_literal(std::string_view word, Value value, Value& out) {
        if (!rest().starts_with(word))
            return fail("invalid literal, expected '" + std::string(word) + "'");
        advance(word.size());
        out = std::move(value);
        return true;
    }

    bool enter(int depth) {
        if (depth > max_depth)
            return fail("nesting deeper than " + std::to_string(max_depth) + " levels");
        return true;
    }

    bool parse_array(Value& out, int depth) {
        const Position start = here();
        if (!enter(depth)) return false;
        advance(); // '['
        Value::Array items;
        skip_whitespace();
        if (!consume(']')) {
            do {
                items.emplace_back();
                if (!parse_value(items.back(), depth)) return false;
                skip_whitespace();
            } while (consume(','));
            if (!consume(']')) return fail_unexpected("',' or ']' after an array element");
        }
        out = Value(std::move(items), start);
        return true;
    }

    bool parse_object(Value& out, int depth) {
        const Position start = here();
        if (!enter(depth)) return false;
        advance(); // '{'
        Value::Object members;
        std::unordered_set<std::string> keys;
        skip_whitespace();
        if (!consume('}')) {
            do {
                skip_whitespace();
                if (!parse_member(members, keys, depth)) return false;
                skip_whitespace();
            } while (consume(','));
            if (!consume('}')) return fail_unexpected("',' or '}' after an object member");
        }
        out = Value(std::move(members), start);
        return true;
    }

    bool parse_member(Value::Object& members, std::unordered_set<std::string>& keys, int depth) {
        if (at_end() || peek() != '"') return fail_unexpected("a string key");
        Member member;
        member.key_position = here();
        if (!parse_string(member.key)) return false;
        if (!keys.insert(member.key).second)
            return fail_at(member.key_position, "duplicate key " + quote_key(member.key));
        skip_whitespace();
        if (!consume(':')) return fail_unexpected("':' after the key");
        if (!parse_value(member.value, depth)) return false;
        members.push_back(std::move(member));
        return true;
    }

    bool parse_string_value(Value& out) {
        const Position start = here();
        std::string s;
        if (!parse_string(s)) return false;
        out = Value(std::move(s), start);
        return true;
    }

    bool parse_string(std::string& out) {
        const Position start = here();
        advance(); // opening quote
        while (!at_end()) {
            const char c = peek();
            if (c == '"') {
                advance();
                return true;
            }
            if (c == '\\') {
                if (!parse_escape(out)) return false;
            } else if (static_cast<unsigned char>(c) < 0x20) {
                return fail(quote_char(rest()) + " (a control character) inside a string; "
                                                 "escape it");
            } else {
                const std::size_t length = utf8_sequence_length(rest());
                if (length == 0)
                    return fail("invalid UTF-8 (" + quote_char(rest()) + ") in a string");
                out.append(text_.substr(pos_, length));
                advance(length);
            }
        }
        return fail_at(start, "unterminated string");
    }

    bool parse_escape(std::string& out) {
        const Position start = here();
        advance(); // backslash
        if (at_end()) return fail_unexpected("an escape character");
        const char c = peek();
        advance();
        switch (c) {
        case '"':
            out.push_back('"');
            return true;
        case '\\':
            out.push_back('\\');
            return true;
        case '/':
            out.push_back('/');
            return true;
        case 'b':
            out.push_back('\b');
            return true;
        case 'f':
            out.push_back('\f');
            return true;
        case 'n':
            out.push_back('\n');
            return true;
        case 'r':
            out.push_back('\r');
            return true;
        case 't':
            out.push_back('\t');
            return true;
        case 'u':
            return parse_unicode_escape(start, out);
        default:
            return fail_at(start, "invalid escape sequence '\\" + std::string(1, c) + "'");
        }
    }

    // After "\u": four hex digits, and for a high surrogate the "\uDC00".."\uDFFF" that
    // must follow it.
    bool parse_unicode_escape(Position start, std::string& out) {
        std::uint32_t unit = 0;
        if (!parse_hex4(unit)) return false;
        if (unit >= 0xDC00 && unit <= 0xDFFF)
            return fail_at(start, "unpaired low surrogate in a \\u escape");
        if (unit >= 0xD800 && unit <= 0xDBFF) {
            std::uint32_t low = 0;
            if (!rest().starts_with("\\u"))
                return fail_at(start, "unpaired high surrogate in a \\u escape");
            advance(2);
            if (!parse_hex4(low)) return false;
            if (low < 0xDC00 || low > 0xDFFF)
                return fail_at(start, "unpaired high surrogate in a \\u escape");
            unit = 0x10000 + ((unit - 0xD800) << 10) + (low - 0xDC00);
        }
        append_utf8(out, unit);
        return true;
    }

    bool parse_hex4(std::uint32_t& out) {
        for (int i = 0; i < 4; ++i) {
            if (at_end()) return fail_unexpected("4 hex digits after \\u");
            const char c = peek();
            std::uint32_t digit;
            if (is_digit(c))
                digit = std::uint32_t(c - '0');
            else if (c >= 'a' && c <= 'f')
                digit = std::uint32_t(c - 'a' + 10);
            else if (c >= 'A' && c <= 'F')
                digit = std::uint32_t(c - 'A' + 10);
            else
                return fail_unexpected("4 hex digits after \\u");
            out = out * 16 + digit;
            advance();
        }
        return true;
    }

    // Grammar: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
    bool parse_number(Value& out) {
        const Position start = here();
        const std::size_t begin = pos_;
        NumberShape shape;
        consume('-');
        if (!scan_integer_part(shape) || !scan_fraction(shape) || !scan_exponent(shape))
            return false;
        const char* first = text_.data() + begin;
        const char* last = text_.data() + pos_;
        double value = 0.0;
        const auto [end, ec] = std::from_chars(first, last, value);
        if (ec == std::errc::result_out_of_range) {
            if (magnitude(shape) >= 0) return fail_at(start, "number out of range");
            value = *first == '-' ? -0.0 : 0.0; // underflow: closer to 0 than any double
        } else if (ec != std::errc() || end != last) {
            return fail_at(start, "invalid number");
        }
        out = Value(Value::Number{value, shape.integer_literal}, start);
        return true;
    }

    bool scan_integer_part(NumberShape& shape) {
        if (at_end() || !is_digit(peek())) return fail_unexpected("a digit");
        if (consume('0')) {
            if (!at_end() && is_digit(peek()))
                return fail("leading zeros are not allowed in numbers");
            return true;
        }
        while (!at_end() && is_digit(peek())) {
            ++shape.integer_digits;
            advance();
        }
        return true;
    }

    bool scan_fraction(NumberShape& shape) {
        if (!consume('.')) return true;
        shape.integer_literal = false;
        if (at_end() || !is_digit(peek()))
            return fail_unexpected("a digit after the decimal point");
        while (!at_end() && is_digit(peek())) {
            if (peek() != '0')
                shape.fraction_nonzero = true;
            else if (!shape.fraction_nonzero)
                ++shape.fraction_zeros;
            advance();
        }
        return true;
    }

    bool scan_exponent(NumberShape& shape) {
        if (at_end() || (peek() != 'e' && peek() != 'E')) return true;
        shape.integer_literal = false;
        advance();
        const bool negative = consume('-');
        if (!negative) consume('+');
        if (at_end() || !is_digit(peek())) return fail_unexpected("a digit in the exponent");
        long exponent = 0;
        while (!at_end() && is_digit(peek())) {
            exponent = std::min(exponent * 10 + (peek() - '0'), 1'000'000'000L);
            advance();
        }
        shape.exponent = negative ? -exponent : exponent;
        return true;
    }

    std::string_view text_;
    const std::string& file_;
    std::size_t pos_ = 0;
    int line_ = 1;
    int column_ = 1;
    std::optional<Error> error_;
};

} // namespace

const Value* Value::find(std::string_view key) const {
    for (const Member& member : as_object())
        if (member.key == key) return &member.value;
    return nullptr;
}

Result<Value> parse(std::string_view text, const std::string& file_name) {
    // Lines and columns are ints; below this size neither can overflow.
    if (text.size() >= max_text_bytes)
        return make_error(file_name + ": larger than " + std::to_string(max_text_bytes) + " bytes");
    return Parser(text, file_name).run();
}

const char* describe(Type type) {
    switch (type) {
    case Type::null:
        return "null";
    case Type::boolean:
        return "a boolean";
    case Type::number:
        return "a number";
    case Type::string:
        return "a string";
    case Type::array:
        return "an array";
    case Type::object:
        return "an object";
    }
    return "a value";
}

} // namespace lantern::json
