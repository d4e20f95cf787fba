// The texture table, the methods and the sequencer (pass_table.hpp). The rows themselves
// live beside their recorders: src/rows/*.cpp.
#include "lantern/gi/pass_table.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/hash.hpp"
#include "lantern/gi/reference_indirect.hpp"
#include "lantern/scene/loader.hpp"
#include "rows/rows.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace lantern::gi {
namespace {

using enum Tex;

constexpr TextureRow texture_rows[tex_count] = {
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
    {direct_point, "direct_point", TexFormat::rgba16f, TexScale::window, false, true},
    {shadow_point, "shadow_point", TexFormat::rg8, TexScale::window, false, true},
    {wall_direct_point_px, "wall_direct_point_px", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_point_nx, "wall_direct_point_nx", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_point_pz, "wall_direct_point_pz", TexFormat::rgba16f, TexScale::window, false, true},
    {wall_direct_point_nz, "wall_direct_point_nz", TexFormat::rgba16f, TexScale::window, false, true},
};

constexpr bool rows_in_order() {
    for (int t = 0; t < tex_count; ++t)
        if (int(texture_rows[t].id) != t) return false;
    return true;
}
static_assert(rows_in_order(), "texture_rows must list the textures in the order of Tex");

// Seed 000's heat diffusion: the pipeline order.
constexpr const PassRow* heat_rows[] = {
    &rows::conduction, &rows::ao,   &rows::direct,        &rows::directional, &rows::emission,
    &rows::heat,       &rows::blur, &rows::wall_indirect, &rows::lit,
};
constexpr Method methods[] = {
    {scene::GiMethod::heat, "heat", heat_rows},
};

// For each row of each method, the positions of its settings in gi_setting_keys(): resolved
// once (the first frame), so a frame hashes settings without looking up names.
const std::vector<int>& setting_indices(const PassRow& row) {
    static const std::map<const PassRow*, std::vector<int>> table = [] {
        const std::vector<std::string> keys = scene::gi_setting_keys();
        std::map<const PassRow*, std::vector<int>> out;
        for (const Method& m : methods)
            for (const PassRow* r : m.rows) {
                std::vector<int>& indices = out[r];
                for (std::string_view key : r->settings) {
                    const auto it = std::find(keys.begin(), keys.end(), key);
                    LANTERN_VERIFY(it != keys.end(), "a pass row lists a setting that is not a gi key");
                    indices.push_back(int(it - keys.begin()));
                }
            }
        return out;
    }();
    const auto it = table.find(&row);
    if (it != table.end()) return it->second;
    // A row of a method built in code (tests): resolved on each call.
    thread_local std::vector<int> indices;
    indices.clear();
    const std::vector<std::string> keys = scene::gi_setting_keys();
    for (std::string_view key : row.settings) {
        const auto k = std::find(keys.begin(), keys.end(), key);
        LANTERN_VERIFY(k != keys.end(), "a pass row lists a setting that is not a gi key");
        indices.push_back(int(k - keys.begin()));
    }
    return indices;
}

// What a row's own work depends on, without its upstream textures.
std::uint64_t own_key(const PassRow& row, const FrameInputs& in, const PassPlan& plan, const InputKeys& inputs,
                      std::span<const double> settings) {
    Hasher h(inputs.window);
    h.add_string(row.name).add(row.outputs(in).bits);
    if (row.inputs & input_walls) h.add(inputs.walls);
    if (row.inputs & input_lights) h.add(inputs.lights);
    if (row.inputs & input_proxies) h.add(inputs.proxies);
    if (row.inputs & input_suns) h.add(inputs.suns);
    if (row.inputs & input_wall_height) h.add(in.wall_height);
    if (row.inputs & input_walls_in_window) h.add(plan.has_walls_in_window);
    for (int i : setting_indices(row)) h.add(i).add(settings[std::size_t(i)]);
    return h.value();
}

} // namespace

const TextureRow& texture_row(Tex t) {
    LANTERN_ASSERT(int(t) < tex_count, "texture id out of range");
    return texture_rows[int(t)];
}

const char* tex_name(Tex t) { return texture_row(t).name.data(); }

std::optional<Tex> texture_by_name(std::string_view name) {
    for (const TextureRow& row : texture_rows)
        if (row.name == name) return row.id;
    return std::nullopt;
}

