#include "lantern/game/save.hpp"

#include "lantern/core/file.hpp"
#include "lantern/core/json.hpp"
#include "lantern/core/json_writer.hpp"
#include "lantern/core/text.hpp"
#include "lantern/game/baking.hpp"
#include "lantern/scene/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <sstream>

namespace lantern::game {
namespace {

// The inventory's keys in a save, in Item order.
constexpr const char* inventory_keys[item_count] = {"wall", "torch", "crystal", "lamp_post", "tree"};

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

const char* light_mode_name(scene::LightMode m) {
    switch (m) {
    case scene::LightMode::mixed: return "mixed";
    case scene::LightMode::baked: return "baked";
    default: return "realtime";
    }
}

// A parsed JSON value written back (an extension's data): numbers written as integers
// where the text had an integer, so a value reads back as it was.
void write_value(json::Writer& w, const json::Value& v) {
    switch (v.type()) {
    case json::Type::null: w.null(); break;
    case json::Type::boolean: w.value(v.as_bool()); break;
    case json::Type::number:
        if (v.is_integer_literal() && std::abs(v.as_number()) < 9.0e15) w.value(static_cast<long long>(v.as_number()));
        else w.value(v.as_number());
        break;
    case json::Type::string: w.value(v.as_string()); break;
    case json::Type::array:
        w.begin_array(json::Layout::one_line);
        for (const json::Value& e : v.as_array()) write_value(w, e);
        w.end();
        break;
    case json::Type::object:
        w.begin_object(json::Layout::one_line);
        for (const json::Member& m : v.as_object()) {
            w.key(m.key);
            write_value(w, m.value);
        }
        w.end();
        break;
    }
}

// One entity, on one line: {"point_light": {...}, "torch": {...}}.
void write_entity(json::Writer& w, const SavedEntity& e) {
    w.begin_object(json::Layout::one_line);
    if (e.point_light) {
        const PointLight& l = *e.point_light;
        w.key("point_light").begin_object();
        write_vec(w, "position", l.position);
        w.field("height", l.height);
        write_vec(w, "color", l.color);
        w.field("intensity", l.intensity).field("radius", l.radius);
        if (l.mode != scene::LightMode::realtime) w.field("mode", light_mode_name(l.mode));
        w.end();
    }
    if (e.emissive_light) {
        const EmissiveLight& l = *e.emissive_light;
        w.key("emissive_light").begin_object();
        write_vec(w, "position", l.position);
        write_vec(w, "color", l.color);
        w.field("intensity", l.intensity).field("radius", l.radius);
        if (l.mode != scene::LightMode::realtime) w.field("mode", light_mode_name(l.mode));
        w.end();
    }
    if (e.directional_light) {
        const DirectionalLight& l = *e.directional_light;
        w.key("directional_light").begin_object();
        write_vec(w, "direction", l.direction);
        write_vec(w, "color", l.color);
        w.field("intensity", l.intensity).field("base_shadow_distance", l.base_shadow_distance);
        w.field("bounce_intensity", l.bounce_intensity);
        if (l.mode != scene::LightMode::realtime) w.field("mode", light_mode_name(l.mode));
        w.end();
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
    if (e.item) {
        w.key("item").begin_object().field("kind", inventory_keys[int(e.item->item)]).field("count", e.item->count);
        write_vec(w, "position", e.item->position);
        w.end();
    }
    if (e.probe_anchor) write_vec(w, "probe_anchor", e.probe_anchor->position);
    if (e.sun) w.field("sun", true);
    w.end();
}

// ---------------------------------------------------------------- reading
//
// Through the scene loader's typed reader (lantern/scene/json_reader.hpp): the same types,
// ranges and messages as scene files, and the lights and proxies read by the scene file's
// own functions, so a save holds no value a scene file could not.

using scene::reading::at_least;
using scene::reading::between;
using scene::reading::EnumName;
using scene::reading::Fields;
using scene::reading::greater_than;
using scene::reading::IntRange;
using scene::reading::Range;
using scene::reading::Reader;
using scene::reading::world_coordinate;

template <typename E, std::size_t K>
constexpr std::array<EnumName<E>, K> enum_names(const char* const (&names)[K]) {
    std::array<EnumName<E>, K> out{};
    for (std::size_t i = 0; i < K; ++i) out[i] = {names[i], E(i)};
    return out;
}
constexpr auto prop_kinds = enum_names<PropKind>(prop_names);
constexpr auto item_kinds = enum_names<Item>(inventory_keys);
constexpr auto world_kinds = enum_names<WorldKind>(kind_names);

void read_entity(Reader& r, const json::Value& v, const std::string& path, SavedEntity& e) {
    Fields f(r, v, path,
             {"point_light", "emissive_light", "directional_light", "shadow_proxy", "torch", "prop", "item", "probe_anchor",
              "sun"});
    if (const json::Value* m = f.find("point_light")) {
        scene::PointLight l;
        scene::reading::read_point_light(r, *m, f.path_of("point_light"), l);
        e.point_light = PointLight{l.position, l.height, l.color, l.intensity, l.radius, l.mode};
    }
    if (const json::Value* m = f.find("emissive_light")) {
        scene::EmissiveLight l;
        scene::reading::read_emissive_light(r, *m, f.path_of("emissive_light"), l);
        e.emissive_light = EmissiveLight{l.position, l.color, l.intensity, l.radius, l.mode};
    }
    if (const json::Value* m = f.find("directional_light")) {
        scene::DirectionalLight l;
        scene::reading::read_directional_light(r, *m, f.path_of("directional_light"), l);
        e.directional_light =
            DirectionalLight{l.direction, l.color, l.intensity, l.base_shadow_distance, l.bounce_intensity, l.mode};
    }
    if (const json::Value* m = f.find("shadow_proxy")) {
        scene::ShadowProxy proxy;
        scene::reading::read_shadow_proxy(r, *m, f.path_of("shadow_proxy"), proxy);
        e.shadow_proxy = ShadowProxy{proxy};
    }
    if (const json::Value* m = f.find("torch")) {
        Torch t;
        Fields(r, *m, f.path_of("torch"), {"base_intensity", "phase"})
            .optional("base_intensity", t.base_intensity, at_least(0.0))
            .optional("phase", t.phase, scene::reading::any_number);
        if (!e.point_light && r.ok()) f.fail("torch", "a torch needs a point_light on the same entity");
        e.torch = t;
    }
    if (f.find("prop")) {
        Prop prop;
        Fields(r, *f.find("prop"), f.path_of("prop"), {"kind", "position"})
            .required("kind", prop.kind, prop_kinds)
            .required("position", prop.position, world_coordinate);
        e.prop = prop;
    }
    if (const json::Value* m = f.find("item")) {
        DroppedItem item;
        Fields(r, *m, f.path_of("item"), {"kind", "count", "position"})
            .required("kind", item.item, item_kinds)
            .optional("count", item.count, IntRange{1, Inventory::max_stack})
            .required("position", item.position, world_coordinate);
        item.age = item_pickup_delay; // on the ground already: no hop
        e.item = item;
    }
    if (f.find("probe_anchor")) {
        ProbeAnchor anchor;
        f.required("probe_anchor", anchor.position, world_coordinate);
        e.probe_anchor = anchor;
    }
    f.optional("sun", e.sun);
    if (e.sun && !e.directional_light && r.ok()) f.fail("sun", "a sun needs a directional_light");
}

void read_edit(Reader& r, const json::Value& v, const std::string& path, systems::Streaming::EditedChunk& out) {
    constexpr int limit = 1 << 24;
    Fields f(r, v, path, {"chunk", "rows"});
    f.required("chunk", out.coord, IntRange{-limit, limit});
    const json::Value* rows = f.find_required("rows");
    if (!rows) return;
    constexpr int n = systems::chunk_size;
    if (!rows->is_array() || rows->as_array().size() != std::size_t(n)) {
        f.fail("rows", "expected an array of " + std::to_string(n) + " strings");
        return;
    }
    out.cells.assign(std::size_t(n * n), 0);
    for (int row = 0; row < n; ++row) {
        const json::Value& line = rows->as_array()[std::size_t(row)];
        const std::string p = scene::reading::index_path(f.path_of("rows"), std::size_t(row));
        std::string s;
        if (!r.read(line, p, s)) return;
        if (s.size() != std::size_t(n)) {
            r.fail(line.position(), p,
                   "expected " + std::to_string(n) + " characters, got " + std::to_string(s.size()));
            return;
        }
        for (int col = 0; col < n; ++col) {
            const char ch = s[std::size_t(col)];
            if (ch != '#' && ch != '.' && !(ch >= 'a' && ch <= 'z')) {
                r.fail(json::Position{line.position().line, line.position().column + 1 + col}, p,
                       "expected '#' (wall), '.' (floor) or a..z (a wall of material 0..25)");
                return;
            }
            out.cells[std::size_t(row * n + col)] =
                ch == '#' ? scene::default_wall_cell : ch == '.' ? 0 : scene::material_cell(ch - 'a');
        }
    }
}

// Every item of the optional array `key` of `top`, read by `read_item` (stops at a problem).
template <typename T, typename ReadItem>
void read_list(Reader& r, Fields& top, std::string_view key, std::vector<T>& out, ReadItem read_item) {
    const json::Value* list = top.find(key);
    if (!list || !r.expect(*list, std::string(key), json::Type::array)) return;
    for (std::size_t i = 0; i < list->as_array().size() && r.ok(); ++i) {
        T item;
        read_item(list->as_array()[i], scene::reading::index_path(std::string(key), i), item);
        if (r.ok()) out.push_back(std::move(item));
    }
}

} // namespace

SaveState capture_save(ecs::World& world, const systems::Streaming& streaming, const WorldSpec& spec) {
    SaveState s;
    s.world = spec;
    world.view<Player, Transform>().each([&](const Player&, const Transform& t) { s.player = {t.position.x, t.position.z}; });
    if (world.has_resource<DayCycle>()) s.day = world.resource<DayCycle>();
    if (world.has_resource<Inventory>()) s.inventory = world.resource<Inventory>();
    // Every entity with a game component, in entity order (stable between saves).
    std::vector<ecs::Entity> entities;
    auto collect = [&](ecs::Entity e) { entities.push_back(e); };
    world.view<PointLight>().each([&](ecs::Entity e, const PointLight&) { collect(e); });
    world.view<EmissiveLight>().each([&](ecs::Entity e, const EmissiveLight&) { collect(e); });
    world.view<DirectionalLight>().each([&](ecs::Entity e, const DirectionalLight&) { collect(e); });
    world.view<ShadowProxy>().each([&](ecs::Entity e, const ShadowProxy&) { collect(e); });
    world.view<Prop>().each([&](ecs::Entity e, const Prop&) { collect(e); });
    world.view<DroppedItem>().each([&](ecs::Entity e, const DroppedItem&) { collect(e); });
    std::sort(entities.begin(), entities.end());
    entities.erase(std::unique(entities.begin(), entities.end()), entities.end());
    for (ecs::Entity e : entities) {
        if (world.try_get<Player>(e)) continue;         // the player's own light is the player's
        if (world.try_get<ExtensionOwned>(e)) continue; // its extension saves it
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
        if (auto* c = world.try_get<DroppedItem>(e)) out.item = *c;
        if (auto* c = world.try_get<ProbeAnchor>(e)) out.probe_anchor = *c;
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
    if (world.has_resource<BakedChunks>())
        for (const auto& [k, b] : world.resource<BakedChunks>().chunks) s.baked.push_back({{b->id.x, b->id.z}, b->key});
    std::sort(s.baked.begin(), s.baked.end(), [](const auto& a, const auto& b) {
        return a.chunk.y != b.chunk.y ? a.chunk.y < b.chunk.y : a.chunk.x < b.chunk.x;
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
    w.key("inventory").begin_object(json::Layout::one_line);
    for (int i = 0; i < item_count; ++i) w.field(inventory_keys[i], s.inventory.counts[std::size_t(i)]);
    w.end();
    w.key("entities").begin_array();
    for (const SavedEntity& e : s.entities) write_entity(w, e);
    w.end();
    // Edited chunks: one row of '#' (wall) and '.' (open) per line, as in a map file, and
    // a..z for walls of material 0..25 (the caves' lava and crystal).
    w.key("edits").begin_array();
    constexpr int n = systems::chunk_size;
    std::string row(std::size_t(n), '.');
    for (const auto& c : s.edits) {
        w.begin_object().key("chunk").begin_array(json::Layout::one_line).value(c.coord.x).value(c.coord.y).end();
        w.key("rows").begin_array();
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) {
                const int cell = c.cells[std::size_t(y * n + x)];
                row[std::size_t(x)] = cell == 0                                  ? '.'
                                      : cell < scene::first_material_cell || cell >= scene::first_material_cell + 26 ? '#'
                                                                                 : char('a' + cell - scene::first_material_cell);
            }
            w.value(row);
        }
        w.end().end();
    }
    w.end();
    // The baked light's cache keys (16 hex digits each).
    if (!s.baked.empty()) {
        w.key("baked").begin_array();
        for (const auto& b : s.baked) {
            char key[17];
            std::snprintf(key, sizeof(key), "%016llx", static_cast<unsigned long long>(b.key));
            w.begin_object(json::Layout::one_line).key("chunk").begin_array(json::Layout::one_line);
            w.value(b.chunk.x).value(b.chunk.y).end().field("key", key).end();
        }
        w.end();
    }
    if (!s.extensions.empty()) {
        w.key("extensions").begin_object();
        for (const auto& [name, value] : s.extensions) {
            w.key(name);
            write_value(w, value);
        }
        w.end();
    }
    w.end();
    return w.take();
}

Result<SaveState> parse_save(std::string_view text, const std::string& file_name) {
    auto doc = json::parse(text, file_name);
    if (!doc) return doc.error();
    Reader r("the save");
    SaveState s;
    Fields top(r, *doc, "", {"lantern_save", "world", "player", "day", "inventory", "entities", "edits", "baked", "extensions"});
    s.file = file_name;
    int version = 0;
    top.required("lantern_save", version, IntRange{1, 1 << 20});
    if (r.ok() && version != save_format_version)
        top.fail("lantern_save", "save format " + std::to_string(version) + " is not supported (this build reads " +
                                     std::to_string(save_format_version) + ")");
    if (const json::Value* w = top.find_required("world")) {
        int seed = int(s.world.seed);
        Fields world(r, *w, "world", {"kind", "path", "seed", "cave_threshold"});
        world.required("kind", s.world.kind, world_kinds)
            .optional("path", s.world.path)
            .optional("seed", seed, IntRange{0, 0x7FFFFFFF})
            .optional("cave_threshold", s.world.cave_threshold, between(0.0, 1.0));
        s.world.seed = std::uint32_t(seed);
        if (r.ok() && s.world.kind != WorldKind::caves && s.world.path.empty())
            r.fail(w->position(), "world.path", std::string("a ") + kind_names[int(s.world.kind)] + " world needs its file");
    }
    top.required("player", s.player, world_coordinate);
    if (const json::Value* d = top.find("day")) {
        constexpr Range day_fraction{.min = 0.0, .max = 1.0, .max_open = true};
        Fields(r, *d, "day", {"time_of_day", "running", "day_length", "drives_sun"})
            .optional("time_of_day", s.day.time_of_day, day_fraction)
            .optional("running", s.day.running)
            .optional("day_length", s.day.day_length, greater_than(0.0))
            .optional("drives_sun", s.day.drives_sun);
    }
    if (const json::Value* inv = top.find("inventory")) {
        Fields items(r, *inv, "inventory", {"wall", "torch", "crystal", "lamp_post", "tree"});
        for (int i = 0; i < item_count; ++i)
            items.optional(inventory_keys[i], s.inventory.counts[std::size_t(i)], IntRange{0, Inventory::max_stack});
    }
    read_list(r, top, "entities", s.entities,
              [&](const json::Value& v, const std::string& path, SavedEntity& e) { read_entity(r, v, path, e); });
    read_list(r, top, "edits", s.edits,
              [&](const json::Value& v, const std::string& path, systems::Streaming::EditedChunk& c) {
                  read_edit(r, v, path, c);
                  for (const auto& earlier : s.edits)
                      if (r.ok() && earlier.coord == c.coord) r.fail(v.position(), path, "chunk listed twice");
              });
    read_list(r, top, "baked", s.baked, [&](const json::Value& v, const std::string& path, SaveState::BakedKey& b) {
        constexpr int limit = 1 << 24;
        Fields f(r, v, path, {"chunk", "key"});
        f.required("chunk", b.chunk, IntRange{-limit, limit});
        std::string key;
        f.required("key", key);
        if (!r.ok()) return;
        const bool hex = key.size() == 16 && std::all_of(key.begin(), key.end(), [](char c) {
                             return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
                         });
        if (!hex) {
            f.fail("key", "expected 16 lowercase hexadecimal digits");
            return;
        }
        b.key = std::strtoull(key.c_str(), nullptr, 16);
        for (const auto& earlier : s.baked)
            if (r.ok() && earlier.chunk == b.chunk) r.fail(v.position(), path, "chunk listed twice");
    });
    // Extensions' data: an object of values, each read by its extension when loaded.
    if (const json::Value* ext = top.find("extensions"); ext && r.expect(*ext, "extensions", json::Type::object))
        for (const json::Member& m : ext->as_object()) s.extensions.emplace_back(m.key, m.value);
    if (!r.ok()) return scene::reading::issue_error(file_name, r.issue());
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

namespace {

// "DIR/stem<suffix>.ext" for the save file "DIR/stem.ext".
std::string beside_save(const std::string& save_file, const std::string& suffix) {
    const std::filesystem::path p(save_file);
    std::filesystem::path out = p.parent_path() / (p.stem().string() + suffix);
    out += p.has_extension() ? p.extension() : std::filesystem::path(".json");
    return out.string();
}

} // namespace

std::string save_slot_path(const std::string& save_file, int slot) {
    LANTERN_ASSERT(slot >= 1 && slot <= save_slot_count, "save slot out of range");
    return slot == 1 ? save_file : beside_save(save_file, "-" + std::to_string(slot));
}

std::string autosave_slot_path(const std::string& save_file, int slot) {
    LANTERN_ASSERT(slot >= 1 && slot <= autosave_slot_count, "autosave slot out of range");
    return beside_save(save_file, "-autosave-" + std::to_string(slot));
}

int next_autosave_slot(const std::string& save_file) {
    int oldest = 1;
    std::int64_t oldest_ns = 0;
    for (int k = 1; k <= autosave_slot_count; ++k) {
        const auto stamp = file_stamp(autosave_slot_path(save_file, k));
        if (!stamp) return k;
        if (k == 1 || stamp->modified_ns < oldest_ns) oldest = k, oldest_ns = stamp->modified_ns;
    }
    return oldest;
}

void apply_save(const SaveState& state, ecs::World& world, ecs::Entity player) {
    std::vector<ecs::Entity> doomed;
    auto mark = [&](ecs::Entity e) { doomed.push_back(e); };
    world.view<PointLight>().each([&](ecs::Entity e, const PointLight&) { mark(e); });
    world.view<EmissiveLight>().each([&](ecs::Entity e, const EmissiveLight&) { mark(e); });
    world.view<DirectionalLight>().each([&](ecs::Entity e, const DirectionalLight&) { mark(e); });
    world.view<ShadowProxy>().each([&](ecs::Entity e, const ShadowProxy&) { mark(e); });
    world.view<Prop>().each([&](ecs::Entity e, const Prop&) { mark(e); });
    world.view<DroppedItem>().each([&](ecs::Entity e, const DroppedItem&) { mark(e); });
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
        if (s.item) world.emplace<DroppedItem>(e, *s.item);
        if (s.probe_anchor) world.emplace<ProbeAnchor>(e, *s.probe_anchor);
        if (s.sun) world.emplace<Sun>(e);
    }
    if (!player.is_null()) {
        world.get<Transform>(player).position = glm::vec3(state.player.x, 0.0f, state.player.y);
        if (PointLight* l = world.try_get<PointLight>(player)) l->position = state.player;
    }
    world.set_resource<DayCycle>(state.day);
    world.set_resource<Inventory>(state.inventory);
}

} // namespace lantern::game
