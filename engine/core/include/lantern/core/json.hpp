// Strict JSON (RFC 8259) parser producing a small DOM in which every value and every object
// key records the 1-based line and column where it starts, so that loaders built on it can
// report "scene.json:12:7: gi.ao.radius: ..." for any value they reject.
//
// Strictness. Exactly RFC 8259: no comments, no trailing commas, no single quotes, no
// NaN/Infinity, no leading zeros or '+', no control characters inside strings, strings must
// be valid UTF-8 and may not contain unpaired surrogate escapes. One extension: a leading
// UTF-8 byte order mark is skipped (RFC 8259 allows parsers to ignore it). Duplicate keys
// in one object are an error. A number whose magnitude exceeds the largest double is an
// error ("number out of range"); one too small for a double becomes 0. Texts of
// max_text_bytes or more are rejected.
//
// Positions. Lines are counted at '\n'; columns count Unicode code points from 1 (a tab is
// one column), which is what editors show for text without tabs.
//
// Trust boundary: safe for untrusted input. Malformed text of any kind comes back as an
// Error; nesting deeper than max_depth is rejected before it can exhaust the stack, and
// memory use follows the input size (a parsed document takes at most about 50 bytes per
// input byte, reached by arrays of one-digit numbers). Error messages quote at most a few
// dozen bytes of the input.
//
// Threads: parse() is reentrant; a Value is an ordinary value type (copyable, movable).
#pragma once

#include "lantern/core/result.hpp"

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace lantern::json {

// 1-based line and column of the first character of a value or key.
struct Position {
    int line = 1;
    int column = 1;
    friend bool operator==(const Position&, const Position&) = default;
};

enum class Type : std::uint8_t { null, boolean, number, string, array, object };

struct Member;

class Value {
  public:
    using Array = std::vector<Value>;
    using Object = std::vector<Member>; // in the order of the text; keys are unique

    // A number as written in the text: `integer_literal` is true when it had neither a
    // fraction nor an exponent ("12", "-3", but not "12.0" or "1e3").
    struct Number {
        double value = 0.0;
        bool integer_literal = false;
    };

    // Defined after Member: the variant needs Member complete (clang checks that eagerly).
    Value();                           // null at 1:1
    Value(std::nullptr_t, Position at);
    template <std::same_as<bool> B> // not from pointers or integers
    Value(B b, Position at);
    Value(Number n, Position at);
    Value(std::string s, Position at);
    Value(const char* s, Position at);
    Value(Array a, Position at);
    Value(Object o, Position at);

    Type type() const { return static_cast<Type>(data_.index()); }
    Position position() const { return position_; }

    bool is_null() const { return type() == Type::null; }
    bool is_bool() const { return type() == Type::boolean; }
    bool is_number() const { return type() == Type::number; }
    bool is_string() const { return type() == Type::string; }
    bool is_array() const { return type() == Type::array; }
    bool is_object() const { return type() == Type::object; }

    // Typed access; calling the accessor of another type is a programmer error (asserts).
    bool as_bool() const { return get<bool>(); }
    double as_number() const { return get<Number>().value; }
    bool is_integer_literal() const { return get<Number>().integer_literal; }
    const std::string& as_string() const { return get<std::string>(); }
    const Array& as_array() const { return get<Array>(); }
    const Object& as_object() const { return get<Object>(); }

    // The member of an object with this key, or nullptr; asserts that this is an object.
    const Value* find(std::string_view key) const;

  private:
    template <typename T>
    const T& get() const {
        LANTERN_ASSERT(std::holds_alternative<T>(data_), "JSON value has another type");
        return std::get<T>(data_);
    }

    // Alternative order matches Type.
    std::variant<std::monostate, bool, Number, std::string, Array, Object> data_;
    Position position_;
};

struct Member {
    std::string key;
    Position key_position; // of the key's opening quote
    Value value;
};

inline Value::Value() = default;
inline Value::Value(std::nullptr_t, Position at) : position_(at) {}
template <std::same_as<bool> B>
Value::Value(B b, Position at) : data_(b), position_(at) {}
inline Value::Value(Number n, Position at) : data_(n), position_(at) {}
inline Value::Value(std::string s, Position at) : data_(std::move(s)), position_(at) {}
inline Value::Value(const char* s, Position at) : data_(std::string(s)), position_(at) {}
inline Value::Value(Array a, Position at) : data_(std::move(a)), position_(at) {}
inline Value::Value(Object o, Position at) : data_(std::move(o)), position_(at) {}

// Deepest nesting of arrays and objects parse() accepts.
inline constexpr int max_depth = 256;
// Largest text parse() accepts (2 GiB - 1), so that lines and columns fit an int.
inline constexpr std::size_t max_text_bytes = 0x7FFFFFFF;

// Parses one JSON text (a single value, optionally surrounded by whitespace). Errors are
// "<file_name>:<line>:<col>: <what>" with exit_code 2. `file_name` is used only in messages.
Result<Value> parse(std::string_view text, const std::string& file_name);

// "null", "a boolean", "a number", "a string", "an array" or "an object": for messages.
const char* describe(Type type);

} // namespace lantern::json