glm::ivec2 texture_size(Tex t, const FrameInputs& in) {
    if (texture_row(t).scale == TexScale::heat_grid) {
        const HeatGrid g = heat_grid(in.window, in.settings.heat_scale);
        return {g.width, g.height};
    }
    return {in.window.width, in.window.height};
}

TexSet PassRow::outputs(const FrameInputs& in) const {
    if (writes_for) return writes_for(in);
    TexSet set;
    for (Tex t : writes) set.add(t);
    return set;
}

const Method& method(scene::GiMethod id) {
    for (const Method& m : methods)
        if (m.id == id) return m;
    LANTERN_VERIFY(false, "gi.method has no method in the pass table");
    return methods[0];
}

const PassRow* find_row(const Method& m, Pass pass) {
    for (const PassRow* row : m.rows)
        if (row->pass == pass) return row;
    return nullptr;
}

const char* pass_name(Pass p) {
    for (const Method& m : methods)
        if (const PassRow* row = find_row(m, p)) return row->name.data();
    return "?";
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
            plan.reason[int(row->pass)].clear();
        }
        if (row->pass == through) requested = false;
    }
    return plan;
}

TexSet textures_written(const FrameInputs& in, const PassPlan& plan) {
    TexSet set;
    for (const PassRow* row : method(in.settings.method).rows)
        if (plan.run.has(row->pass)) set.bits |= row->outputs(in).bits;
    return set;
}

InputKeys input_keys_of(const FrameInputs& in) {
    InputKeys k;
    k.window = hash_window(in.window);
    Hasher walls;
    walls.add(in.walls.width).add(in.walls.height).add(in.walls.origin.x).add(in.walls.origin.y)
        .add(in.walls.phase.x).add(in.walls.phase.y);
    walls.add_bytes(in.walls.cells, std::size_t(in.walls.width) * std::size_t(in.walls.height));
    k.walls = walls.value();
    k.lights = Hasher().add_span(std::span(in.point_lights)).add_span(std::span(in.emissive_lights)).value();
    k.proxies = Hasher().add_span(std::span(in.proxies)).value();
    k.suns = Hasher().add_span(std::span(in.directional_lights)).value();
    return k;
}

std::array<std::uint64_t, pass_count> derive_keys(const FrameInputs& in, const PassPlan& plan, const InputKeys& inputs) {
    return derive_keys(method(in.settings.method), in, plan, inputs);
}

std::array<std::uint64_t, pass_count> derive_keys(const Method& m, const FrameInputs& in, const PassPlan& plan,
                                                  const InputKeys& inputs) {
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
        Hasher h(own[int(row.pass)]);
        for (Tex t : row.reads) h.add(producer[int(t)]);
        const TexSet out = outputs[int(row.pass)];
        // Later rows that overwrite an output in place change what this row leaves behind.
        for (std::size_t j = i + 1; j < rows.size(); ++j) {
            const Pass later = rows[j]->pass;
            if (plan.run.has(later) && (outputs[int(later)].bits & out.bits)) h.add(own[int(later)]);
        }
        keys[int(row.pass)] = h.value();
        for (int t = 0; t < tex_count; ++t)
            if (out.has(Tex(t))) producer[std::size_t(t)] = keys[int(row.pass)];
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
    }
    return s;
}

void execute_reference(const FrameInputs& in, const PassPlan& plan, PassSet subset, const RefOptions& options,
                       ReferenceStore& store, PassTimer timed, void* user) {
    ReferenceContext context{in, plan, options, store};
    for (const PassRow* row : method(in.settings.method).rows) {
        if (!plan.run.has(row->pass) || !subset.has(row->pass)) continue;
        const std::int64_t start = now_ns();
        row->reference(context);
        if (timed) timed(user, row->pass, start, now_ns());
    }
}

void release_unwritten(const FrameInputs& in, const PassPlan& plan, ReferenceStore& store) {
    const TexSet written = textures_written(in, plan);
    for (int t = 0; t < tex_count; ++t)
        if (!written.has(Tex(t))) store.textures[std::size_t(t)].reset();
    if (!written.has(Tex::lit)) store.lit.reset();
}

} // namespace lantern::gi
