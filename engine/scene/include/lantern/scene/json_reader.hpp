// Typed, range-checked reading of JSON values into fields, keeping the first problem found
// together with its position and JSON path; the callers turn that problem into a file
// message ("scene.json:3:7: gi.padding: ...", issue_error) or a --set message. The one reader
// of Lantern's JSON formats: scene files, --set, and the game's saves, which read their lights
// and proxies with the scene file's own functions at the end of this header.
#pragma once

#include "lantern/core/json.hpp"
#include "lantern/core/result.hpp"
#include "lantern/scene/scene.hpp"

#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace lantern::scene::reading {

struct Issue {
    json::Position where;
    std::string path; // "gi.ao.radius", "point_lights[2].color[1]"
    std::string what; // "must be in (0, 8], got 12"
};

// An interval of allowed numbers, with an optional note explaining the bound.
struct Range {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false;
    bool max_open = false;
    std::string_view note = {};

    bool contains(double v) const;
    std::string describe() const; // "in [0, 1]", "in (0, 16]", ">= 0", "> 0", "finite"
};

inline constexpr Range any_number{};
// World coordinates (x, z of positions, camera points): within +-2^24 world units, where a
// float still holds every whole tile and a tile index still fits an int; beyond it the
// renderer could not place a texel (docs/scenes.md, "Size limits").
inline constexpr double max_world_coordinate = 16777216.0;
inline constexpr Range world_coordinate{.min = -max_world_coordinate, .max = max_world_coordinate,
                                        .note = "world coordinates stay within +-2^24"};
constexpr Range at_least(double min) {
    return {.min = min};
}
constexpr Range greater_than(double min) {
    return {.min = min, .min_open = true};
}
constexpr Range between(double min, double max) {
    return {.min = min, .max = max};
}

struct IntRange {
    int min = std::numeric_limits<int>::min();
    int max = std::numeric_limits<int>::max();
};

template <typename E>
struct EnumName {
    std::string_view name;
    E value;
};

// Shortest text that reads back as `v` ("1.5", "64", "1e+300").
std::string format_number(double v);
// The shortest text that reads back as `v` (0.2f is "0.2", not 0.2f's double "0.2000000029...").
std::string format_float(float v);

// A character of a file as messages quote it: 'x' when printable ASCII, else byte 0xNN.
std::string quote_char(char c);
// The character of `text` that starts at byte `at`: "'é' (U+00E9)" for a well-formed UTF-8
// character, as quote_char for ASCII and for a byte that starts no character.
std::string quote_char_at(std::string_view text, std::size_t at);

// Text from a file as messages quote it: control characters and bytes that are not UTF-8
// escaped (\x01), cut to 40 bytes plus "..." when longer, so that hostile input can
// neither flood the terminal nor break the message's one line (core/text.hpp: printable).
std::string shorten(std::string_view text);

// "path[index]".
std::string index_path(const std::string& path, std::size_t index);

// Converts JSON values to C++ fields. Every read checks type and range and returns false
// on a problem; only the first problem is kept, so later reads may run but cannot hide it.
class Reader {
  public:
    // `document` names the whole file in messages about its top level ("unknown key 'x' in
    // the scene").
    Reader() = default;
    explicit Reader(std::string document) : document_(std::move(document)) {}

    bool ok() const { return !issue_.has_value(); }
    const Issue& issue() const { return *issue_; }

    // Records a problem (unless one is recorded already) and returns false.
    bool fail(json::Position where, std::string path, std::string what);

    bool read(const json::Value& v, const std::string& path, float& out, const Range& range);
    bool read(const json::Value& v, const std::string& path, int& out, IntRange range);
    bool read(const json::Value& v, const std::string& path, bool& out);
    bool read(const json::Value& v, const std::string& path, std::string& out);
    // Arrays of exactly 2 or 3 numbers, each checked against the range.
    bool read(const json::Value& v, const std::string& path, glm::vec2& out, const Range& each);
    bool read(const json::Value& v, const std::string& path, glm::vec3& out, const Range& each);
    bool read(const json::Value& v, const std::string& path, glm::ivec2& out, IntRange each);

