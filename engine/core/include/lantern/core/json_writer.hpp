// JSON text out: the one writer behind every file Lantern writes as JSON (saves, timings,
// traces, status lines), so that all of them escape alike and parse back with json::parse.
//
//   json::Writer w;
//   w.begin_object().field("frames", 600).key("scopes").begin_array();
//   for (...) w.begin_object(json::Layout::one_line).field("name", s.name).field("p50", p50, 3).end();
//   w.end().end();
//   write_file_atomic(path, w.take());
//
// Strings: '"' and '\' escaped, control characters as \n, \t, \r, \b, \f or \u00XX, bytes
// that are not UTF-8 replaced by U+FFFD (the parser accepts only UTF-8, so what is written
// always reads back). Numbers: floats and doubles in the shortest text that reads back as the
// same value; with `decimals`, fixed-point (reports); not finite: null (JSON has no NaN).
// Layout: a container's elements on their own lines, indented by two spaces per level
// (Layout::lines, the default), or on one line separated by ", " (Layout::one_line; every
// container inside one is on that line too).
//
// Misuse (a value where a key is due, end() with nothing open, take() with containers open)
// is a programmer error and asserts. Not thread-safe; an ordinary value type.
#pragma once

#include <concepts>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::json {

class Value;

enum class Layout : std::uint8_t { lines, one_line };

// `s` as a JSON string literal, quotes included.
std::string quoted(std::string_view s);
void append_quoted(std::string& out, std::string_view s);

class Writer {
  public:
    Writer& begin_object(Layout layout = Layout::lines);
    Writer& begin_array(Layout layout = Layout::lines);
    Writer& end(); // closes the innermost object or array

    Writer& key(std::string_view name); // in an object, before each value

    Writer& value(std::string_view s);
    Writer& value(const char* s) { return value(std::string_view(s)); }
    Writer& value(const std::string& s) { return value(std::string_view(s)); }
    Writer& value(bool b);
    Writer& value(double v);
    Writer& value(float v);
    Writer& value(double v, int decimals); // fixed-point, e.g. 3 -> "12.345"
    template <std::integral I>
        requires(!std::same_as<I, bool>)
    Writer& value(I v) {
        return integer(static_cast<long long>(v));
    }
    Writer& null();

    // key(name).value(...)
    template <typename... V>
    Writer& field(std::string_view name, const V&... v) {
        key(name);
        return value(v...);
    }

    // The text so far; take() asserts that every container is closed and ends it with '\n'.
    const std::string& text() const { return out_; }
    std::string take();

  private:
    struct Level {
        bool object = false;
        bool one_line = false;
        bool empty = true;
    };
    Writer& integer(long long v);
    template <typename F>
    Writer& shortest(F v); // float or double, shortest text that reads back exactly
    Writer& begin(char open, bool object, Layout layout);
    void before_value(); // separator and indentation; checks a key was given in an object
    void newline_indent(std::size_t depth);

    std::string out_;
    std::vector<Level> levels_;
    bool key_pending_ = false; // a key was written; its value comes next
    bool done_ = false;        // the top-level value is complete
};

// Writes a parsed document back (json::parse's DOM): members in their order, numbers
// written as integers where the text had an integer literal (and it fits 2^53), else in the
// shortest text of the double. `layout(container, depth)` picks each container's layout
// (depth 0 is the top-level value); nullptr: Layout::lines everywhere. Inside a one-line
// container everything is on that line.
using LayoutRule = Layout (*)(const Value& container, int depth);
void write(Writer& w, const Value& v, LayoutRule layout = nullptr);

} // namespace lantern::json
