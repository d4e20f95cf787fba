#include "lantern/game/save.hpp"

#include "lantern/core/file.hpp"
#include "lantern/core/json.hpp"
#include "lantern/core/json_writer.hpp"
#include "lantern/core/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <sstream>

namespace lantern::game {
namespace {

// ---------------------------------------------------------------- writing

// Vectors as one-line arrays of their floats (shortest text that reads back exactly).
template <int N>
void write_vec(json::Writer& w, std::string_view key, glm::vec<N, float> v) {
    w.key(key).begin_array(json::Layout::one_line);
    for (int i = 0; i < N; ++i) w.value(v[i]);
    w.end();
}

constexpr const char* prop_names[] = {"crystal", "tree", "lamp_post"};
constexpr const char* shape_names[] = {"box", "circle"};
constexpr const char* width_names[] = {"projected", "max_axis"};
constexpr const char* penumbra_names[] = {"inward", "outward", "both"};
constexpr const char* kind_names[] = {"caves", "map", "scene"};

// One entity, on one line: {"point_light": {...}, "torch": {...}}.
void write_entity(json::Writer& w, const SavedEntity& e) {
    w.begin_object(json::Layout::one_line);
    if (e.point_light) {
        const PointLight& l = *e.point_light;
        w.key("point_light").begin_object();
        write_vec(w, "position", l.position);
        w.field("height", l.height);
        write_vec(w, "color", l.color);
        w.field("intensity", l.intensity).field("radius", l.radius).end();
    }
    if (e.emissive_light) {
        const EmissiveLight& l = *e.emissive_light;
        w.key("emissive_light").begin_object();
        write_vec(w, "position", l.position);
        write_vec(w, "color", l.color);
        w.field("intensity", l.intensity).field("radius", l.radius).end();
    }
    if (e.directional_light) {
        const DirectionalLight& l = *e.directional_light;
        w.key("directional_light").begin_object();
        write_vec(w, "direction", l.direction);
        write_vec(w, "color", l.color);
        w.field("intensity", l.intensity).field("base_shadow_distance", l.base_shadow_distance);
        w.field("bounce_intensity", l.bounce_intensity).end();
    }
    if (e.shadow_proxy) {
        const scene::ShadowProxy& p = e.shadow_proxy->shape;
        w.key("shadow_proxy").begin_object();
        write_vec(w, "position", p.position);
        w.field("shape", shape_names[int(p.shape)]);
        write_vec(w, "size", p.size);
        w.field("max_length", p.max_length).field("end_cap_blend", p.end_cap_blend);
        w.field("penumbra_width", p.penumbra_width).field("penumbra_length", p.penumbra_length);
        w.field("penumbra_power", p.penumbra_power).field("width_mode", width_names[int(p.width_mode)]);
        w.field("penumbra_mode", penumbra_names[int(p.penumbra_mode)]).end();
    }
    if (e.torch)
        w.key("torch").begin_object().field("base_intensity", e.torch->base_intensity).field("phase", e.torch->phase).end();
    if (e.prop) {
        w.key("prop").begin_object().field("kind", prop_names[int(e.prop->kind)]);
        write_vec(w, "position", e.prop->position);
        w.end();
    }
    if (e.sun) w.field("sun", true);
    w.end();
}

// ---------------------------------------------------------------- reading

// Typed reads with the first problem kept as "<file>:<line>:<col>: <path>: <what>".
class Reader {
  public:
    explicit Reader(std::string file) : file_(std::move(file)) {}
    bool ok() const { return !error_; }
    Error error() const { return Error{*error_, 2}; }

    bool fail(const json::Value& at, const std::string& path, const std::string& what) {
        return fail(at.position(), path, what);
    }
    bool fail(json::Position at, const std::string& path, const std::string& what) {
        if (!error_)
            error_ = file_ + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": " + path + ": " + what;
        return false;
    }