    // `names` is not deduced, so a std::array of names converts.
    template <typename E>
    bool read(const json::Value& v, const std::string& path, E& out,
              std::type_identity_t<std::span<const EnumName<E>>> names) {
        const std::string* text = enum_text(v, path, names);
        if (!text) return false;
        for (const EnumName<E>& entry : names) {
            if (entry.name == *text) {
                out = entry.value;
                return true;
            }
        }
        return fail(v.position(), path,
                    "expected " + list_names(names) + ", got \"" + shorten(*text) + "\"");
    }

    // Checks that `v` is an object (resp. array); records "expected an object, got ...".
    bool expect(const json::Value& v, const std::string& path, json::Type type);

    // Records the first key of `object` not in `known`, at the key:
    // "unknown key 'resoluton' in gi (did you mean 'resolution'?)".
    bool expect_known_keys(const json::Value& object, const std::string& path,
                           std::span<const std::string_view> known);
    // Records "unknown key 'KEY' in PATH" at `where`, for the key at PATH.KEY.
    bool fail_unknown_key(std::string_view key, json::Position where, const std::string& path,
                          std::span<const std::string_view> known);

  private:
    bool read_number(const json::Value& v, const std::string& path, const Range& range,
                     double& out);
    bool read_components(const json::Value& v, const std::string& path, std::span<float> out,
                         const Range& each);

    template <typename E>
    const std::string* enum_text(const json::Value& v, const std::string& path,
                                 std::span<const EnumName<E>> names) {
        if (v.is_string()) return &v.as_string();
        fail(v.position(), path,
             "expected " + list_names(names) + ", got " + json::describe(v.type()));
        return nullptr;
    }

    template <typename E>
    static std::string list_names(std::span<const EnumName<E>> names) {
        std::string text = "one of";
        for (const EnumName<E>& entry : names)
            text += std::string(&entry == names.data() ? " \"" : ", \"") + std::string(entry.name) +
                    "\"";
        return text;
    }

    std::string document_ = "the scene";
    std::optional<Issue> issue_;
};

// The members of one JSON object read into fields, in the order of the calls:
//     Fields(reader, value, "point_lights[0]", {"position", "radius"})
//         .required("position", light.position, any_number)
//         .optional("radius", light.radius, greater_than(0));
// The constructor checks that `object` is an object with only `known` keys. After a
// problem every further call does nothing.
class Fields {
  public:
    Fields(Reader& reader, const json::Value& object, std::string path,
           std::initializer_list<std::string_view> known);

    // Absent key: records "required key is missing" at the object's position.
    template <typename T, typename... Constraint>
    Fields& required(std::string_view key, T& out, const Constraint&... constraint) {
        if (const json::Value* v = find_required(key))
            reader_.read(*v, path_of(key), out, constraint...);
        return *this;
    }
    // Absent key: `out` keeps its value (the default).
    template <typename T, typename... Constraint>
    Fields& optional(std::string_view key, T& out, const Constraint&... constraint) {
        if (const json::Value* v = find(key)) reader_.read(*v, path_of(key), out, constraint...);
        return *this;
    }

    // Which of two mutually exclusive keys is present ("" after a problem). Records
    // "required key is missing (or give '<second>')" at the object when neither is, and
    // "give only one of ..." at the second when both are.
    std::string_view one_of(std::string_view first, std::string_view second);

    // Records a problem with the value of `key`, which must be present.
    bool fail(std::string_view key, std::string what);

    // The member's value, or nullptr when it is absent or a problem was recorded.
    const json::Value* find(std::string_view key) const;
    const json::Value* find_required(std::string_view key);
    std::string path_of(std::string_view key) const;
    bool ok() const { return reader_.ok(); }

  private:
    Reader& reader_;
    const json::Value& object_;
    std::string path_;
};

// "<file>:<line>:<col>: <path>: <what>", exit status 2.
Error issue_error(const std::string& file, const Issue& issue);

// The objects of a scene file's lists ("point_lights", ...; docs/scenes.md), with their keys,
// defaults and ranges, for any format that embeds them. Directions come back normalised.
void read_point_light(Reader& reader, const json::Value& value, const std::string& path, PointLight& light);
void read_emissive_light(Reader& reader, const json::Value& value, const std::string& path,
                         EmissiveLight& light);
void read_directional_light(Reader& reader, const json::Value& value, const std::string& path,
                            DirectionalLight& light);
void read_shadow_proxy(Reader& reader, const json::Value& value, const std::string& path, ShadowProxy& proxy);

} // namespace lantern::scene::reading
