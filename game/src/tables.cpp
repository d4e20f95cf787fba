#include "lantern/game/tables.hpp"

#include "lantern/core/file.hpp"
#include "lantern/core/json.hpp"
#include "lantern/core/json_writer.hpp"
#include "lantern/scene/json_reader.hpp"
#include "lantern/scene/procedural.hpp"

#include <algorithm>

namespace lantern::game {
namespace {

using scene::reading::Fields;
using scene::reading::IntRange;
using scene::reading::Reader;

constexpr std::uint64_t max_tables_file_bytes = 1 << 20;
constexpr const char* light_keys[] = {"torch", "crystal", "lamp_post", "player"};

ItemLight GameTables::*const light_members[] = {&GameTables::torch, &GameTables::crystal, &GameTables::lamp_post,
                                                &GameTables::player};

GameTables make_defaults() {
    GameTables t;
    t.materials = scene::cave_materials();
    // Ambient: a dim fill in each light's hue, so a model's side away from a torch is not
    // black but tinted by it (seed 001).
    t.torch = {{1.0f, 0.62f, 0.28f}, 1.0f, 6.5f, 1.2f, {0.06f, 0.035f, 0.015f}};
    t.crystal = {{0.3f, 0.6f, 1.0f}, 0.9f, 4.0f, 0.0f, {0.012f, 0.025f, 0.05f}};
    t.lamp_post = {{1.0f, 0.9f, 0.7f}, 0.9f, 7.0f, 2.5f, {0.05f, 0.045f, 0.035f}};
    t.player = {{1.0f, 0.8f, 0.55f}, 0.35f, 4.0f, 1.0f, {0.02f, 0.016f, 0.011f}};
    return t;
}

void write_vec3(json::Writer& w, const char* key, glm::vec3 v) {
    w.key(key).begin_array(json::Layout::one_line).value(v.x).value(v.y).value(v.z).end();
}

} // namespace

const GameTables& default_tables() {
    static const GameTables tables = make_defaults();
    return tables;
}

std::string format_tables(const GameTables& t) {
    json::Writer w;
    w.begin_object().field("lantern_tables", tables_format_version);
    w.key("materials").begin_object();
    for (const scene::Material& m : t.materials) {
        w.key(m.name).begin_object(json::Layout::one_line);
        write_vec3(w, "albedo", m.albedo);
        write_vec3(w, "emission", m.emission);
        w.field("pulse", m.pulse);
        w.end();
    }
    w.end();
    w.key("lights").begin_object();
    for (std::size_t i = 0; i < std::size(light_keys); ++i) {
        const ItemLight& l = t.*light_members[i];
        w.key(light_keys[i]).begin_object(json::Layout::one_line);
        write_vec3(w, "color", l.color);
        w.field("intensity", l.intensity).field("radius", l.radius);
        if (light_members[i] != &GameTables::crystal) w.field("height", l.height);
        write_vec3(w, "ambient", l.ambient);
        w.end();
    }
    w.end().end();
    return w.take();
}

Result<GameTables> parse_tables(std::string_view text, const std::string& file_name) {
    auto doc = json::parse(text, file_name);
    if (!doc) return doc.error();
    Reader r("the game tables");
    GameTables t = default_tables();
    Fields top(r, *doc, "", {"lantern_tables", "materials", "lights"});
    int version = 0;
    top.required("lantern_tables", version, IntRange{1, 1 << 20});
    if (r.ok() && version != tables_format_version)
        top.fail("lantern_tables", "tables format " + std::to_string(version) + " is not supported (this build reads " +
                                       std::to_string(tables_format_version) + ")");
    if (const json::Value* mats = r.ok() ? top.find("materials") : nullptr; mats && r.expect(*mats, "materials", json::Type::object)) {
        // Keyed by the caves' material names: each tunes one; a name the caves lack is refused.
        for (const json::Member& member : mats->as_object()) {
            const std::string path = "materials." + member.key;
            auto m = std::find_if(t.materials.begin(), t.materials.end(),
                                  [&](const scene::Material& x) { return x.name == member.key; });
            if (m == t.materials.end()) {
                std::string names;
                for (const scene::Material& x : t.materials) names += (names.empty() ? "" : ", ") + x.name;
                r.fail(member.key_position, path,
                       "unknown material \"" + scene::reading::shorten(member.key) + "\" (the caves have " + names + ")");
                break;
            }
            Fields mf(r, member.value, path, {"albedo", "emission", "pulse"});
            mf.optional("albedo", m->albedo, scene::reading::between(0.0, 1.0))
                .optional("emission", m->emission, scene::reading::at_least(0.0))
                .optional("pulse", m->pulse, scene::reading::between(0.0, 60.0));
            if (!r.ok()) break;
            // Seed 004's pulsing emission: the bake keeps one pulsing part, so one frequency.
            for (const scene::Material& other : t.materials)
                if (&other != &*m && other.pulse > 0.0f && m->pulse > 0.0f && other.pulse != m->pulse) {
                    mf.fail("pulse", "every pulsing material pulses at one frequency (the bake keeps one pulsing part); \"" +
                                         other.name + "\" pulses at " + scene::reading::format_float(other.pulse) + " Hz");
                    break;
                }
            if (!r.ok()) break;
        }
    }
    if (const json::Value* lights = r.ok() ? top.find("lights") : nullptr) {
        Fields f(r, *lights, "lights", {light_keys[0], light_keys[1], light_keys[2], light_keys[3]});
        for (std::size_t i = 0; i < std::size(light_keys) && r.ok(); ++i) {
            const json::Value* v = f.find(light_keys[i]);
            if (!v) continue;
            ItemLight& l = t.*light_members[i];
            const bool point = light_members[i] != &GameTables::crystal;
            Fields lf = point ? Fields(r, *v, f.path_of(light_keys[i]), {"color", "intensity", "radius", "height", "ambient"})
                              : Fields(r, *v, f.path_of(light_keys[i]), {"color", "intensity", "radius", "ambient"});
            lf.optional("color", l.color, scene::reading::at_least(0.0))
                .optional("intensity", l.intensity, scene::reading::at_least(0.0))
                .optional("radius", l.radius, scene::reading::between(0.25, 120.0))
                .optional("ambient", l.ambient, scene::reading::between(0.0, 16.0));
            if (point) lf.optional("height", l.height, scene::reading::between(0.0, 16.0));
        }
    }
    if (!r.ok()) return scene::reading::issue_error(file_name, r.issue());
    return t;
}

Result<GameTables> read_tables(const std::string& path) {
    auto text = read_text_file(path, max_tables_file_bytes);
    if (!text) return make_error(text.error().message);
    return parse_tables(*text, path);
}

} // namespace lantern::game
