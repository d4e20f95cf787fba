// The game's per-texel lit models: their boxes, pixel-art textures, and the passes per frame.
#include "app/texel_world.hpp"

#include "lantern/core/hash.hpp"
#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/device.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <mutex>

namespace lantern::game {
namespace {

constexpr std::array<glm::vec3, std::size_t(TexelModel::count)> halves = {{
    {0.26f, 0.42f, 0.2f},  // player body
    {0.22f, 0.2f, 0.22f},  // player head
    {0.14f, 0.18f, 0.14f}, // backpack
    {0.1f, 0.45f, 0.1f},   // tree trunk
    {0.42f, 0.38f, 0.42f}, // tree crown
    {0.06f, 0.7f, 0.06f},  // lamp post
    {0.04f, 0.25f, 0.04f}, // torch stick
    {0.12f, 0.28f, 0.12f}, // crystal
    {0.07f, 0.14f, 0.07f}, // crystal shard
    {0.2f, 0.2f, 0.2f},    // item: a block of rock
    {0.05f, 0.17f, 0.05f}, // item: a torch
    {0.09f, 0.17f, 0.09f}, // item: a crystal
    {0.07f, 0.2f, 0.07f},  // item: a lamp post's head
    {0.1f, 0.18f, 0.1f},   // item: a sapling
}};

float noise(int model, int face, int i, int j) {
    std::uint32_t h = std::uint32_t(i) * 73856093u ^ std::uint32_t(j) * 19349663u ^ std::uint32_t(face) * 83492791u ^
                      std::uint32_t(model + 1) * 2654435761u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return float(h & 0xffffu) / 65535.0f;
}

// Face f's texel (i, j) of a w x h face (j = 0 the top row; faces +x, -x, +z, -z, top): its
// linear albedo and its normal-map value (rgb in [0, 1], as a normal-map texture holds it).
struct Texel {
    glm::vec3 albedo;
    glm::vec3 normal{0.5f, 0.5f, 1.0f};
};

Texel paint(TexelModel model, int f, int i, int j, int w, int h) {
    const float n = noise(int(model), f, i, j);
    const float vary = 0.94f + 0.12f * n;
    const bool side = f < 4, top = f == 4;
    switch (model) {
    case TexelModel::player_body: {
        if (side && j == (h * 11) / 20) { // the belt, a buckle on the front (+z, the camera's side)
            const bool buckle = f == 2 && std::abs(2 * i - (w - 1)) <= 1;
            return {buckle ? glm::vec3(0.8f, 0.68f, 0.3f) : glm::vec3(0.18f, 0.11f, 0.06f) * vary};
        }
        if (top || j == 0) return {glm::vec3(0.3f, 0.45f, 0.85f) * vary}; // collar and shoulders
        return {glm::vec3(0.22f, 0.36f, 0.72f) * vary};
    }
    case TexelModel::player_head: {
        const glm::vec3 hair = glm::vec3(0.28f, 0.16f, 0.08f) * vary;
        if (top || j < std::max(1, h / 4) || (f == 3 && j < h / 2)) return {hair};
        if (f == 2 && j == h / 2 && (i == w / 4 || i == w - 1 - w / 4)) return {glm::vec3(0.06f, 0.05f, 0.08f)}; // eyes
        return {glm::vec3(0.9f, 0.72f, 0.56f) * vary};
    }
    case TexelModel::backpack: {
        if (top || j < 2) return {glm::vec3(0.36f, 0.23f, 0.11f) * vary}; // the flap
        if (side && (i == 0 || i == w - 1)) return {glm::vec3(0.3f, 0.19f, 0.09f)}; // straps
        return {glm::vec3(0.45f, 0.3f, 0.15f) * vary};
    }
    case TexelModel::tree_trunk: {
        // Bark: grooves every other column, their sides tilted towards them in the normal map.
        const bool groove = side && (i & 1) == 1;
        const glm::vec3 normal = side ? glm::vec3(groove ? 0.35f : 0.65f, 0.5f, 0.9f) : glm::vec3(0.5f, 0.5f, 1.0f);
        return {glm::vec3(0.36f, 0.23f, 0.12f) * (groove ? 0.72f : 1.0f) * vary, normal};
    }
    case TexelModel::tree_crown: {
        // Leaves: light and dark clumps, each leaf tilted its own way.
        glm::vec3 c(0.2f, 0.42f, 0.16f);
        if (n > 0.8f) c = glm::vec3(0.3f, 0.55f, 0.2f);
        else if (n < 0.18f) c = glm::vec3(0.12f, 0.28f, 0.1f);
        if (side && j >= h - 1) c *= 0.75f; // the underside's shade at the bottom edge
        const float a = noise(int(model), f + 7, i, j), b = noise(int(model), f + 13, i, j);
        return {c, glm::vec3(0.3f + 0.4f * a, 0.3f + 0.4f * b, 0.85f)};
    }
    case TexelModel::lamp_post:
        return {side && j % 6 == 0 ? glm::vec3(0.35f, 0.35f, 0.4f) : glm::vec3(0.2f, 0.2f, 0.23f) * vary};
    case TexelModel::crystal:
    case TexelModel::crystal_shard: {
        // Facets: bands running up the shard at a slant, each tilted its own way in the
        // normal map and a little brighter or darker; a pale core line; the top brightest.
        // Near white: the part's tint (the crystal's light colour) gives the hue.
        if (top) return {glm::vec3(0.95f) * vary, glm::vec3(0.5f, 0.5f, 1.0f)};
        const int band = (i + (h - 1 - j) / 2) / 2;
        const float tilt = (band & 1) ? 0.32f : 0.68f;
        const float shade = (band & 1) ? 0.72f : 0.9f;
        const bool core = i == w / 2 && j > h / 4;
        return {glm::vec3(core ? 1.0f : shade) * vary, glm::vec3(tilt, 0.5f, 0.88f)};
    }
    case TexelModel::item_block: {
        // Rock: grey with dark specks and a crack across the top and down one side.
        const bool crack = (top && i == j) || (f == 2 && i == w / 2 && j > h / 3);
        if (crack) return {glm::vec3(0.16f, 0.15f, 0.14f)};
        const glm::vec3 rock(0.46f, 0.42f, 0.4f);
        return {rock * (n < 0.15f ? 0.7f : vary), glm::vec3(0.4f + 0.2f * n, 0.5f, 0.9f)};
    }
    case TexelModel::item_torch:
        if (j < std::max(1, h / 4) || top) return {glm::vec3(1.0f, 0.62f, 0.25f)}; // its head, unlit
        return {glm::vec3(0.35f, 0.22f, 0.1f) * vary};
    case TexelModel::item_crystal: {
        const int band = (i + (h - 1 - j)) / 2;
        return {glm::vec3((band & 1) ? 0.75f : 0.92f) * vary, glm::vec3((band & 1) ? 0.32f : 0.68f, 0.5f, 0.88f)};
    }
    case TexelModel::item_lamp_post:
        if (top || j < h / 3) return {glm::vec3(1.0f, 0.9f, 0.7f) * vary}; // the lamp
        return {glm::vec3(0.2f, 0.2f, 0.23f) * vary};
    case TexelModel::item_sapling:
        if (top || j < (h * 2) / 3) {
            const glm::vec3 leaf = n > 0.6f ? glm::vec3(0.3f, 0.55f, 0.2f) : glm::vec3(0.2f, 0.42f, 0.16f);
            return {leaf, glm::vec3(0.3f + 0.4f * n, 0.5f, 0.85f)};
        }
        return {glm::vec3(0.36f, 0.23f, 0.12f) * vary};
    case TexelModel::torch_stick:
    case TexelModel::count: break;
    }
    return {glm::vec3(0.35f, 0.22f, 0.1f) * vary};
}

texel::Model make_model(TexelModel model, int lod) {
    const glm::vec3 half = halves[std::size_t(model)];
    texel::Model m = texel::box_model(-half, half, texel_density >> lod);
    const std::size_t texels = std::size_t(m.size) * std::size_t(m.size);
    m.albedo.assign(texels, glm::vec4(0.0f));
    m.normal_map.assign(texels, glm::vec4(0.5f, 0.5f, 1.0f, 0.0f));
    for (int f = 0; f < int(m.faces.size()); ++f) {
        const glm::ivec4 r = m.faces[std::size_t(f)];
        for (int j = 0; j < r.w; ++j)
            for (int i = 0; i < r.z; ++i) {
                const Texel t = paint(model, f, i, j, r.z, r.w);
                const std::size_t at = std::size_t(r.y + j) * std::size_t(m.size) + std::size_t(r.x + i);
                m.albedo[at] = glm::vec4(t.albedo, 1.0f);
                m.normal_map[at] = glm::vec4(t.normal, 0.0f);
            }
    }
    return m;
}

} // namespace

glm::vec3 texel_model_half(TexelModel model) { return halves[std::size_t(model)]; }

TexelModel item_model(Item item) {
    switch (item) {
    case Item::wall: return TexelModel::item_block;
    case Item::torch: return TexelModel::item_torch;
    case Item::crystal: return TexelModel::item_crystal;
    case Item::lamp_post: return TexelModel::item_lamp_post;
    case Item::tree: return TexelModel::item_sapling;
    }
    return TexelModel::item_block;
}

int texel_lod_for(glm::vec3 center, glm::vec2 view_target) {
    return glm::distance(glm::vec2(center.x, center.z), view_target) > texel_lod_distance ? 1 : 0;
}

const texel::Model& texel_model(TexelModel model, int lod) {
    static std::once_flag once;
    static std::array<std::array<texel::Model, std::size_t(TexelModel::count)>, texel_lod_count> models;
    std::call_once(once, [] {
        for (int l = 0; l < texel_lod_count; ++l)
            for (int k = 0; k < int(TexelModel::count); ++k) models[std::size_t(l)][std::size_t(k)] = make_model(TexelModel(k), l);
    });
    return models[std::size_t(std::clamp(lod, 0, texel_lod_count - 1))][std::size_t(model)];
}

Result<std::unique_ptr<TexelWorld>> TexelWorld::create(gpu::Device& device) {
    // Room for a crowded view from the start (about 40 trees with the player and torches:
    // 64k texels, 7 MB), so walking allocates no device memory: the buffers only grow past it.
    texel::vk::TexelPasses::Capacity reserve;
    reserve.texels = 1u << 16;
    reserve.placements = 256;
    reserve.triangles = 256 * 10;
    reserve.lights = 64;
    reserve.wall_cells = 128 * 128;
    auto passes = texel::vk::TexelPasses::create(device, reserve);
    if (!passes) return passes.error();
    return std::unique_ptr<TexelWorld>(new TexelWorld(std::move(*passes)));
}

void TexelWorld::record(gpu::CommandList& cmd, std::span<const TexelPart> parts, std::span<const texel::TexelLight> lights,
                        const gi::WallView& walls, float wall_height, texel::vk::TexelRowTimer* timer) {
    // The atlas holds the still parts first, then the moving ones (the player, swaying tree
    // crowns, dropped items): what moves each frame is one run of texels, carried into the
    // world again by one UV-to-world dispatch, and the light pass's workgroups do not mix the
    // two kinds. order_[j] is the part placed j-th.
    order_.clear();
    for (int pass = 0; pass < 2; ++pass)
        for (std::size_t k = 0; k < parts.size(); ++k)
            if (parts[k].moves == (pass == 1)) order_.push_back(std::uint32_t(k));
    std::vector<texel::Placement> placements;
    placements.reserve(parts.size());
    // The layout's key: the parts' models and levels of detail (which art, so which normal
    // maps and albedo), cheaper than hashing the atlas's normal maps each frame.
    Hasher models;
    for (const std::uint32_t k : order_) {
        const TexelPart& p = parts[k];
        const int model = std::clamp(p.model, 0, int(TexelModel::count) - 1);
        const texel::Model& art = texel_model(TexelModel(model), p.lod);
        placements.push_back({&art, glm::translate(glm::mat4(1.0f), p.center), p.moves});
        models.add(model).add(art.size);
    }
    // Walls are copied as far as the longest light (or the sun's shadow search) reaches.
    float reach = 1.0f;
    for (const texel::TexelLight& l : lights) reach = std::max(reach, l.position_range.w);
    texel::TexelScene scene = texel::build_scene(placements, walls, wall_height, reach);

    // The texel pass table plans the frame (docs/texel.md, "The pass table"): UV to world for
    // a new layout or the placements that moved (the walking player); seed 001's static lights
    // (the baked-mode lights, texel::as_baked) baked once for the still parts, again only when
    // the layout, the walls, those lights or a still part change; the realtime pass when
    // anything it reads changed.
    const texel::TexelFrame frame{scene, lights, models.value() | 1u}; // never 0 (0: hash the maps)
    const texel::TexelPlan plan = texel::plan_texel_frame(frame, history_);
    // The albedo (the raster's; the passes do not read it) follows the layout.
    if (plan.upload_layout) {
        albedo_.assign(scene.texel_count, glm::vec4(0.0f));
        for (std::size_t k = 0; k < placements.size(); ++k) {
            const texel::Model& m = *placements[k].model;
            std::copy(m.albedo.begin(), m.albedo.end(), albedo_.begin() + scene.placements[k].ranges.z);
        }
    }
    passes_->record_plan(cmd, frame, plan, timer);
    if (plan.upload_layout) passes_->upload_albedo(cmd, albedo_);
    if (plan.runs(texel::TexelPass::bake)) ++bakes_;
    last_plan_ = plan;

    records_.resize(parts.size());
    for (std::size_t j = 0; j < order_.size(); ++j) {
        const std::uint32_t k = order_[j];
        const texel::Model& m = *placements[j].model;
        TexelRecord& r = records_[k];
        r.texture = glm::vec4(float(scene.placements[j].ranges.z), float(m.size), float(parts[k].probe + 1), parts[k].glow);
        for (std::size_t f = 0; f < 5; ++f) r.faces[f] = glm::vec4(m.faces[f]);
    }
}

} // namespace lantern::game
