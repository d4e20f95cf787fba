#include "lantern/scene/writer.hpp"

#include "lantern/core/json_writer.hpp"

#include <algorithm>
#include <array>
#include <charconv>

namespace lantern::scene {

namespace {

using json::Value;

constexpr std::array light_mode_names{"realtime", "mixed", "baked"};
constexpr std::array shape_names{"box", "circle"};
constexpr std::array width_mode_names{"projected", "max_axis"};
constexpr std::array penumbra_mode_names{"inward", "outward", "both"};

// The float as the double of its shortest decimal text ("0.6", not 0.6000000238418579): it
// writes as that text and reads back as the same float.
Value number(float v) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    double d = double(v);
    std::from_chars(text, end, d);
    return Value(Value::Number{d, false}, {});
}
Value number(glm::vec2 v) { return Value(Value::Array{number(v.x), number(v.y)}, {}); }
Value number(glm::vec3 v) { return Value(Value::Array{number(v.x), number(v.y), number(v.z)}, {}); }
template <std::size_t N, typename E>
Value name(const std::array<const char*, N>& names, E e) {
    return Value(names[std::size_t(e)], {});
}
json::Member member(const char* key, Value v) { return json::Member{key, {}, std::move(v)}; }

// The file's list `key` (an empty array when absent or not an array).
const Value::Array& list_of(const Value& root, std::string_view key) {
    static const Value::Array none;
    const Value* v = root.find(key);
    return v && v->is_array() ? v->as_array() : none;
}

template <typename T>
Result<Value> rewritten(const Value& root, const std::string& path, const char* key,
                        const std::vector<ListEntry<T>>& entries) {
    const Value::Array& file = list_of(root, key);
    Value::Array out;
    out.reserve(entries.size());
    for (const ListEntry<T>& e : entries) {
        if (e.original < 0) {
            out.push_back(to_json(e.value));
        } else if (std::size_t(e.original) < file.size()) {
            out.push_back(file[std::size_t(e.original)]);
        } else {
            return make_error(path + ": " + key + "[" + std::to_string(e.original) + "]: the file has " +
                              std::to_string(file.size()) + " entries (it changed since it was read)");
        }
    }
    return Value(std::move(out), {});
}

// Containers that hold only numbers (a position, a colour), and objects deeper than the
// top-level lists' entries holding only those and scalars, go on one line; the rest (the
// top level, "world", "gi", the lists, rows) one element a line.
bool flat_numbers(const Value& v) {
    if (!v.is_array()) return false;
    for (const Value& e : v.as_array())
        if (!e.is_number()) return false;
    return true;
}
json::Layout scene_layout(const Value& v, int depth) {
    if (flat_numbers(v)) return json::Layout::one_line;
    if (v.is_object() && depth >= 2) {
        for (const json::Member& m : v.as_object())
            if (m.value.is_object() || (m.value.is_array() && !flat_numbers(m.value))) return json::Layout::lines;
        return json::Layout::one_line;
    }
    return json::Layout::lines;
}

template <typename T>
void originals(std::vector<ListEntry<T>>& out, const std::vector<T>& values, std::size_t count) {
    out.clear();
    for (std::size_t i = 0; i < count; ++i) out.push_back({values[i], int(i)});
}

} // namespace

json::Value to_json(const PointLight& l) {
    Value::Object o{member("position", number(l.position)), member("height", number(l.height)),
                    member("color", number(l.color)),       member("intensity", number(l.intensity)),
                    member("radius", number(l.radius)),     member("mode", name(light_mode_names, l.mode))};
    if (l.indirect != 1.0f) o.push_back(member("indirect", number(l.indirect)));
    return Value(std::move(o), {});
}

json::Value to_json(const EmissiveLight& l) {
    Value::Object o{member("position", number(l.position)), member("color", number(l.color)),
                    member("intensity", number(l.intensity)), member("radius", number(l.radius)),
                    member("mode", name(light_mode_names, l.mode))};
    if (l.indirect != 1.0f) o.push_back(member("indirect", number(l.indirect)));
    return Value(std::move(o), {});
}

json::Value to_json(const ShadowProxy& p) {
    Value::Object o{member("position", number(p.position)), member("shape", name(shape_names, p.shape)),
                    member("size", number(p.size)), member("max_length", number(p.max_length)),
                    member("end_cap_blend", number(p.end_cap_blend)),
                    member("penumbra_width", number(p.penumbra_width)),
                    member("penumbra_length", number(p.penumbra_length)),
                    member("penumbra_power", number(p.penumbra_power)),
                    member("width_mode", name(width_mode_names, p.width_mode)),
                    member("penumbra_mode", name(penumbra_mode_names, p.penumbra_mode))};
    if (!p.is_static) o.push_back(member("static", Value(false, {})));
    return Value(std::move(o), {});
}

Result<SceneLists> scene_lists(std::string_view text, const std::string& path, const Scene& scene) {
    auto root = json::parse(text, path);
    if (!root) return root.error();
    if (!root->is_object()) return make_error(path + ":1:1: a scene file holds a JSON object");
    const std::size_t points = list_of(*root, "point_lights").size();
    const std::size_t emissives = list_of(*root, "emissive_lights").size();
    const std::size_t proxies = list_of(*root, "shadow_proxies").size();
    if (points != scene.point_lights.size() || emissives != scene.emissive_lights.size() ||
        proxies > scene.shadow_proxies.size())
        return make_error(path + ": the file's lights and proxies are not the scene's (it changed since it was read)");
    SceneLists out;
    originals(out.point_lights, scene.point_lights, points);
    originals(out.emissive_lights, scene.emissive_lights, emissives);
    originals(out.shadow_proxies, scene.shadow_proxies, proxies);
    return out;
}

Result<std::string> rewrite_scene_lists(std::string_view text, const std::string& path, const SceneLists& lists) {
    auto root = json::parse(text, path);
    if (!root) return root.error();
    if (!root->is_object()) return make_error(path + ":1:1: a scene file holds a JSON object");
    Value::Object members = root->as_object();
    auto replace = [&](const char* key, Result<Value> list) -> Result<void> {
        if (!list) return list.error();
        auto it = std::find_if(members.begin(), members.end(), [&](const json::Member& m) { return m.key == key; });
        if (it != members.end())
            it->value = std::move(*list);
        else if (!list->as_array().empty())
            members.push_back(member(key, std::move(*list)));
        return {};
    };
    if (auto ok = replace("point_lights", rewritten(*root, path, "point_lights", lists.point_lights)); !ok)
        return ok.error();
    if (auto ok = replace("emissive_lights", rewritten(*root, path, "emissive_lights", lists.emissive_lights)); !ok)
        return ok.error();
    if (auto ok = replace("shadow_proxies", rewritten(*root, path, "shadow_proxies", lists.shadow_proxies)); !ok)
        return ok.error();
    json::Writer w;
    json::write(w, Value(std::move(members), {}), scene_layout);
    return w.take();
}

Scene with_lists(const Scene& scene, std::size_t own_proxies, const SceneLists& lists) {
    Scene out = scene;
    out.point_lights.clear();
    for (const auto& e : lists.point_lights) out.point_lights.push_back(e.value);
    out.emissive_lights.clear();
    for (const auto& e : lists.emissive_lights) out.emissive_lights.push_back(e.value);
    out.shadow_proxies.clear();
    for (const auto& e : lists.shadow_proxies) out.shadow_proxies.push_back(e.value);
    for (std::size_t i = own_proxies; i < scene.shadow_proxies.size(); ++i) out.shadow_proxies.push_back(scene.shadow_proxies[i]);
    return out;
}

} // namespace lantern::scene
