#include "lantern/scene/json_reader.hpp"

#include "lantern/core/text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

namespace lantern::scene::reading {
namespace {

// Levenshtein distance, for "did you mean" suggestions on short keys.
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
        }
        std::swap(previous, current);
    }
    return previous[b.size()];
}

// " (did you mean 'resolution'?)" when one known key is within two edits, else "".
std::string suggestion(std::string_view key, std::span<const std::string_view> known) {
    std::string_view best;
    std::size_t best_distance = 3;
    for (std::string_view candidate : known) {
        const std::size_t distance = edit_distance(key, candidate);
        if (distance < best_distance) {
            best = candidate;
            best_distance = distance;
        }
    }
    if (best.empty() || best_distance >= key.size()) return {};
    return " (did you mean '" + std::string(best) + "'?)";
}

} // namespace

std::string index_path(const std::string& path, std::size_t index) {
    return path + "[" + std::to_string(index) + "]";
}

std::string quote_char(char c) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7F) return std::string("'") + c + "'";
    char buffer[16];
    std::snprintf(buffer, sizeof(buffer), "byte 0x%02X", byte);
    return buffer;
}

std::string quote_char_at(std::string_view text, std::size_t at) {
    std::uint32_t cp = 0;
    const std::size_t n = utf8_char(text.substr(at), &cp);
    if (n <= 1) return quote_char(text[at]);
    char code[16];
    std::snprintf(code, sizeof(code), "U+%04X", unsigned(cp));
    return "'" + std::string(text.substr(at, n)) + "' (" + code + ")";
}

std::string format_number(double v) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
    return std::string(buffer, result.ptr);
}

std::string format_float(float v) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
    return std::string(buffer, result.ptr);
}

std::string shorten(std::string_view text) { return printable(text, 40); }

bool Range::contains(double v) const {
    if (std::isnan(v)) return false;
    const bool above_min = min_open ? v > min : v >= min;
    const bool below_max = max_open ? v < max : v <= max;
    return above_min && below_max;
}

std::string Range::describe() const {
    const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
    if (has_min && has_max)
        return std::string("in ") + (min_open ? "(" : "[") + format_number(min) + ", " +
               format_number(max) + (max_open ? ")" : "]");
    if (has_min) return (min_open ? "> " : ">= ") + format_number(min);
    if (has_max) return (max_open ? "< " : "<= ") + format_number(max);
    return "finite";
}

bool Reader::fail(json::Position where, std::string path, std::string what) {
    if (!issue_) issue_ = Issue{where, std::move(path), std::move(what)};
    return false;
}

bool Reader::read_number(const json::Value& v, const std::string& path, const Range& range,
                         double& out) {
    if (!v.is_number())
        return fail(v.position(), path,
                    std::string("expected a number, got ") + json::describe(v.type()));
    const double value = v.as_number();
    if (!range.contains(value)) {
        std::string what = "must be " + range.describe() + ", got " + format_number(value);
        if (!range.note.empty()) what += " (" + std::string(range.note) + ")";
        return fail(v.position(), path, std::move(what));
    }
    out = value;
    return true;
}

bool Reader::read(const json::Value& v, const std::string& path, float& out, const Range& range) {
    double value = 0.0;
    if (!read_number(v, path, range, value)) return false;
    if (std::abs(value) > double(std::numeric_limits<float>::max()))
        return fail(v.position(), path, format_number(value) + " does not fit a 32-bit float");
    // A value that is not 0 must not become 0 (a size or a radius that rounds to nothing).
    if (value != 0.0 && std::abs(value) < double(std::numeric_limits<float>::min()))
        return fail(v.position(), path, format_number(value) + " is too close to 0 for a 32-bit float");
    out = static_cast<float>(value);
    return true;
}

bool Reader::read(const json::Value& v, const std::string& path, int& out, IntRange range) {
    if (!v.is_number())
        return fail(v.position(), path,
                    std::string("expected an integer, got ") + json::describe(v.type()));
    const double value = v.as_number();
    if (value != std::floor(value))
        return fail(v.position(), path, "expected an integer, got " + format_number(value));
    if (value < range.min || value > range.max)
        return fail(v.position(), path,
                    "must be an integer in [" + std::to_string(range.min) + ", " +
                        std::to_string(range.max) + "], got " + format_number(value));
    out = static_cast<int>(value);
    return true;
}

bool Reader::read(const json::Value& v, const std::string& path, bool& out) {
    if (!v.is_bool())
        return fail(v.position(), path,
                    std::string("expected true or false, got ") + json::describe(v.type()));
    out = v.as_bool();
    return true;
}

bool Reader::read(const json::Value& v, const std::string& path, std::string& out) {
    if (!expect(v, path, json::Type::string)) return false;
    out = v.as_string();
    return true;
}