    // Checks that `v` is an object with only `known` keys and every key of `required`.
    bool object(const json::Value& v, const std::string& path, std::initializer_list<std::string_view> known,
                std::initializer_list<std::string_view> required) {
        if (!v.is_object()) return fail(v, path, std::string("expected an object, got ") + json::describe(v.type()));
        for (const json::Member& m : v.as_object())
            if (std::find(known.begin(), known.end(), m.key) == known.end())
                return fail(m.key_position, path, "unknown key '" + m.key + "'");
        for (std::string_view key : required)
            if (!v.find(key)) return fail(v, path, "missing key '" + std::string(key) + "'");
        return true;
    }

    bool read(const json::Value& v, const std::string& path, float& out) {
        if (!v.is_number()) return fail(v, path, std::string("expected a number, got ") + json::describe(v.type()));
        const double d = v.as_number();
        if (!std::isfinite(float(d))) return fail(v, path, "number out of range");
        out = float(d);
        return true;
    }
    bool read(const json::Value& v, const std::string& path, int& out, int min, int max) {
        if (!v.is_number() || !v.is_integer_literal())
            return fail(v, path, std::string("expected an integer, got ") + json::describe(v.type()));
        const double d = v.as_number();
        if (d < min || d > max)
            return fail(v, path, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
        out = int(d);
        return true;
    }
    bool read(const json::Value& v, const std::string& path, bool& out) {
        if (!v.is_bool()) return fail(v, path, std::string("expected true or false, got ") + json::describe(v.type()));
        out = v.as_bool();
        return true;
    }
    bool read(const json::Value& v, const std::string& path, std::string& out) {
        if (!v.is_string()) return fail(v, path, std::string("expected a string, got ") + json::describe(v.type()));
        out = v.as_string();
        return true;
    }
    template <int N>
    bool read(const json::Value& v, const std::string& path, glm::vec<N, float>& out) {
        if (!v.is_array() || v.as_array().size() != std::size_t(N))
            return fail(v, path, "expected an array of " + std::to_string(N) + " numbers");
        for (int i = 0; i < N; ++i)
            if (!read(v.as_array()[std::size_t(i)], path + "[" + std::to_string(i) + "]", out[i])) return false;
        return true;
    }
    template <typename E, std::size_t K>
    bool read(const json::Value& v, const std::string& path, E& out, const char* const (&names)[K]) {
        std::string s;
        if (!read(v, path, s)) return false;
        for (std::size_t i = 0; i < K; ++i)
            if (s == names[i]) {
                out = E(i);
                return true;
            }
        std::string list;
        for (std::size_t i = 0; i < K; ++i) list += std::string(i ? ", " : "") + "\"" + names[i] + "\"";
        return fail(v, path, "expected one of " + list + ", got \"" + s.substr(0, 40) + "\"");
    }
    // Reads member `key` of object `v` when present (absent keys keep their defaults).
    template <typename T, typename... Extra>
    bool field(const json::Value& v, const std::string& path, std::string_view key, T& out, Extra&&... extra) {
        const json::Value* m = v.find(key);
        if (!m) return true;
        return read(*m, path + "." + std::string(key), out, std::forward<Extra>(extra)...);
    }

  private:
    std::string file_;
    std::optional<std::string> error_;
};

bool read_positive(Reader& r, const json::Value& v, const std::string& path, const char* key, float& out) {
    if (!r.field(v, path, key, out)) return false;
    if (const json::Value* m = v.find(key); m && !(out > 0.0f)) return r.fail(*m, path + "." + key, "must be > 0");
    return true;
}

bool read_entity(Reader& r, const json::Value& v, const std::string& path, SavedEntity& e) {
    if (!r.object(v, path, {"point_light", "emissive_light", "directional_light", "shadow_proxy", "torch", "prop", "sun"},
                  {}))
        return false;
    if (const json::Value* m = v.find("point_light")) {
        const std::string p = path + ".point_light";
        PointLight l;
        if (!r.object(*m, p, {"position", "height", "color", "intensity", "radius"}, {"position"}) ||
            !r.field(*m, p, "position", l.position) || !r.field(*m, p, "height", l.height) ||
            !r.field(*m, p, "color", l.color) || !r.field(*m, p, "intensity", l.intensity) ||
            !read_positive(r, *m, p, "radius", l.radius))
            return false;
        e.point_light = l;
    }
    if (const json::Value* m = v.find("emissive_light")) {
        const std::string p = path + ".emissive_light";
        EmissiveLight l;
        if (!r.object(*m, p, {"position", "color", "intensity", "radius"}, {"position"}) ||
            !r.field(*m, p, "position", l.position) || !r.field(*m, p, "color", l.color) ||
            !r.field(*m, p, "intensity", l.intensity) || !read_positive(r, *m, p, "radius", l.radius))
            return false;
        e.emissive_light = l;
    }
    if (const json::Value* m = v.find("directional_light")) {
        const std::string p = path + ".directional_light";
        DirectionalLight l;
        if (!r.object(*m, p, {"direction", "color", "intensity", "base_shadow_distance", "bounce_intensity"},
                      {"direction"}) ||
            !r.field(*m, p, "direction", l.direction) || !r.field(*m, p, "color", l.color) ||
            !r.field(*m, p, "intensity", l.intensity) ||
            !r.field(*m, p, "base_shadow_distance", l.base_shadow_distance) ||
            !r.field(*m, p, "bounce_intensity", l.bounce_intensity))
            return false;
        e.directional_light = l;
    }
    if (const json::Value* m = v.find("shadow_proxy")) {
        const std::string p = path + ".shadow_proxy";
        scene::ShadowProxy s;
        if (!r.object(*m, p,
                      {"position", "shape", "size", "max_length", "end_cap_blend", "penumbra_width", "penumbra_length",
                       "penumbra_power", "width_mode", "penumbra_mode"},
                      {"position"}) ||
            !r.field(*m, p, "position", s.position) || !r.field(*m, p, "shape", s.shape, shape_names) ||
            !r.field(*m, p, "size", s.size) || !read_positive(r, *m, p, "max_length", s.max_length) ||
            !r.field(*m, p, "end_cap_blend", s.end_cap_blend) || !r.field(*m, p, "penumbra_width", s.penumbra_width) ||
            !r.field(*m, p, "penumbra_length", s.penumbra_length) ||
            !r.field(*m, p, "penumbra_power", s.penumbra_power) ||
            !r.field(*m, p, "width_mode", s.width_mode, width_names) ||
            !r.field(*m, p, "penumbra_mode", s.penumbra_mode, penumbra_names))
            return false;
        e.shadow_proxy = ShadowProxy{s};
    }
    if (const json::Value* m = v.find("torch")) {
        const std::string p = path + ".torch";
        Torch t;
        if (!r.object(*m, p, {"base_intensity", "phase"}, {}) || !r.field(*m, p, "base_intensity", t.base_intensity) ||
            !r.field(*m, p, "phase", t.phase))
            return false;
        if (!e.point_light) return r.fail(*m, p, "a torch needs a point_light on the same entity");
        e.torch = t;
    }
    if (const json::Value* m = v.find("prop")) {
        const std::string p = path + ".prop";
        Prop prop;
        if (!r.object(*m, p, {"kind", "position"}, {"kind", "position"}) ||
            !r.field(*m, p, "kind", prop.kind, prop_names) || !r.field(*m, p, "position", prop.position))
            return false;
        e.prop = prop;
    }
    if (const json::Value* m = v.find("sun")) {
        if (!r.read(*m, path + ".sun", e.sun)) return false;
        if (e.sun && !e.directional_light) return r.fail(*m, path + ".sun", "a sun needs a directional_light");
    }
    return true;
}

bool read_edit(Reader& r, const json::Value& v, const std::string& path, systems::Streaming::EditedChunk& out) {
    if (!r.object(v, path, {"chunk", "rows"}, {"chunk", "rows"})) return false;
    const json::Value& c = *v.find("chunk");
    if (!c.is_array() || c.as_array().size() != 2) return r.fail(c, path + ".chunk", "expected an array of 2 integers");
    constexpr int limit = 1 << 24;
    if (!r.read(c.as_array()[0], path + ".chunk[0]", out.coord.x, -limit, limit) ||
        !r.read(c.as_array()[1], path + ".chunk[1]", out.coord.y, -limit, limit))
        return false;
    const json::Value& rows = *v.find("rows");
    constexpr int n = systems::chunk_size;
    if (!rows.is_array() || rows.as_array().size() != std::size_t(n))
        return r.fail(rows, path + ".rows", "expected an array of " + std::to_string(n) + " strings");
    out.cells.assign(std::size_t(n * n), 0);
    for (int row = 0; row < n; ++row) {
        const json::Value& line = rows.as_array()[std::size_t(row)];
        const std::string p = path + ".rows[" + std::to_string(row) + "]";
        std::string s;
        if (!r.read(line, p, s)) return false;
        if (s.size() != std::size_t(n))
            return r.fail(line, p, "expected " + std::to_string(n) + " characters, got " + std::to_string(s.size()));
        for (int col = 0; col < n; ++col) {
            const char ch = s[std::size_t(col)];
            if (ch != '#' && ch != '.')
                return r.fail(json::Position{line.position().line, line.position().column + 1 + col}, p,
                              "expected '#' (wall) or '.' (floor)");
            out.cells[std::size_t(row * n + col)] = ch == '#' ? 1 : 0;
        }
    }
    return true;
}

} // namespace

SaveState capture_save(ecs::World& world, const systems::Streaming& streaming, const WorldSpec& spec) {
    SaveState s;
    s.world = spec;
    world.view<Player, Transform>().each([&](const Player&, const Transform& t) { s.player = {t.position.x, t.position.z}; });
    if (world.has_resource<DayCycle>()) s.day = world.resource<DayCycle>();
    // Every entity with a game component, in entity order (stable between saves).
    std::vector<ecs::Entity> entities;
    auto collect = [&](ecs::Entity e) { entities.push_back(e); };
    world.view<PointLight>().each([&](ecs::Entity e, const PointLight&) { collect(e); });
    world.view<EmissiveLight>().each([&](ecs::Entity e, const EmissiveLight&) { collect(e); });
    world.view<DirectionalLight>().each([&](ecs::Entity e, const DirectionalLight&) { collect(e); });
    world.view<ShadowProxy>().each([&](ecs::Entity e, const ShadowProxy&) { collect(e); });
    world.view<Prop>().each([&](ecs::Entity e, const Prop&) { collect(e); });
    std::sort(entities.begin(), entities.end());
    entities.erase(std::unique(entities.begin(), entities.end()), entities.end());
    for (ecs::Entity e : entities) {
        if (world.try_get<Player>(e)) continue; // the player's own light is the player's
        SavedEntity out;
        if (auto* c = world.try_get<PointLight>(e)) out.point_light = *c;
        if (auto* c = world.try_get<EmissiveLight>(e)) out.emissive_light = *c;
        if (auto* c = world.try_get<DirectionalLight>(e)) out.directional_light = *c;
        if (auto* c = world.try_get<ShadowProxy>(e)) out.shadow_proxy = *c;
        if (auto* c = world.try_get<Torch>(e)) {
            out.torch = *c;
            out.point_light->intensity = c->base_intensity; // not this frame's flicker
        }
        if (auto* c = world.try_get<Prop>(e)) out.prop = *c;
        out.sun = world.try_get<Sun>(e) != nullptr;
        s.entities.push_back(std::move(out));
    }
    // Canonical order (by their text), so the same game saves to the same file whatever
    // order its entities were created in.
    std::vector<std::pair<std::string, std::size_t>> keyed;
    for (std::size_t i = 0; i < s.entities.size(); ++i) {
        json::Writer w;
        write_entity(w, s.entities[i]);
        keyed.push_back({w.take(), i});
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<SavedEntity> sorted;
    for (const auto& [text, i] : keyed) sorted.push_back(std::move(s.entities[i]));
    s.entities = std::move(sorted);
    s.edits = streaming.edited_chunks(world);
    std::sort(s.edits.begin(), s.edits.end(), [](const auto& a, const auto& b) {
        return a.coord.y != b.coord.y ? a.coord.y < b.coord.y : a.coord.x < b.coord.x;
    });
    return s;
}

std::string format_save(const SaveState& s) {
    json::Writer w;
    w.begin_object().field("lantern_save", save_format_version);
    w.key("world").begin_object(json::Layout::one_line).field("kind", kind_names[int(s.world.kind)]);
    w.field("path", s.world.path).field("seed", s.world.seed).field("cave_threshold", s.world.cave_threshold).end();
    write_vec(w, "player", s.player);
    w.key("day").begin_object(json::Layout::one_line).field("time_of_day", s.day.time_of_day);
    w.field("running", s.day.running).field("day_length", s.day.day_length).field("drives_sun", s.day.drives_sun).end();
    w.key("entities").begin_array();
    for (const SavedEntity& e : s.entities) write_entity(w, e);
    w.end();
    // Edited chunks: one row of '#' (wall) and '.' (open) per line, as in a map file.
    w.key("edits").begin_array();
    constexpr int n = systems::chunk_size;
    std::string row(std::size_t(n), '.');
    for (const auto& c : s.edits) {
        w.begin_object().key("chunk").begin_array(json::Layout::one_line).value(c.coord.x).value(c.coord.y).end();
        w.key("rows").begin_array();
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) row[std::size_t(x)] = c.cells[std::size_t(y * n + x)] ? '#' : '.';
            w.value(row);
        }
        w.end().end();
    }
    w.end().end();
    return w.take();
}

Result<SaveState> parse_save(std::string_view text, const std::string& file_name) {
    auto doc = json::parse(text, file_name);
    if (!doc) return doc.error();
    Reader r(file_name);
    const json::Value& root = *doc;
    SaveState s;
    if (!r.object(root, "save", {"lantern_save", "world", "player", "day", "entities", "edits"},
                  {"lantern_save", "world", "player"}))
        return r.error();
    int version = 0;
    if (!r.read(*root.find("lantern_save"), "lantern_save", version, 1, 1 << 20)) return r.error();
    if (version != save_format_version) {
        r.fail(*root.find("lantern_save"), "lantern_save",
               "save format " + std::to_string(version) + " is not supported (this build reads " +
                   std::to_string(save_format_version) + ")");
        return r.error();
    }
    const json::Value& w = *root.find("world");
    int seed = int(s.world.seed);
    if (!r.object(w, "world", {"kind", "path", "seed", "cave_threshold"}, {"kind"}) ||
        !r.field(w, "world", "cave_threshold", s.world.cave_threshold) ||
        !r.field(w, "world", "kind", s.world.kind, kind_names) || !r.field(w, "world", "path", s.world.path) ||
        !r.field(w, "world", "seed", seed, 0, 0x7FFFFFFF))
        return r.error();
    s.world.seed = std::uint32_t(seed);
    if (s.world.kind != WorldKind::caves && s.world.path.empty()) {
        r.fail(w, "world.path", std::string("a ") + kind_names[int(s.world.kind)] + " world needs its file");
        return r.error();
    }
    if (!r.read(*root.find("player"), "player", s.player)) return r.error();
    if (const json::Value* d = root.find("day")) {
        if (!r.object(*d, "day", {"time_of_day", "running", "day_length", "drives_sun"}, {}) ||
            !r.field(*d, "day", "time_of_day", s.day.time_of_day) || !r.field(*d, "day", "running", s.day.running) ||
            !r.field(*d, "day", "drives_sun", s.day.drives_sun) ||
            !read_positive(r, *d, "day", "day_length", s.day.day_length))
            return r.error();
        if (s.day.time_of_day < 0.0f || s.day.time_of_day >= 1.0f) {
            r.fail(*d->find("time_of_day"), "day.time_of_day", "must be in [0, 1)");
            return r.error();
        }
    }
    if (const json::Value* list = root.find("entities")) {
        if (!list->is_array()) {
            r.fail(*list, "entities", "expected an array");
            return r.error();
        }
        for (std::size_t i = 0; i < list->as_array().size(); ++i) {
            SavedEntity e;
            if (!read_entity(r, list->as_array()[i], "entities[" + std::to_string(i) + "]", e)) return r.error();
            s.entities.push_back(std::move(e));
        }
    }
    if (const json::Value* list = root.find("edits")) {
        if (!list->is_array()) {
            r.fail(*list, "edits", "expected an array");
            return r.error();
        }
        for (std::size_t i = 0; i < list->as_array().size(); ++i) {
            systems::Streaming::EditedChunk c;
            const std::string p = "edits[" + std::to_string(i) + "]";
            if (!read_edit(r, list->as_array()[i], p, c)) return r.error();
            for (const auto& earlier : s.edits)
                if (earlier.coord == c.coord) {
                    r.fail(list->as_array()[i], p, "chunk listed twice");
                    return r.error();
                }
            s.edits.push_back(std::move(c));
        }
    }
    return s;
}

Result<void> write_save(const std::string& path, const SaveState& state) {
    return write_file_atomic(path, format_save(state));
}

Result<SaveState> read_save(const std::string& path) {
    auto text = read_text_file(path, max_save_file_bytes);
    if (!text) return text.error();
    auto save = parse_save(*text, path);
    if (!save) return save;
    // The world file the save refers to must be there: say so naming the save and its key,
    // before the game starts making the world.
    if (save->world.kind != WorldKind::caves)
        if (auto ok = check_input_file(save->world.path); !ok)
            return make_error(printable(path + ": world.path: " + ok.error().message, 1024), 2);
    return save;
}

void apply_save(const SaveState& state, ecs::World& world, ecs::Entity player) {
    std::vector<ecs::Entity> doomed;
    auto mark = [&](ecs::Entity e) { doomed.push_back(e); };
    world.view<PointLight>().each([&](ecs::Entity e, const PointLight&) { mark(e); });
    world.view<EmissiveLight>().each([&](ecs::Entity e, const EmissiveLight&) { mark(e); });
    world.view<DirectionalLight>().each([&](ecs::Entity e, const DirectionalLight&) { mark(e); });
    world.view<ShadowProxy>().each([&](ecs::Entity e, const ShadowProxy&) { mark(e); });
    world.view<Prop>().each([&](ecs::Entity e, const Prop&) { mark(e); });
    std::sort(doomed.begin(), doomed.end());
    doomed.erase(std::unique(doomed.begin(), doomed.end()), doomed.end());
    for (ecs::Entity e : doomed)
        if (!world.try_get<Player>(e)) world.destroy(e);
    for (const SavedEntity& s : state.entities) {
        const ecs::Entity e = world.create();
        if (s.point_light) world.emplace<PointLight>(e, *s.point_light);
        if (s.emissive_light) world.emplace<EmissiveLight>(e, *s.emissive_light);
        if (s.directional_light) world.emplace<DirectionalLight>(e, *s.directional_light);
        if (s.shadow_proxy) world.emplace<ShadowProxy>(e, *s.shadow_proxy);
        if (s.torch) world.emplace<Torch>(e, *s.torch);
        if (s.prop) world.emplace<Prop>(e, *s.prop);
        if (s.sun) world.emplace<Sun>(e);
    }
    if (!player.is_null()) {
        world.get<Transform>(player).position = glm::vec3(state.player.x, 0.0f, state.player.y);
        if (PointLight* l = world.try_get<PointLight>(player)) l->position = state.player;
    }
    world.set_resource<DayCycle>(state.day);
}

} // namespace lantern::game
