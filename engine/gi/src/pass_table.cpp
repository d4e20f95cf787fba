// The texture table, the methods and the sequencer (pass_table.hpp). The rows themselves
// live beside their recorders: src/rows/*.cpp.
#include "lantern/gi/pass_table.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/hash.hpp"
#include "lantern/gi/baked_light.hpp"
#include "lantern/gi/reference_indirect.hpp"
#include "lantern/gi/gather.hpp"
#include "lantern/gi/probes.hpp"
#include "lantern/gi/radiosity.hpp"
#include "lantern/scene/loader.hpp"
#include "rows/rows.hpp"

#include <algorithm>
#include <bit>
#include <mutex>
#include <string>
#include <vector>

namespace lantern::gi {
namespace {

using enum Tex;

glm::ivec2 gather_grid_size(const FrameInputs& in) {
    const HeatGrid g = gather_grid(in);
    return {g.width, g.height};
}

glm::ivec2 radiosity_grid_size(const FrameInputs& in) {
    const HeatGrid g = radiosity_grid(in);
    return {g.width, g.height};
}

constexpr TextureRow builtin_textures[builtin_tex_count] = {
    {conduction, "conduction", TexFormat::r8},
    {ao, "ao", TexFormat::r8},
    {direct, "direct", TexFormat::rgba16f},
    {shadow, "shadow", TexFormat::rg8},
    {wall_direct_px, "wall_direct_px", TexFormat::rgba16f},
    {wall_direct_nx, "wall_direct_nx", TexFormat::rgba16f},
    {wall_direct_pz, "wall_direct_pz", TexFormat::rgba16f},
    {wall_direct_nz, "wall_direct_nz", TexFormat::rgba16f},
    {emission, "emission", TexFormat::rgba16f},
    {heat_a, "heat_a", TexFormat::rgba16f, TexScale::heat_grid, false, true},
    {heat_b, "heat_b", TexFormat::rgba16f, TexScale::heat_grid, false, true},
    {heat_mask, "heat_mask", TexFormat::r8, TexScale::heat_grid, true, true},
    {indirect, "indirect", TexFormat::rgba16f},
    {blur_temp, "blur_temp", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_indirect_px, "wall_indirect_px", TexFormat::rgba16f},
    {wall_indirect_nx, "wall_indirect_nx", TexFormat::rgba16f},
    {wall_indirect_pz, "wall_indirect_pz", TexFormat::rgba16f},
    {wall_indirect_nz, "wall_indirect_nz", TexFormat::rgba16f},
    {lit, "lit", TexFormat::r8, TexScale::window, true, true},
    {direct_sun, "direct_sun", TexFormat::rgba16f, TexScale::window, false, true},
    {shadow_sun, "shadow_sun", TexFormat::rg8, TexScale::window, false, true},
    {wall_direct_sun_px, "wall_direct_sun_px", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_sun_nx, "wall_direct_sun_nx", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_sun_pz, "wall_direct_sun_pz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_sun_nz, "wall_direct_sun_nz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_px, "wall_upper_px", TexFormat::rgba16f},
    {wall_upper_nx, "wall_upper_nx", TexFormat::rgba16f},
    {wall_upper_pz, "wall_upper_pz", TexFormat::rgba16f},
    {wall_upper_nz, "wall_upper_nz", TexFormat::rgba16f},
    {wall_upper_sun_px, "wall_upper_sun_px", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_sun_nx, "wall_upper_sun_nx", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_sun_pz, "wall_upper_sun_pz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_sun_nz, "wall_upper_sun_nz", TexFormat::rgba16f, TexScale::window, false, true},
    {jfa_a, "jfa_a", TexFormat::r8, TexScale::custom, true, true, radiosity_grid_size},
    {jfa_b, "jfa_b", TexFormat::r8, TexScale::custom, true, true, radiosity_grid_size},
    {distance_field, "distance_field", TexFormat::rgba16f, TexScale::custom, false, false, radiosity_grid_size},
    {distance_steps, "distance_steps", TexFormat::r8, TexScale::custom, true, true, radiosity_grid_size},
    {radiosity_light, "radiosity_light", TexFormat::rgba16f, TexScale::custom, false, true, radiosity_grid_size},
    {radiosity, "radiosity", TexFormat::rgba16f, TexScale::custom, false, false, radiosity_grid_size},
    {gather_face_a, "gather_face_a", TexFormat::rgba16f, TexScale::custom, false, true, gather_face_size},
    {gather_face_b, "gather_face_b", TexFormat::rgba16f, TexScale::custom, false, true, gather_face_size},
    {gather_ground, "gather_ground", TexFormat::rgba16f, TexScale::custom, false, false, gather_grid_size},
    {direct_mixed, "direct_mixed", TexFormat::rgba16f, TexScale::window, false, true},
    {shadow_mixed, "shadow_mixed", TexFormat::rg8, TexScale::window, false, true},
    {wall_direct_mixed_px, "wall_direct_mixed_px", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_mixed_nx, "wall_direct_mixed_nx", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_mixed_pz, "wall_direct_mixed_pz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_mixed_nz, "wall_direct_mixed_nz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_mixed_px, "wall_upper_mixed_px", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_mixed_nx, "wall_upper_mixed_nx", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_mixed_pz, "wall_upper_mixed_pz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_mixed_nz, "wall_upper_mixed_nz", TexFormat::rgba16f, TexScale::window, false, true},
    {direct_mixed_sun, "direct_mixed_sun", TexFormat::rgba16f, TexScale::window, false, true},
    {shadow_mixed_sun, "shadow_mixed_sun", TexFormat::rg8, TexScale::window, false, true},
    {wall_direct_mixed_sun_px, "wall_direct_mixed_sun_px", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_mixed_sun_nx, "wall_direct_mixed_sun_nx", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_mixed_sun_pz, "wall_direct_mixed_sun_pz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_mixed_sun_nz, "wall_direct_mixed_sun_nz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_mixed_sun_px, "wall_upper_mixed_sun_px", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_mixed_sun_nx, "wall_upper_mixed_sun_nx", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_mixed_sun_pz, "wall_upper_mixed_sun_pz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_upper_mixed_sun_nz, "wall_upper_mixed_sun_nz", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_view, "baked_view", TexFormat::rgba16f},
    {baked_ground, "baked_ground", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_face_px, "baked_face_px", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_face_nx, "baked_face_nx", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_face_pz, "baked_face_pz", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_face_nz, "baked_face_nz", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_pulse_ground, "baked_pulse_ground", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_pulse_face_px, "baked_pulse_face_px", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_pulse_face_nx, "baked_pulse_face_nx", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_pulse_face_pz, "baked_pulse_face_pz", TexFormat::rgba16f, TexScale::window, false, true},
    {baked_pulse_face_nz, "baked_pulse_face_nz", TexFormat::rgba16f, TexScale::window, false, true},
    {probes, "probes", TexFormat::rgba16f, TexScale::custom, false, false, probe_texture_size},
};

constexpr bool rows_in_order() {
    for (int t = 0; t < builtin_tex_count; ++t)
        if (int(builtin_textures[t].id) != t) return false;
    return true;
}
static_assert(rows_in_order(), "builtin_textures must list the textures in the order of Tex");

// Seed 000's heat diffusion: the pipeline order.
constexpr const PassRow* heat_rows[] = {
    &rows::conduction, &rows::ao,   &rows::directional,   &rows::direct, &rows::emission,
    &rows::heat,       &rows::blur, &rows::wall_indirect, &rows::probes, &rows::mixed, &rows::baked_sample, &rows::baked, &rows::lit,
};
// Seed 003's radiosity: the same direct light and emission, then the distance field and the
// raymarch in place of heat; the blur is the seed's denoiser.
constexpr const PassRow* radiosity_rows[] = {
    &rows::conduction,     &rows::ao,        &rows::directional, &rows::direct,   &rows::emission,
    &rows::distance_field, &rows::radiosity, &rows::blur,   &rows::wall_indirect, &rows::probes, &rows::mixed, &rows::baked_sample, &rows::baked, &rows::lit,
};

// The gather method (physical): Lantern's direct light, then the wall faces' bounces and the
// ground gather in place of emission and heat; the blur smooths the gather's ray pattern.
// (It writes wall_indirect_* itself: no wall_indirect row.)
constexpr const PassRow* gather_rows[] = {
    &rows::conduction, &rows::ao, &rows::directional, &rows::direct, &rows::gather, &rows::blur, &rows::probes, &rows::mixed, &rows::baked_sample, &rows::baked, &rows::lit,
};

// The registry: the built-in textures, rows and methods, then what add_texture/add_row
// added at start-up. Read without a lock afterwards (pass_table.hpp, "Threads").
struct Registry {
    std::array<TextureRow, tex_count> textures{};
    int texture_count = 0;
    std::array<PassRow, pass_count> rows{}; // copies of the added rows (built-ins: rows::*)
    std::array<const PassRow*, pass_count> row_of{};
    int pass_count_used = 0;
    // For each pass id, the positions of its row's settings in gi_setting_keys(): resolved
    // once, so a frame hashes settings without looking up names.
    std::array<std::vector<int>, pass_count> setting_indices;
    struct MethodRows {
        Method method;
        std::vector<const PassRow*> rows;
    };
    std::vector<MethodRows> methods;
    std::mutex adding; // add_texture/add_row among themselves

    Registry() {
        for (const TextureRow& t : builtin_textures) textures[std::size_t(texture_count++)] = t;
        methods.push_back({{scene::GiMethod::heat, "heat", {}}, {std::begin(heat_rows), std::end(heat_rows)}});
        methods.push_back(
            {{scene::GiMethod::radiosity, "radiosity", {}}, {std::begin(radiosity_rows), std::end(radiosity_rows)}});
        methods.push_back({{scene::GiMethod::gather, "gather", {}}, {std::begin(gather_rows), std::end(gather_rows)}});
        const std::vector<std::string> keys = scene::gi_setting_keys();
        for (MethodRows& m : methods) {
            m.method.rows = m.rows;
            for (const PassRow* r : m.rows) {
                row_of[std::size_t(r->pass)] = r;
                auto indices = resolve_settings(*r, keys);
                LANTERN_VERIFY(indices.has_value(), "a built-in pass row lists a setting that is not a gi key");
                setting_indices[std::size_t(r->pass)] = std::move(*indices);
            }
        }
        pass_count_used = builtin_pass_count;
    }

    static std::optional<std::vector<int>> resolve_settings(const PassRow& row, const std::vector<std::string>& keys) {
        std::vector<int> out;
        for (std::string_view key : row.settings) {
            const auto it = std::find(keys.begin(), keys.end(), key);
            if (it == keys.end()) return std::nullopt;
            out.push_back(int(it - keys.begin()));
        }
        return out;
    }
};

Registry& registry() {
    static Registry r;
    return r;
}

const std::vector<int>& setting_indices(const PassRow& row) {
    Registry& reg = registry();
    if (int(row.pass) < pass_count && reg.row_of[std::size_t(row.pass)] == &row)
        return reg.setting_indices[std::size_t(row.pass)];
    // A row of a method built in code (tests): resolved on each call.
    thread_local std::vector<int> indices;
    auto found = Registry::resolve_settings(row, scene::gi_setting_keys());
    LANTERN_VERIFY(found.has_value(), "a pass row lists a setting that is not a gi key");
    indices = std::move(*found);
    return indices;
}

bool is_file_stem(std::string_view name) {
    if (name.empty() || name.size() > 64) return false;
    for (char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
    return true;
}

// What a row's own work depends on, without its upstream textures.
std::uint64_t own_key(const PassRow& row, const FrameInputs& in, const PassPlan& plan, const InputKeys& inputs,
                      std::span<const double> settings) {
    Hasher h(inputs.window);
    h.add_string(row.name);
    for (std::uint64_t w : row.outputs(in).words) h.add(w);
    if (row.inputs & input_walls) h.add(inputs.walls);
    if (row.inputs & input_lights) h.add(inputs.lights);
    if (row.inputs & input_proxies) h.add(inputs.proxies);
    if (row.inputs & input_suns) h.add(inputs.suns);
    if (row.inputs & input_mixed_suns) h.add(inputs.mixed_suns);
    if (row.inputs & input_wall_height) h.add(in.wall_height);
    if (row.inputs & input_walls_in_window) h.add(plan.has_walls_in_window);
    if (row.inputs & input_baked) h.add(inputs.baked);
    if (row.inputs & input_baked_pulse) h.add(inputs.baked_pulse);
    if (row.inputs & input_mixed_lights) h.add(inputs.mixed);
    for (int i : setting_indices(row)) h.add(i).add(settings[std::size_t(i)]);
    return h.value();
}

} // namespace

const TextureRow& texture_row(Tex t) {
    const Registry& reg = registry();
    LANTERN_ASSERT(int(t) < reg.texture_count, "texture id not registered");
    return reg.textures[std::size_t(t)];
}

const char* tex_name(Tex t) { return texture_row(t).name.data(); }

int registered_texture_count() { return registry().texture_count; }

std::optional<Tex> texture_by_name(std::string_view name) {
    const Registry& reg = registry();
    for (int t = 0; t < reg.texture_count; ++t)
        if (reg.textures[std::size_t(t)].name == name) return Tex(t);
    return std::nullopt;
}

glm::ivec2 texture_size(Tex t, const FrameInputs& in) {
    const TextureRow& row = texture_row(t);
    if (row.scale == TexScale::heat_grid) {
        const HeatGrid g = heat_grid(in.window, in.settings.heat_scale);
        return {g.width, g.height};
    }
    if (row.scale == TexScale::custom) return row.size(in);
    return {in.window.width, in.window.height};
}

TexSet PassRow::outputs(const FrameInputs& in) const {
    if (writes_for) return writes_for(in);
    TexSet set;
    for (Tex t : writes) set.add(t);
    return set;
}

const Method& method(scene::GiMethod id) {
    Registry& reg = registry();
    for (const Registry::MethodRows& m : reg.methods)
        if (m.method.id == id) return m.method;
    LANTERN_VERIFY(false, "gi.method has no method in the pass table");
    return reg.methods[0].method;
}

std::vector<const Method*> methods() {
    std::vector<const Method*> out;
    for (const Registry::MethodRows& m : registry().methods) out.push_back(&m.method);
    return out;
}

const PassRow* find_row(const Method& m, Pass pass) {
    for (const PassRow* row : m.rows)
        if (row->pass == pass) return row;
    return nullptr;
}

const PassRow* find_row(Pass pass) {
    if (int(pass) >= pass_count) return nullptr;
    return registry().row_of[std::size_t(pass)];
}

const char* pass_name(Pass p) {
    const PassRow* row = find_row(p);
    return row ? row->name.data() : "?";
}

int registered_pass_count() { return registry().pass_count_used; }

Result<Tex> add_texture(TextureRow row) {
    Registry& reg = registry();
    std::lock_guard lock(reg.adding);
    const std::string what = "add_texture(\"" + std::string(row.name) + "\"): ";
    if (!is_file_stem(row.name)) return make_error(what + "the name must be 1-64 of a-z, 0-9 and _", 1);
    if (texture_by_name(row.name)) return make_error(what + "a texture of that name exists", 1);
    if (row.scale == TexScale::custom && !row.size) return make_error(what + "a custom scale needs a size function", 1);
    if (reg.texture_count >= tex_count)
        return make_error(what + "the texture table is full (" + std::to_string(tex_count) + ")", 1);
    row.id = Tex(reg.texture_count);
    reg.textures[std::size_t(reg.texture_count)] = row;
    ++reg.texture_count;
    return row.id;
}

Result<Pass> add_row(scene::GiMethod id, Pass after, PassRow row) {
    Registry& reg = registry();
    std::lock_guard lock(reg.adding);
    const std::string what = "add_row(\"" + std::string(row.name) + "\"): ";
    Registry::MethodRows* m = nullptr;
    for (Registry::MethodRows& candidate : reg.methods)
        if (candidate.method.id == id) m = &candidate;
    if (!m) return make_error(what + "no such gi.method", 1);
    const auto at = std::find_if(m->rows.begin(), m->rows.end(), [&](const PassRow* r) { return r->pass == after; });
    if (at == m->rows.end())
        return make_error(what + "pass '" + pass_name(after) + "' is not in gi.method " + std::string(m->method.name), 1);
    if (!is_file_stem(row.name)) return make_error(what + "the name must be 1-64 of a-z, 0-9 and _", 1);
    for (int p = 0; p < reg.pass_count_used; ++p)
        if (reg.row_of[std::size_t(p)] && reg.row_of[std::size_t(p)]->name == row.name)
            return make_error(what + "a pass of that name exists", 1);
    if (!row.record || !row.reference) return make_error(what + "a row needs a recorder and a reference", 1);
    for (std::span<const Tex> list : {row.reads, row.writes})
        for (Tex t : list)
            if (int(t) >= reg.texture_count) return make_error(what + "a texture id is not registered", 1);
    auto indices = Registry::resolve_settings(row, scene::gi_setting_keys());
    if (!indices) return make_error(what + "a listed setting is not a gi key (docs/scenes.md, the gi table)", 1);
    if (reg.pass_count_used >= pass_count)
        return make_error(what + "the pass table is full (" + std::to_string(pass_count) + ")", 1);
    const int id_index = reg.pass_count_used++;
    row.pass = Pass(id_index);
    PassRow& stored = reg.rows[std::size_t(id_index)];
    stored = row;
    reg.row_of[std::size_t(id_index)] = &stored;
    reg.setting_indices[std::size_t(id_index)] = std::move(*indices);
    m->rows.insert(at + 1, &stored);
    m->method.rows = m->rows;
    return row.pass;
}

PassPlan plan_passes(const FrameInputs& in, bool lit_image, Pass through) {
    PassPlan plan;
    plan.has_walls_in_window = walls_in_window(in);
    for (int p = 0; p < pass_count; ++p) plan.reason[p] = "not in gi.method";
    bool requested = true;
    for (const PassRow* row : method(in.settings.method).rows) {
        const char* why = requested ? nullptr : "not requested";
        if (!why && row->not_needed) why = row->not_needed(in, lit_image, plan.has_walls_in_window);
        if (why) {
            plan.reason[int(row->pass)] = why;
        } else {
            plan.run.add(row->pass);
            plan.reason[int(row->pass)] = {};
        }
        if (row->pass == through) requested = false;
    }
    return plan;
}

TexSet textures_written(const FrameInputs& in, const PassPlan& plan) {
    TexSet set;
    for (const PassRow* row : method(in.settings.method).rows)
        if (plan.run.has(row->pass)) set |= row->outputs(in);
    return set;
}

std::uint64_t texture_bytes(const FrameInputs& in, const PassPlan& plan, TextureStorage storage) {
    const TexSet written = textures_written(in, plan);
    std::uint64_t total = 0;
    for (int t = 0; t < registered_texture_count(); ++t) {
        if (!written.has(Tex(t))) continue;
        const TextureRow& row = texture_row(Tex(t));
        const glm::ivec2 size = texture_size(Tex(t), in);
        const std::uint64_t w = std::uint64_t(std::max(size.x, 0)), h = std::uint64_t(std::max(size.y, 0));
        if (storage == TextureStorage::gpu) {
            const std::uint64_t texel = row.words32 ? 4 : std::uint64_t(bytes_per_texel(row.format));
            total += ((w + 3) & ~std::uint64_t(3)) * h * texel;
        } else {
            total += w * h * std::uint64_t(channel_count(row.format)) * sizeof(float);
        }
    }
    return total;
}

Result<void> check_texture_budget(const FrameInputs& in, const PassPlan& plan, TextureStorage storage) {
    const std::uint64_t need = texture_bytes(in, plan, storage);
    if (need <= max_gi_texture_bytes) return {};
    const auto mib = [](std::uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20) + " MiB"; };
    return make_error("GI window of " + std::to_string(in.window.width) + " x " + std::to_string(in.window.height) +
                          " texels needs " + mib(need) + " of " +
                          (storage == TextureStorage::gpu ? "GPU" : "reference") + " textures, over the budget of " +
                          mib(max_gi_texture_bytes) + " (docs/gi.md, \"Memory budget\"); lower gi.resolution or gi.padding",
                      2);
}

InputKeys input_keys_of(const FrameInputs& in) {
    InputKeys k;
    k.window = hash_window(in.window);
    Hasher walls;
    walls.add(in.walls.width).add(in.walls.height).add(in.walls.origin.x).add(in.walls.origin.y)
        .add(in.walls.phase.x).add(in.walls.phase.y);
    walls.add_bytes(in.walls.cells, std::size_t(in.walls.width) * std::size_t(in.walls.height));
    walls.add_span(std::span(in.materials)); // what the walls reflect and emit
    k.walls = walls.value();
    k.lights = Hasher().add_span(std::span(in.point_lights)).add_span(std::span(in.emissive_lights)).value();
    k.mixed = Hasher().add_span(std::span(in.mixed_lights)).add_span(std::span(in.mixed_emissives)).value();
    k.proxies = Hasher().add_span(std::span(in.proxies)).value();
    k.suns = Hasher().add_span(std::span(in.directional_lights)).value();
    k.baked = baked_input_key(in);
    k.baked_pulse = baked_pulse_key(in);
    k.mixed_suns = mixed_suns_key(in);
    return k;
}

std::uint64_t baked_input_key(const FrameInputs& in) {
    if (!in.baked) return 0;
    const BakedSun sun = baked_sun_of(in);
    if (sun.key < 0) return in.baked->key;
    return Hasher().add(in.baked->key).add(sun.key).add(sun.blend).add(sun.color.r).add(sun.color.g).add(sun.color.b).value();
}

std::uint64_t mixed_suns_key(const FrameInputs& in) {
    Hasher h;
    for (const GpuDirectionalLight& sun : in.directional_lights)
        if (is_mixed_sun(sun)) h.add_bytes(&sun, sizeof sun);
    return h.value();
}

std::uint64_t baked_pulse_key(const FrameInputs& in) {
    return in.baked && in.baked->pulsing ? Hasher().add(in.baked_pulse).value() : 0;
}

void Convergence::advance(PassSet ran) {
    for (std::size_t p = 0; p < std::size_t(pass_count); ++p) {
        if (!ran.has(Pass(p)) || settled_key[p] == 0) continue;
        if (frames[p] < 0xFFFF) ++frames[p];
        if (age[p] < 0xFFFF) ++age[p];
    }
}

std::array<std::uint64_t, pass_count> derive_keys(const FrameInputs& in, PassPlan& plan, const InputKeys& inputs,
                                                  Convergence* convergence) {
    return derive_keys(method(in.settings.method), in, plan, inputs, convergence);
}

std::array<std::uint64_t, pass_count> derive_keys(const Method& m, const FrameInputs& in, PassPlan& plan,
                                                  const InputKeys& inputs, Convergence* convergence) {
    std::array<std::uint64_t, pass_count> keys{};
    // The settings' values change rarely: kept per thread while the settings stay equal.
    thread_local std::optional<scene::GiSettings> last_settings;
    thread_local std::vector<double> settings;
    if (!last_settings || !(*last_settings == in.settings)) {
        settings = scene::gi_setting_values(in.settings);
        last_settings = in.settings;
    }
    const auto rows = m.rows;
    // Each planned row's own key and outputs, once.
    std::array<std::uint64_t, pass_count> own{};
    std::array<TexSet, pass_count> outputs{};
    for (const PassRow* row : rows)
        if (plan.run.has(row->pass)) {
            own[int(row->pass)] = own_key(*row, in, plan, inputs, settings);
            outputs[int(row->pass)] = row->outputs(in);
        }
    std::array<std::uint64_t, tex_count> producer{}; // key of the planned row that last wrote each texture
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const PassRow& row = *rows[i];
        if (!plan.run.has(row.pass)) continue;
        // `reset` is the same key without the reads whose changes keep a converging row's
        // history (PassRow::history_keeps).
        Hasher h(own[int(row.pass)]), reset(own[int(row.pass)]);
        for (Tex t : row.reads) {
            h.add(producer[int(t)]);
            const bool keeps = std::find(row.history_keeps.begin(), row.history_keeps.end(), t) != row.history_keeps.end();
            reset.add(keeps ? 0 : producer[int(t)]);
        }
        const TexSet out = outputs[int(row.pass)];
        // Later rows that overwrite an output in place change what this row leaves behind.
        for (std::size_t j = i + 1; j < rows.size(); ++j) {
            const Pass later = rows[j]->pass;
            if (plan.run.has(later) && outputs[int(later)].intersects(out)) {
                h.add(own[int(later)]);
                reset.add(own[int(later)]);
            }
        }
        keys[int(row.pass)] = h.value();
        if (row.converge_frames) {
            // Settled key = without history; `frames` counts the frames run since it changed,
            // `age` those since the history started afresh (what the row sees).
            const std::size_t p = std::size_t(row.pass);
            int frames = 0, age = 0;
            if (convergence) {
                if (convergence->reset_key[p] != reset.value()) {
                    convergence->reset_key[p] = reset.value();
                    convergence->age[p] = 0;
                    convergence->settled_key[p] = keys[p];
                    convergence->frames[p] = 0;
                } else if (convergence->settled_key[p] != keys[p]) {
                    convergence->settled_key[p] = keys[p];
                    convergence->frames[p] = 0;
                }
                frames = convergence->frames[p];
                age = convergence->age[p];
            }
            plan.history[p] = std::uint16_t(age);
            const int last = std::max(1, row.converge_frames(in)) - 1;
            keys[p] = Hasher(keys[p]).add(std::min(frames, last)).add(convergence ? convergence->epoch : 0u).value();
        }
        out.for_each([&](Tex t) { producer[std::size_t(t)] = keys[int(row.pass)]; });
    }
    return keys;
}

// ---- the reference store and sequencer

const Texture& ReferenceStore::at(Tex t) const {
    const Texture* found = find(t);
    LANTERN_ASSERT(found != nullptr, "a reference pass reads a texture no earlier pass wrote");
    return *found;
}

const Texture* ReferenceStore::find(Tex t) const {
    const auto& slot = textures[std::size_t(t)];
    return slot ? &*slot : nullptr;
}

void ReferenceStore::put(Tex t, Texture texture) {
    texture.name = tex_name(t);
    textures[std::size_t(t)] = std::move(texture);
}

ShadingInputs ReferenceStore::shading_inputs(const FrameInputs& in) const {
    ShadingInputs s;
    s.frame = &in;
    s.direct = find(Tex::direct);
    s.indirect = find(Tex::indirect);
    s.ao = find(Tex::ao);
    s.shadow = find(Tex::shadow);
    for (int f = 0; f < 4; ++f) {
        s.wall_direct[std::size_t(f)] = find(Tex(int(Tex::wall_direct_px) + f));
        s.wall_indirect[std::size_t(f)] = find(Tex(int(Tex::wall_indirect_px) + f));
        s.wall_upper[std::size_t(f)] = find(Tex(int(Tex::wall_upper_px) + f));
    }
    return s;
}

void execute_reference(const FrameInputs& in, const PassPlan& plan, PassSet subset, const RefOptions& options,
                       ReferenceStore& store, PassTimer timed, void* user) {
    for (const PassRow* row : method(in.settings.method).rows) {
        if (!plan.run.has(row->pass) || !subset.has(row->pass)) continue;
        const std::int64_t start = now_ns();
        ReferenceContext context{in, plan, options, store, 0, plan.history[int(row->pass)]};
        const int iterations = row->iteration_count(in);
        for (context.iteration = 0; context.iteration < iterations; ++context.iteration) row->reference(context);
        if (timed) timed(user, row->pass, start, now_ns());
    }
}

void release_unwritten(const FrameInputs& in, const PassPlan& plan, ReferenceStore& store) {
    const TexSet written = textures_written(in, plan);
    for (int t = 0; t < registered_texture_count(); ++t)
        if (!written.has(Tex(t))) store.textures[std::size_t(t)].reset();
    if (!written.has(Tex::lit)) store.lit.reset();
}

} // namespace lantern::gi
