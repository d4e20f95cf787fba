#include "gi_settings.hpp"

#include "lantern/scene/loader.hpp"

#include <algorithm>
#include <array>
#include <span>
#include <variant>
#include <vector>

namespace lantern::scene {
namespace reading {
namespace {

template <typename... F>
struct Overloaded : F... {
    using F::operator()...;
};
template <typename... F>
Overloaded(F...) -> Overloaded<F...>; // C++20 deduces this; clang 14 does not yet

constexpr std::array<EnumName<HeatScale>, 3> heat_scale_names{{
    {"full", HeatScale::full},
    {"half", HeatScale::half},
    {"quarter", HeatScale::quarter},
}};

constexpr std::array<EnumName<ToneMap>, 4> tone_map_names{{
    {"none", ToneMap::none},
    {"reinhard", ToneMap::reinhard},
    {"reinhard_white", ToneMap::reinhard_white},
    {"aces", ToneMap::aces},
}};

constexpr std::array<EnumName<WindowSnap>, 2> window_snap_names{{
    {"tile", WindowSnap::tile},
    {"texel", WindowSnap::texel},
}};

constexpr std::array<EnumName<SunShadowMethod>, 2> sun_shadow_method_names{{
    {"dda", SunShadowMethod::dda},
    {"shadow_map", SunShadowMethod::shadow_map},
}};

constexpr std::array<EnumName<ShadowMethod>, 2> shadow_method_names{{
    {"dda", ShadowMethod::dda},
    {"shadow_map", ShadowMethod::shadow_map},
}};

constexpr std::array<EnumName<ProxyWallShadows>, 2> proxy_wall_shadows_names{{
    {"full", ProxyWallShadows::full},
    {"unfold", ProxyWallShadows::unfold},
}};

constexpr std::array<EnumName<GiMethod>, 3> method_names{{
    {"heat", GiMethod::heat},
    {"radiosity", GiMethod::radiosity},
    {"gather", GiMethod::gather},
}};

constexpr std::array<EnumName<NoiseShift>, 3> noise_shift_names{{
    {"rotate", NoiseShift::rotate},
    {"golden", NoiseShift::golden},
    {"off", NoiseShift::off},
}};

constexpr Range radiosity_epsilon_range{.min = 0.0, .max = 64.0, .min_open = true};
constexpr Range radiosity_feedback_range{
    .min = 0.0,
    .max = 1.0,
    .max_open = true,
    .note = "at 1 a closed room's light grows without bound; see docs/gi.md",
};

constexpr Range diffusion_rate_range{
    .min = 0.0,
    .max = 1.25,
    .note = "above 1.25 the heat blend exceeds 1 and the diffusion overshoots; see docs/gi.md",
};
constexpr Range diffusion_distance_range{.min = 0.0, .max = 16.0, .min_open = true};
constexpr Range ao_radius_range{.min = 0.0, .max = 8.0, .min_open = true};
constexpr Range wall_face_exponent_range{.min = 0.0, .max = 16.0, .min_open = true};

struct FloatField {
    float* target;
    Range range;
};
struct IntField {
    int* target;
    IntRange range;
};
struct BoolField {
    bool* target;
};
template <typename E>
struct EnumField {
    E* target;
    std::span<const EnumName<E>> names;
};
using FieldTarget = std::variant<FloatField, IntField, BoolField, EnumField<HeatScale>, EnumField<ToneMap>,
                                 EnumField<GiMethod>, EnumField<WindowSnap>, EnumField<ShadowMethod>, EnumField<SunShadowMethod>,
                                 EnumField<ProxyWallShadows>, EnumField<NoiseShift>>;

struct GiField {
    std::string_view key; // below "gi"; keys of nested objects joined by dots ("ao.radius")
    FieldTarget target;
};

// The one table of gi keys: JSON name, the field of `gi` it sets and the allowed values.
// The order is that of GiSettings and docs/scenes.md.
std::array<GiField, 53> gi_fields(GiSettings& gi) {
    return {{
        {"method", EnumField<GiMethod>{&gi.method, method_names}},
        {"resolution", IntField{&gi.resolution, {1, 32}}},
        {"padding", FloatField{&gi.padding, between(1.0, 8.0)}},
        {"window_snap", EnumField<WindowSnap>{&gi.window_snap, window_snap_names}},
        {"heat_rounds", IntField{&gi.heat_rounds, {0, 100000}}},
        {"heat_scale", EnumField<HeatScale>{&gi.heat_scale, heat_scale_names}},
        {"diffusion_rate", FloatField{&gi.diffusion_rate, diffusion_rate_range}},
        {"diffusion_distance", FloatField{&gi.diffusion_distance, diffusion_distance_range}},
        {"emission_strength", FloatField{&gi.emission_strength, at_least(0.0)}},
        {"range_boost", FloatField{&gi.range_boost, at_least(0.0)}},
        {"intensity_multiplier", FloatField{&gi.intensity_multiplier, at_least(0.0)}},
        {"per_channel", BoolField{&gi.per_channel}},
        {"segment_check", BoolField{&gi.segment_check}},
        {"light_softness", FloatField{&gi.light_softness, greater_than(0.0)}},
        {"wall_face_exponent", FloatField{&gi.wall_face_exponent, wall_face_exponent_range}},
        {"wall_lighting", BoolField{&gi.wall_lighting}},
        {"wall_faces.px", BoolField{&gi.wall_faces.px}},
        {"wall_faces.nx", BoolField{&gi.wall_faces.nx}},
        {"wall_faces.pz", BoolField{&gi.wall_faces.pz}},
        {"wall_faces.nz", BoolField{&gi.wall_faces.nz}},
        {"ao.enabled", BoolField{&gi.ao.enabled}},
        {"ao.radius", FloatField{&gi.ao.radius, ao_radius_range}},
        {"ao.power", FloatField{&gi.ao.power, greater_than(0.0)}},
        {"ao.strength", FloatField{&gi.ao.strength, between(0.0, 1.0)}},
        {"ao.dither", BoolField{&gi.ao.dither}},
        {"ao.walls", BoolField{&gi.ao.walls}},
        {"blur", BoolField{&gi.blur}},
        {"tone_map", EnumField<ToneMap>{&gi.tone_map, tone_map_names}},
        {"white_point", FloatField{&gi.white_point, greater_than(0.0)}},
        {"directional_angle_scale", FloatField{&gi.directional_angle_scale, between(0.0, 1.0)}},
        {"shadow_method", EnumField<ShadowMethod>{&gi.shadow_method, shadow_method_names}},
        {"sun_shadow_method", EnumField<SunShadowMethod>{&gi.sun_shadow_method, sun_shadow_method_names}},
        {"max_lights", IntField{&gi.max_lights, {0, 4096}}},
        {"max_shadow_proxies", IntField{&gi.max_shadow_proxies, {0, 256}}},
        {"proxy_wall_shadows", EnumField<ProxyWallShadows>{&gi.proxy_wall_shadows, proxy_wall_shadows_names}},
        {"radiosity.scale", EnumField<HeatScale>{&gi.radiosity.scale, heat_scale_names}},
        {"radiosity.rays", IntField{&gi.radiosity.rays, {1, 256}}},
        {"radiosity.steps", IntField{&gi.radiosity.steps, {1, 256}}},
        {"radiosity.epsilon", FloatField{&gi.radiosity.epsilon, radiosity_epsilon_range}},
        {"radiosity.feedback", FloatField{&gi.radiosity.feedback, radiosity_feedback_range}},
        {"radiosity.accumulate", IntField{&gi.radiosity.accumulate, {1, 1024}}},
        {"radiosity.noise", EnumField<NoiseShift>{&gi.radiosity.noise, noise_shift_names}},
        {"radiosity.frames", IntField{&gi.radiosity.frames, {1, 4096}}},
        {"gather.scale", EnumField<HeatScale>{&gi.gather.scale, heat_scale_names}},
        {"gather.rays", IntField{&gi.gather.rays, {1, 1024}}},
        {"gather.face_rays", IntField{&gi.gather.face_rays, {1, 1024}}},
        {"gather.bounces", IntField{&gi.gather.bounces, {1, 64}}},
        {"gather.frames", IntField{&gi.gather.frames, {1, 4096}}},
        {"gather.margin", IntField{&gi.gather.margin, {0, 64}}},
        {"wall_albedo", FloatField{&gi.wall_albedo, between(0.0, 1.0)}},
        {"albedo_boost", FloatField{&gi.albedo_boost, between(1.0, 10.0)}},
        {"baked_intensity", FloatField{&gi.baked_intensity, between(0.0, 16.0)}},
        {"probe_rays", IntField{&gi.probe_rays, {0, 256}}},
    }};
}

bool read_field(Reader& reader, const GiField& field, const json::Value& v,
                const std::string& path) {
    return std::visit(
        Overloaded{
            [&](const FloatField& f) { return reader.read(v, path, *f.target, f.range); },
            [&](const IntField& f) { return reader.read(v, path, *f.target, f.range); },
            [&](const BoolField& f) { return reader.read(v, path, *f.target); },
            [&](const auto& f) { return reader.read(v, path, *f.target, f.names); },
        },
        field.target);
}

// The field's current value as the JSON a file would hold (null for an enum value that
// has no name), so that validation reuses the readers' checks and messages.
json::Value current_value(const GiField& field) {
    return std::visit(Overloaded{
                          [](const FloatField& f) {
                              return json::Value(json::Value::Number{*f.target, false}, {});
                          },
                          [](const IntField& f) {
                              return json::Value(json::Value::Number{double(*f.target), true}, {});
                          },
                          [](const BoolField& f) { return json::Value(*f.target, {}); },
                          [](const auto& f) {
                              for (const auto& entry : f.names)
                                  if (entry.value == *f.target)
                                      return json::Value(std::string(entry.name), {});
                              return json::Value(nullptr, {});
                          },
                      },
                      field.target);
}

const GiField* find_field(std::span<const GiField> fields, std::string_view key) {
    for (const GiField& field : fields)
        if (field.key == key) return &field;
    return nullptr;
}

// True when `key` is "<group>.<something>".
bool is_inside(std::string_view key, std::string_view group) {
    return key.size() > group.size() && key.starts_with(group) && key[group.size()] == '.';
}

// True for the name of a nested object such as "ao".
bool is_group(std::span<const GiField> fields, std::string_view key) {
    return std::any_of(fields.begin(), fields.end(),
                       [&](const GiField& field) { return is_inside(field.key, key); });
}

// The keys directly inside `group` ("" for gi itself, else e.g. "ao"), for suggestions.
std::vector<std::string_view> keys_in_group(std::span<const GiField> fields,
                                            std::string_view group) {
    std::vector<std::string_view> keys;
    const std::size_t skip = group.empty() ? 0 : group.size() + 1;
    for (const GiField& field : fields) {
        if (!group.empty() && !is_inside(field.key, group)) continue;
        std::string_view key = field.key.substr(skip);
        key = key.substr(0, key.find('.'));
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
    return keys;
}

// Reads the gi object (group "") or one nested in it (group "ao").
bool read_group(Reader& reader, const json::Value& object, const std::string& group,
                std::span<const GiField> fields) {
    const std::string path = group.empty() ? "gi" : "gi." + group;
    const std::string prefix = group.empty() ? "" : group + ".";
    if (!reader.expect(object, path, json::Type::object)) return false;
    for (const json::Member& member : object.as_object()) {
        const std::string key = prefix + member.key;
        const bool plain_key = member.key.find('.') == std::string::npos; // no "ao.radius" alias
        if (plain_key && group.empty() && is_group(fields, key)) {
            read_group(reader, member.value, key, fields);
        } else if (const GiField* field = plain_key ? find_field(fields, key) : nullptr) {
            read_field(reader, *field, member.value, path + "." + member.key);
        } else {
            reader.fail_unknown_key(member.key, member.key_position, path,
                                    keys_in_group(fields, group));
        }
        if (!reader.ok()) return false;
    }
    return true;
}

} // namespace

bool read_gi_settings(Reader& reader, const json::Value& object, GiSettings& gi) {
    const auto fields = gi_fields(gi);
    return read_group(reader, object, "", fields);
}

bool read_gi_key(Reader& reader, std::string_view key, const json::Value& value, GiSettings& gi) {
    const auto fields = gi_fields(gi);
    const std::string path = "gi." + std::string(key);
    if (const GiField* field = find_field(fields, key))
        return read_field(reader, *field, value, path);
    if (is_group(fields, key)) {
        std::string what = "is an object; set its keys one at a time:";
        for (std::string_view inner : keys_in_group(fields, key))
            what += " " + path + "." + std::string(inner);
        return reader.fail(value.position(), path, what);
    }
    std::vector<std::string_view> all_keys;
    for (const GiField& field : fields) all_keys.push_back(field.key);
    return reader.fail_unknown_key(key, value.position(), "gi", all_keys);
}

} // namespace reading

std::vector<std::string> gi_setting_keys() {
    GiSettings gi;
    std::vector<std::string> keys;
    for (const reading::GiField& field : reading::gi_fields(gi)) keys.emplace_back(field.key);
    return keys;
}

namespace {
double number_of(const reading::GiField& field) {
    return std::visit(reading::Overloaded{
                          [](const reading::FloatField& f) { return double(*f.target); },
                          [](const reading::IntField& f) { return double(*f.target); },
                          [](const reading::BoolField& f) { return *f.target ? 1.0 : 0.0; },
                          [](const auto& f) { return double(int(*f.target)); },
                      },
                      field.target);
}
} // namespace

std::optional<double> gi_setting_value(const GiSettings& gi, std::string_view key) {
    GiSettings copy = gi; // the table binds mutable fields
    const auto fields = reading::gi_fields(copy);
    const reading::GiField* field = reading::find_field(fields, key);
    if (!field) return std::nullopt;
    return number_of(*field);
}

std::vector<double> gi_setting_values(const GiSettings& gi) {
    GiSettings copy = gi;
    std::vector<double> values;
    for (const reading::GiField& field : reading::gi_fields(copy)) values.push_back(number_of(field));
    return values;
}

Result<void> validate_gi_settings(const GiSettings& gi) {
    GiSettings checked = gi; // the table binds mutable fields; reading back writes the same values
    reading::Reader reader;
    for (const reading::GiField& field : reading::gi_fields(checked)) {
        if (!reading::read_field(reader, field, reading::current_value(field),
                                "gi." + std::string(field.key))) {
            const reading::Issue& issue = reader.issue();
            return make_error(issue.path + ": " + issue.what);
        }
    }
    return {};
}

} // namespace lantern::scene