bool Reader::read_components(const json::Value& v, const std::string& path, std::span<float> out,
                             const Range& each) {
    const std::string expected = "expected an array of " + std::to_string(out.size()) + " numbers";
    if (!v.is_array())
        return fail(v.position(), path, expected + ", got " + json::describe(v.type()));
    const json::Value::Array& items = v.as_array();
    if (items.size() != out.size())
        return fail(v.position(), path, expected + ", got " + std::to_string(items.size()));
    for (std::size_t i = 0; i < out.size(); ++i)
        if (!read(items[i], index_path(path, i), out[i], each)) return false;
    return true;
}

bool Reader::read(const json::Value& v, const std::string& path, glm::vec2& out,
                  const Range& each) {
    glm::vec2 value;
    if (!read_components(v, path, std::span<float>(glm::value_ptr(value), 2), each)) return false;
    out = value;
    return true;
}

bool Reader::read(const json::Value& v, const std::string& path, glm::vec3& out,
                  const Range& each) {
    glm::vec3 value;
    if (!read_components(v, path, std::span<float>(glm::value_ptr(value), 3), each)) return false;
    out = value;
    return true;
}

bool Reader::read(const json::Value& v, const std::string& path, glm::ivec2& out, IntRange each) {
    if (!v.is_array() || v.as_array().size() != 2) {
        const std::string got =
            v.is_array() ? std::to_string(v.as_array().size()) : json::describe(v.type());
        return fail(v.position(), path, "expected an array of 2 integers, got " + got);
    }
    glm::ivec2 value;
    for (int i = 0; i < 2; ++i)
        if (!read(v.as_array()[std::size_t(i)], index_path(path, std::size_t(i)), value[i], each))
            return false;
    out = value;
    return true;
}

bool Reader::expect(const json::Value& v, const std::string& path, json::Type type) {
    if (v.type() == type) return true;
    return fail(v.position(), path,
                std::string("expected ") + json::describe(type) + ", got " +
                    json::describe(v.type()));
}

bool Reader::expect_known_keys(const json::Value& object, const std::string& path,
                               std::span<const std::string_view> known) {
    for (const json::Member& member : object.as_object())
        if (std::find(known.begin(), known.end(), member.key) == known.end())
            return fail_unknown_key(member.key, member.key_position, path, known);
    return true;
}

bool Reader::fail_unknown_key(std::string_view key, json::Position where, const std::string& path,
                              std::span<const std::string_view> known) {
    const std::string owner = path.empty() ? document_ : path;
    const std::string short_key = shorten(key);
    const std::string key_path = path.empty() ? short_key : path + "." + short_key;
    return fail(where, key_path,
                "unknown key '" + short_key + "' in " + owner + suggestion(key, known));
}

Fields::Fields(Reader& reader, const json::Value& object, std::string path,
               std::initializer_list<std::string_view> known)
    : reader_(reader), object_(object), path_(std::move(path)) {
    // Invariant: while reader_.ok(), object_ is an object.
    if (reader_.ok() && reader_.expect(object_, path_, json::Type::object))
        reader_.expect_known_keys(object_, path_, std::span(known.begin(), known.size()));
}

std::string_view Fields::one_of(std::string_view first, std::string_view second) {
    const json::Value* a = find(first);
    const json::Value* b = find(second);
    if (!reader_.ok()) return {};
    if (a && b) {
        fail(second,
             "give only one of '" + std::string(first) + "' and '" + std::string(second) + "'");
        return {};
    }
    if (!a && !b) {
        reader_.fail(object_.position(), path_of(first),
                     "required key is missing (or give '" + std::string(second) + "')");
        return {};
    }
    return a ? first : second;
}

bool Fields::fail(std::string_view key, std::string what) {
    if (!reader_.ok()) return false;
    const json::Value* v = find(key);
    LANTERN_ASSERT(v, "Fields::fail on an absent key");
    return reader_.fail(v->position(), path_of(key), std::move(what));
}

const json::Value* Fields::find(std::string_view key) const {
    return reader_.ok() ? object_.find(key) : nullptr;
}

const json::Value* Fields::find_required(std::string_view key) {
    const json::Value* v = find(key);
    if (!v && reader_.ok())
        reader_.fail(object_.position(), path_of(key), "required key is missing");
    return v;
}

std::string Fields::path_of(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

Error issue_error(const std::string& file, const Issue& issue) {
    const std::string path = issue.path.empty() ? "" : issue.path + ": ";
    return make_error(file + ":" + std::to_string(issue.where.line) + ":" + std::to_string(issue.where.column) +
                      ": " + path + issue.what);
}

} // namespace lantern::scene::reading
