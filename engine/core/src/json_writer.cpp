#include "lantern/core/json_writer.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/json.hpp"
#include "lantern/core/text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace lantern::json {

void append_quoted(std::string& out, std::string_view s) {
    out += '"';
    for (std::size_t i = 0; i < s.size();) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c >= 0x80) {
            const std::size_t n = utf8_char(s.substr(i));
            if (n == 0) {
                out += "\\ufffd"; // not UTF-8: the replacement character
                ++i;
            } else {
                out.append(s.substr(i, n));
                i += n;
            }
            continue;
        }
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\t': out += "\\t"; break;
        case '\r': out += "\\r"; break;
        case '\b': out += "\\b"; break;
        case '\f': out += "\\f"; break;
        default:
            if (c < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof(buf), "\\u%04x", unsigned(c));
                out += buf;
            } else {
                out += char(c);
            }
        }
        ++i;
    }
    out += '"';
}

std::string quoted(std::string_view s) {
    std::string out;
    append_quoted(out, s);
    return out;
}

void Writer::newline_indent(std::size_t depth) {
    out_ += '\n';
    out_.append(depth * 2, ' ');
}

void Writer::before_value() {
    LANTERN_ASSERT(!done_, "json::Writer: a second top-level value");
    if (levels_.empty()) return;
    Level& level = levels_.back();
    if (level.object) {
        LANTERN_ASSERT(key_pending_, "json::Writer: a value in an object without a key");
        key_pending_ = false;
        return; // key() wrote the separator
    }
    if (!level.empty) out_ += level.one_line ? ", " : ",";
    if (!level.one_line) newline_indent(levels_.size());
    level.empty = false;
}

Writer& Writer::key(std::string_view name) {
    LANTERN_ASSERT(!levels_.empty() && levels_.back().object && !key_pending_,
                   "json::Writer: a key outside an object or twice");
    Level& level = levels_.back();
    if (!level.empty) out_ += level.one_line ? ", " : ",";
    if (!level.one_line) newline_indent(levels_.size());
    level.empty = false;
    append_quoted(out_, name);
    out_ += ": ";
    key_pending_ = true;
    return *this;
}

Writer& Writer::begin(char open, bool object, Layout layout) {
    before_value();
    out_ += open;
    const bool inside_one_line = !levels_.empty() && levels_.back().one_line;
    levels_.push_back({object, inside_one_line || layout == Layout::one_line, true});
    return *this;
}

Writer& Writer::begin_object(Layout layout) { return begin('{', true, layout); }
Writer& Writer::begin_array(Layout layout) { return begin('[', false, layout); }

Writer& Writer::end() {
    LANTERN_ASSERT(!levels_.empty() && !key_pending_, "json::Writer: end() with nothing open or after a key");
    const Level level = levels_.back();
    levels_.pop_back();
    if (!level.empty && !level.one_line) newline_indent(levels_.size());
    out_ += level.object ? '}' : ']';
    if (levels_.empty()) done_ = true;
    return *this;
}

Writer& Writer::value(std::string_view s) {
    before_value();
    append_quoted(out_, s);
    if (levels_.empty()) done_ = true;
    return *this;
}

Writer& Writer::value(bool b) {
    before_value();
    out_ += b ? "true" : "false";
    if (levels_.empty()) done_ = true;
    return *this;
}

Writer& Writer::null() {
    before_value();
    out_ += "null";
    if (levels_.empty()) done_ = true;
    return *this;
}

Writer& Writer::integer(long long v) {
    before_value();
    out_ += std::to_string(v);
    if (levels_.empty()) done_ = true;
    return *this;
}

template <typename F>
Writer& Writer::shortest(F v) {
    if (!std::isfinite(v)) return null();
    before_value();
    char buf[64];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), v);
    LANTERN_ASSERT(ec == std::errc(), "json::Writer: number formatting failed");
    out_.append(buf, end);
    if (levels_.empty()) done_ = true;
    return *this;
}

Writer& Writer::value(double v) { return shortest(v); }
Writer& Writer::value(float v) { return shortest(v); }

Writer& Writer::value(double v, int decimals) {
    LANTERN_ASSERT(decimals >= 0 && decimals <= 17, "json::Writer: decimals outside 0..17");
    if (!std::isfinite(v)) return null();
    before_value();
    char buf[400];
    std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
    out_ += buf;
    if (levels_.empty()) done_ = true;
    return *this;
}

std::string Writer::take() {
    LANTERN_ASSERT(levels_.empty() && done_, "json::Writer::take with containers open or nothing written");
    out_ += '\n';
    std::string out = std::move(out_);
    out_.clear();
    done_ = false;
    return out;
}

namespace {

void write_at(Writer& w, const Value& v, LayoutRule layout, int depth) {
    switch (v.type()) {
    case Type::null: w.null(); return;
    case Type::boolean: w.value(v.as_bool()); return;
    case Type::number:
        if (const double d = v.as_number(); v.is_integer_literal() && std::abs(d) <= 9007199254740992.0)
            w.value(static_cast<long long>(d));
        else
            w.value(d);
        return;
    case Type::string: w.value(v.as_string()); return;
    case Type::array:
        w.begin_array(layout ? layout(v, depth) : Layout::lines);
        for (const Value& e : v.as_array()) write_at(w, e, layout, depth + 1);
        w.end();
        return;
    case Type::object:
        w.begin_object(layout ? layout(v, depth) : Layout::lines);
        for (const Member& m : v.as_object()) {
            w.key(m.key);
            write_at(w, m.value, layout, depth + 1);
        }
        w.end();
        return;
    }
}

} // namespace

void write(Writer& w, const Value& v, LayoutRule layout) { write_at(w, v, layout, 0); }

} // namespace lantern::json
