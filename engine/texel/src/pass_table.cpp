// The texel passes as rows, their sequencer and the reference backend (pass_table.hpp).
#include "lantern/texel/pass_table.hpp"

#include "lantern/core/hash.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/geometric.hpp>

// The GPU structs are vec4s only (their sizes are asserted in texel.hpp): no padding.
template <>
inline constexpr bool lantern::hash_as_bytes<lantern::texel::GpuTriangle> = true; // vec4s only (static_assert in texel.hpp)
template <>
inline constexpr bool lantern::hash_as_bytes<lantern::texel::GpuPlacement> = true;
template <>
inline constexpr bool lantern::hash_as_bytes<lantern::texel::TexelLight> = true;

namespace lantern::texel {
namespace {

using enum TexelData;

const char* no_texels(const TexelFrame& frame) {
    return frame.scene.texel_count == 0 ? "no texels" : nullptr;
}

constexpr TexelData uv_reads[] = {scene};
constexpr TexelData uv_writes[] = {surfaces};
constexpr TexelData bake_reads[] = {scene, lights, surfaces};
constexpr TexelData bake_writes[] = {baked};
constexpr TexelData light_reads[] = {scene, lights, surfaces, baked};
constexpr TexelData light_writes[] = {lit};

// UV to world depends on the layout and on where every placement stands. The bake depends on
// where the still ones stand only: it reads still placements' surfaces (moving ones receive
// nothing and cast nothing in it), so it lists its inputs instead of uv_to_world's key.
const std::array<TexelRow, texel_pass_count> rows = {{
    {TexelPass::uv_to_world, "texel uv to world", uv_reads, uv_writes,
     texel_input_layout | texel_input_still_places | texel_input_moving_places, no_texels},
    {TexelPass::bake, "texel bake", bake_reads, bake_writes,
     texel_input_layout | texel_input_still_places | texel_input_walls | texel_input_static_lights, no_texels},
    {TexelPass::light, "texel light", light_reads, light_writes,
     texel_input_layout | texel_input_still_places | texel_input_moving_places | texel_input_walls |
         texel_input_lights,
     no_texels},
}};

// Which rows' keys a row's key includes (the rows that wrote what it reads), beside its inputs.
constexpr std::array<std::uint32_t, texel_pass_count> upstream = {
    0u,                                                                 // uv_to_world
    0u,                                                                 // bake: its inputs cover its surfaces
    (1u << int(TexelPass::uv_to_world)) | (1u << int(TexelPass::bake)), // light
};

std::uint64_t placement_hash(const TexelScene& scene, const GpuPlacement& p) {
    Hasher h;
    h.add_span(std::span<const GpuTriangle>(scene.triangles).subspan(p.ranges.x, p.ranges.y));
    return h.value();
}

std::vector<TexelLight> static_lights_of(std::span<const TexelLight> lights) {
    std::vector<TexelLight> out;
    for (const TexelLight& l : lights)
        if (is_baked(l)) out.push_back(l);
    return out;
}

} // namespace

std::span<const TexelRow> texel_rows() { return rows; }
const TexelRow& texel_row(TexelPass pass) { return rows.at(std::size_t(pass)); }

namespace {

// The inputs' keys, and (with `places`) each placement's triangles' hash, hashed once.
TexelKeys input_keys(const TexelFrame& frame, std::vector<std::uint64_t>* places) {
    const TexelScene& s = frame.scene;
    if (places) places->clear();
    TexelKeys keys{};
    Hasher layout;
    layout.add(s.texel_count).add(s.normal_maps.size()).add(frame.layout_key);
    if (frame.layout_key == 0) // floats only
        layout.add_bytes(s.normal_maps.data(), s.normal_maps.size() * sizeof(glm::vec4));
    Hasher still, moving;
    for (const GpuPlacement& p : s.placements) {
        // The layout: each placement's triangle and texel ranges and whether it moves (not
        // where it stands: its bounds are its triangles').
        const bool moves = placement_moves(s, p);
        layout.add(p.ranges.x).add(p.ranges.y).add(p.ranges.z).add(p.ranges.w).add(moves);
        const std::uint64_t where = placement_hash(s, p);
        (moves ? moving : still).add_u64(where);
        if (places) places->push_back(where);
    }
    Hasher walls;
    walls.add(s.walls.origin.x).add(s.walls.origin.y).add(s.walls.width).add(s.walls.height).add(s.wall_height);
    walls.add_span(std::span<const std::uint32_t>(s.walls.words));
    Hasher fixed, all;
    for (const TexelLight& l : frame.lights) {
        all.add(l);
        if (is_baked(l)) fixed.add(l);
    }
    keys[std::countr_zero(std::uint32_t(texel_input_layout))] = layout.value();
    keys[std::countr_zero(std::uint32_t(texel_input_still_places))] = still.value();
    keys[std::countr_zero(std::uint32_t(texel_input_moving_places))] = moving.value();
    keys[std::countr_zero(std::uint32_t(texel_input_walls))] = walls.value();
    keys[std::countr_zero(std::uint32_t(texel_input_static_lights))] = fixed.value();
    keys[std::countr_zero(std::uint32_t(texel_input_lights))] = all.value();
    return keys;
}

} // namespace

TexelKeys texel_input_keys(const TexelFrame& frame) { return input_keys(frame, nullptr); }

TexelPlan plan_texel_frame(const TexelFrame& frame, TexelHistory& history) {
    TexelPlan plan;
    std::vector<std::uint64_t> places;
    const TexelKeys inputs = input_keys(frame, &places);
    const auto input_changed = [&](std::uint32_t bit) {
        const int i = std::countr_zero(bit);
        return inputs[std::size_t(i)] != history.inputs[std::size_t(i)];
    };
    for (const TexelRow& row : rows) {
        const std::size_t r = std::size_t(row.pass);
        Hasher key(0x74657865'6c726f77ull + r); // "texelrow"
        for (int i = 0; i < texel_input_count; ++i)
            if (row.inputs & (1u << i)) key.add_u64(inputs[std::size_t(i)]);
        for (int u = 0; u < texel_pass_count; ++u)
            if (upstream[r] & (1u << u)) key.add_u64(plan.keys[std::size_t(u)]);
        plan.keys[r] = key.value();
        if (const char* why = row.not_needed ? row.not_needed(frame) : nullptr) {
            plan.why_not[r] = why;
            plan.keys[r] = 0; // nothing held: it runs once it is needed
            continue;
        }
        plan.run[r] = plan.keys[r] != history.keys[r];
        if (!plan.run[r]) plan.why_not[r] = "unchanged";
    }
    // The scene's uploads, and which placements UV to world redoes.
    const std::size_t count = places.size();
    const bool layout = input_changed(texel_input_layout) || history.placements.size() != count;
    plan.upload_layout = layout;
    plan.upload_walls = !layout && input_changed(texel_input_walls);
    if (!layout && plan.runs(TexelPass::uv_to_world)) {
        for (std::size_t k = 0; k < count; ++k)
            if (places[k] != history.placements[k]) plan.moved.push_back(std::uint32_t(k));
        plan.upload_triangles = !plan.moved.empty();
        // Nothing moved, yet the row's key changed (history lost its keys): all of it.
        if (plan.moved.empty()) plan.upload_layout = true;
    }
    history.inputs = inputs;
    history.placements = std::move(places);
    for (int r = 0; r < texel_pass_count; ++r)
        if (plan.run[std::size_t(r)] || plan.keys[std::size_t(r)] == 0) history.keys[std::size_t(r)] = plan.keys[std::size_t(r)];
    return plan;
}

void execute_reference(const TexelFrame& frame, const TexelPlan& plan, TexelReferenceStore& store) {
    const TexelScene& scene = frame.scene;
    const std::size_t texels = scene.texel_count;
    if (store.surfaces.size() != texels) { // a new atlas: nothing baked yet
        store.surfaces.assign(texels, TexelSurface{});
        store.baked.assign(texels, glm::vec4(0.0f));
        store.lit.assign(texels, glm::vec4(0.0f));
    }
    if (plan.runs(TexelPass::uv_to_world)) {
        if (plan.moved.empty()) store.surfaces = uv_to_world(scene);
        for (const std::uint32_t k : plan.moved) uv_to_world_placement(scene, k, store.surfaces);
    }
    if (plan.runs(TexelPass::bake)) store.baked = reference_light(scene, store.surfaces, static_lights_of(frame.lights));
    if (plan.runs(TexelPass::light)) store.lit = reference_light(scene, store.surfaces, frame.lights, store.baked);
}

std::vector<std::uint32_t> light_lists(const TexelScene& scene, std::span<const TexelLight> lights, LightPass pass) {
    std::vector<std::uint8_t> moves;
    for (const GpuPlacement& p : scene.placements) moves.push_back(placement_moves(scene, p) ? 1 : 0);
    return light_lists(scene.placements, moves, lights, pass);
}

std::vector<std::uint32_t> light_lists(std::span<const GpuPlacement> placements, std::span<const std::uint8_t> moving,
                                       std::span<const TexelLight> lights, LightPass pass) {
    const std::size_t count = placements.size();
    std::vector<std::uint32_t> out(2 * count, 0u);
    for (std::size_t k = 0; k < count; ++k) {
        const GpuPlacement& p = placements[k];
        const bool moves = k < moving.size() && moving[k] != 0;
        out[2 * k] = std::uint32_t(out.size() - 2 * count);
        if (pass == LightPass::bake && moves) continue; // all of its light is realtime
        const glm::vec3 centre(p.bounds);
        // Texels lie on the placement's triangles, inside its sphere: a light farther than its
        // range from every point of the sphere (with a margin for rounding) reaches none of them.
        const float margin = 1e-3f * (1.0f + p.bounds.w + glm::length(centre));
        for (std::size_t l = 0; l < lights.size(); ++l) {
            const TexelLight& light = lights[l];
            if (pass == LightPass::realtime && !moves && is_baked(light)) continue; // in baked()
            if (!is_directional(light)) {
                const float d = glm::distance(glm::vec3(light.position_range), centre);
                if (d > light.position_range.w + p.bounds.w + margin) continue; // NaN stays: conservative
            }
            out.push_back(std::uint32_t(l));
        }
        out[2 * k + 1] = std::uint32_t(out.size() - 2 * count) - out[2 * k];
    }
    return out;
}

} // namespace lantern::texel
