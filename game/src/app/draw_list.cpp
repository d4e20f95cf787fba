#include "app/draw_list.hpp"

#include "app/texel_world.hpp"

#include "lantern/gi/window.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::game {
namespace {

BoxInstance box(glm::vec3 center, glm::vec3 half, glm::vec3 color, Material m, float emissive = 0.0f,
                float mask = float(face_all)) {
    return BoxInstance{center, float(int(m)), half, mask, color, emissive};
}

constexpr glm::vec3 player_xray_colour(0.55f, 0.8f, 1.0f);
// A texel-lit crystal's glow: below the plain glowing box's 1.6, since its own light (and
// the others') lights its facets on top.
constexpr float crystal_glow = 1.1f;
// A dropped item's hop out of the ground (seconds), and its colour without texel lighting.
constexpr float item_hop_time = 0.3f;
constexpr glm::vec3 item_colours[item_count] = {
    {0.46f, 0.42f, 0.4f}, {0.8f, 0.5f, 0.2f}, {0.5f, 0.75f, 1.0f}, {0.6f, 0.58f, 0.5f}, {0.25f, 0.48f, 0.18f}};

} // namespace

glm::vec2 crown_sway(double time, glm::vec2 at) {
    // Two slow sines across the wind and one along it, each tree in its own phase; the time
    // wrapped so floats keep their precision in long games.
    const float t = float(std::fmod(time, 3600.0));
    const float phase = at.x * 0.71f + at.y * 1.37f;
    return crown_sway_tiles * glm::vec2(0.7f * std::sin(1.3f * t + phase) + 0.3f * std::sin(2.9f * t + 2.1f * phase),
                                        std::sin(0.9f * t + 1.7f * phase));
}

namespace {

bool in_rect(glm::vec2 p, glm::vec2 lo, glm::vec2 hi) { return p.x >= lo.x && p.y >= lo.y && p.x <= hi.x && p.y <= hi.y; }

} // namespace

std::optional<std::pair<glm::ivec2, bool>> cursor_target(const Controls& c, const scene::PerspectiveCamera& camera,
                                                         glm::vec2 player, float wall_height, const IsWall& is_wall) {
    if (!c.has_cursor) return std::nullopt;
    const Ray ray = camera_ray(camera, c.cursor_ndc);
    auto reach = [&](glm::ivec2 t) { return glm::distance(glm::vec2(t) + 0.5f, player) <= interaction_range; };
    if (auto w = pick_wall(ray, wall_height, is_wall)) {
        if (reach(*w)) return std::pair{*w, true};
        return std::nullopt;
    }
    if (auto g = pick_ground(ray); g && reach(*g)) return std::pair{*g, false};
    return std::nullopt;
}

void build_draw_list(ecs::World& world, const systems::Streaming& streaming, const DrawContext& ctx, DrawList& out) {
    // Every list starts empty (the frame's resource is reused: a list left to grow drew the
    // player's silhouette at every place it had been).
    out.boxes.clear();
    out.probes.clear();
    out.xray.clear();
    out.late.clear();
    out.texel_parts.clear();
    // The tiles in view: the camera's ground footprint, widened by the walls' height (a
    // wall top is seen nearer the camera than its foot).
    const auto area = gi::visible_area(scene::ViewSpec{ctx.camera});
    if (!area) return;
    const glm::vec2 lo = glm::floor(area->min) - 2.0f;
    const glm::vec2 hi = glm::ceil(area->min + area->size) + glm::vec2(2.0f, 2.0f + ctx.wall_height * 2.0f);
    const float h = ctx.wall_height;
    const glm::vec2 view_target(ctx.camera.target.x, ctx.camera.target.z); // the texel models' LOD is by distance to it

    // The ground: one flat box with only its top face.
    const glm::vec2 mid = (lo + hi) * 0.5f, half = (hi - lo) * 0.5f;
    out.boxes.push_back(box({mid.x, 0.0f, mid.y}, {half.x, 0.0f, half.y}, {0.38f, 0.33f, 0.28f}, Material::ground, 0.0f,
                            float(face_top)));

    // Walls: one box per wall tile, with only the faces that border air.
    auto wall = [&](int x, int z) { return streaming.is_wall({x, z}); };
    for (int z = int(lo.y); z < int(hi.y); ++z)
        for (int x = int(lo.x); x < int(hi.x); ++x) {
            if (!wall(x, z)) continue;
            int mask = face_top;
            if (!wall(x + 1, z)) mask |= face_pos_x;
            if (!wall(x - 1, z)) mask |= face_neg_x;
            if (!wall(x, z + 1)) mask |= face_pos_z;
            if (!wall(x, z - 1)) mask |= face_neg_z;
            glm::vec3 color(0.46f, 0.42f, 0.4f);
            float emissive = 0.0f;
            const int cell = streaming.cell({x, z});
            if (ctx.materials && cell >= scene::first_material_cell &&
                std::size_t(cell - scene::first_material_cell) < ctx.materials->size()) {
                // A mineral: its albedo, and where it glows the glow's colour, shining.
                const scene::Material& m = (*ctx.materials)[std::size_t(cell - scene::first_material_cell)];
                const float e = std::max({m.emission.r, m.emission.g, m.emission.b});
                color = e > 0.0f ? m.emission / e : m.albedo;
                emissive = e > 0.0f ? std::clamp(3.0f * e, 0.6f, 1.5f) : 0.0f;
                emissive *= scene::pulse_factor(m.pulse, ctx.time); // seed 004's pulsing emission (1 when steady)
            }
            out.boxes.push_back(box({float(x) + 0.5f, h * 0.5f, float(z) + 0.5f}, {0.5f, h * 0.5f, 0.5f}, color,
                                    Material::wall, emissive, float(mask)));
        }

    // Things that move or stand in the open are lit by the light probes too (the baked light's,
    // with baked light in use, and the GI's live ones): one record per object, a lit_probes box
    // per part. The record's index, or -1 without either.
    auto probe_record = [&](glm::vec2 at) -> int {
        if (!ctx.probes && !ctx.live_probes) return -1;
        ProbeRecord r;
        if (ctx.probes) {
            const bake::CircularHarmonics probes = ctx.probes->probes_at(at);
            for (int k = 0; k < 5; ++k) r.c[k] = glm::vec4(probes.c[std::size_t(k)], 0.0f);
        }
        if (ctx.live_probes) r.live = glm::vec4(at, 1.0f, 0.0f);
        out.probes.push_back(r);
        return int(out.probes.size() - 1);
    };
    // Seed 004's anchor override: an object with a ProbeAnchor samples the probes there.
    auto anchored = [&](ecs::Entity e, glm::vec2 at) {
        const ProbeAnchor* a = world.try_get<ProbeAnchor>(e);
        return a ? a->position : at;
    };
    auto probe_lit = [&](ecs::Entity e, glm::vec2 at) -> std::pair<Material, float> {
        if ((!ctx.probes && !ctx.live_probes) || ctx.texel_lighting) return {Material::prop, 0.0f}; // texel lit: a record per part, below
        return {Material::lit_probes, float(probe_record(anchored(e, at)))};
    };

    bool moving_parts = false; // the player's parts (TexelPart::moves)
    // A part of a model that is lit per texel with texel lighting on (its model's box, white:
    // the texture has the colours), else the box it always was.
    // `tint` and `glow`: a glowing part's colour and strength (a crystal), lit per texel too.
    auto part = [&](ecs::Entity e, int index, TexelModel model, glm::vec3 center, glm::vec3 color,
                    std::pair<Material, float> lit, std::vector<BoxInstance>& into, glm::vec3 tint = glm::vec3(1.0f),
                    float glow = 0.0f) {
        const glm::vec3 extent = texel_model_half(model);
        if (!ctx.texel_lighting) {
            into.push_back(box(center, extent, color, lit.first, lit.second));
            return;
        }
        // The baked light's probes at the part, for its side faces (the texel pass has the
        // direct light, the GI textures the baked light's ground part).
        TexelPart p{e.bits() * 8u + std::uint64_t(index), int(model), center, texel_lod_for(center, view_target),
                    probe_record(anchored(e, {center.x, center.z}))};
        p.glow = glow;
        p.moves = moving_parts;
        out.texel_parts.push_back(p);
        into.push_back(box(center, extent, tint, Material::texel_lit, float(out.texel_parts.size() - 1)));
    };

    // Props.
    world.view<Prop>().each([&](ecs::Entity e, const Prop& p) {
        if (!in_rect(p.position, lo, hi)) return;
        const glm::vec3 at(p.position.x, 0.0f, p.position.y);
        switch (p.kind) {
        case PropKind::crystal: {
            glm::vec3 color(0.4f, 0.7f, 1.0f);
            if (const EmissiveLight* l = world.try_get<EmissiveLight>(e)) color = l->color;
            // Glowing shards; with texel lighting their facets are lit per texel on top.
            part(e, 0, TexelModel::crystal, at + glm::vec3(0, 0.28f, 0), color, {Material::glow, 1.6f}, out.boxes, color,
                 crystal_glow);
            part(e, 1, TexelModel::crystal_shard, at + glm::vec3(0.14f, 0.14f, 0.05f), color, {Material::glow, 1.2f},
                 out.boxes, color, 0.75f * crystal_glow);
            break;
        }
        case PropKind::tree: {
            const auto lit = probe_lit(e, p.position);
            part(e, 0, TexelModel::tree_trunk, at + glm::vec3(0, 0.45f, 0), {0.36f, 0.23f, 0.12f}, lit, out.boxes);
            // The crown sways in the wind (seed 001's improvement 2): a moving part, carried
            // into the world again each frame and lit live.
            const glm::vec2 sway = crown_sway(ctx.time, p.position);
            moving_parts = true;
            part(e, 1, TexelModel::tree_crown, at + glm::vec3(sway.x, 1.25f, sway.y), {0.2f, 0.42f, 0.16f}, lit, out.boxes);
            moving_parts = false;
            break;
        }
        case PropKind::lamp_post: {
            part(e, 0, TexelModel::lamp_post, at + glm::vec3(0, 0.7f, 0), {0.2f, 0.2f, 0.23f}, probe_lit(e, p.position),
                 out.boxes);
            out.boxes.push_back(box(at + glm::vec3(0, 1.5f, 0), {0.14f, 0.12f, 0.14f}, {1.0f, 0.9f, 0.7f}, Material::glow, 2.0f));
            break;
        }
        }
    });

    // Torches: a stick and a flame that flickers with the light.
    world.view<Torch, PointLight>().each([&](ecs::Entity e, const Torch& t, const PointLight& l) {
        if (!in_rect(l.position, lo, hi)) return;
        const glm::vec3 at(l.position.x, 0.0f, l.position.y);
        const float f = l.intensity / std::max(t.base_intensity, 1e-3f);
        part(e, 0, TexelModel::torch_stick, at + glm::vec3(0, 0.25f, 0), {0.35f, 0.22f, 0.1f}, {Material::prop, 0.0f},
             out.boxes);
        out.boxes.push_back(box(at + glm::vec3(0, 0.58f, 0), glm::vec3(0.08f, 0.1f * f, 0.08f), {1.0f, 0.6f, 0.25f},
                                Material::glow, 2.2f * f));
    });

    // Dropped items: a small model of the item that hops out of the ground where it was
    // mined, then rests there until the player comes near (collect_items glides it over). Lit
    // as a moving thing: every light live on it, the baked light's probes at it.
    world.view<DroppedItem>().each([&](ecs::Entity e, const DroppedItem& d) {
        if (!in_rect(d.position, lo, hi)) return;
        const TexelModel model = item_model(d.item);
        const float hop = d.age < item_hop_time ? 0.45f * std::sin(3.14159265f * d.age / item_hop_time) : 0.0f;
        const glm::vec3 at(d.position.x, texel_model_half(model).y + hop, d.position.y);
        moving_parts = true;
        part(e, 0, model, at, item_colours[std::size_t(d.item)], probe_lit(e, d.position), out.boxes);
        moving_parts = false;
    });

    // A scene file's own lights (no torch, prop or player of the game's carries them) are
    // drawn too, so no light comes from nothing: a point light as a small lamp of its colour
    // at its height (a post below it), an emissive light as a glowing slab on the ground.
    world.view<PointLight>().each([&](ecs::Entity e, const PointLight& l) {
        if (world.try_get<Torch>(e) || world.try_get<Prop>(e) || world.try_get<Player>(e)) return;
        if (!in_rect(l.position, lo, hi) || streaming.is_wall(glm::ivec2(glm::floor(l.position)))) return;
        const glm::vec3 at(l.position.x, 0.0f, l.position.y);
        const float y = std::clamp(l.height, 0.3f, 3.0f);
        const glm::vec3 glow = l.color / std::max({l.color.r, l.color.g, l.color.b, 1e-3f});
        out.boxes.push_back(box(at + glm::vec3(0, (y - 0.1f) * 0.5f, 0), {0.04f, (y - 0.1f) * 0.5f, 0.04f},
                                {0.2f, 0.2f, 0.23f}, Material::prop));
        out.boxes.push_back(box(at + glm::vec3(0, y, 0), glm::vec3(0.1f), glow, Material::glow, 2.0f));
    });
    world.view<EmissiveLight>().each([&](ecs::Entity e, const EmissiveLight& l) {
        if (world.try_get<Prop>(e) || !in_rect(l.position, lo, hi)) return;
        if (streaming.is_wall(glm::ivec2(glm::floor(l.position)))) return;
        const glm::vec3 glow = l.color / std::max({l.color.r, l.color.g, l.color.b, 1e-3f});
        const float r = std::clamp(l.radius * 0.08f, 0.12f, 0.35f);
        out.boxes.push_back(box({l.position.x, 0.03f, l.position.y}, {r, 0.03f, r}, glow, Material::glow, 1.4f));
    });

    // The player.
    world.view<Player, Transform>().each([&](ecs::Entity e, const Player& p, const Transform& t) {
        const glm::vec3 at(t.position.x, 0.0f, t.position.z);
        const auto lit = probe_lit(e, {t.position.x, t.position.z});
        // Its parts are drawn after the x-ray pass (DrawList::late): only the world hides it.
        moving_parts = true;
        part(e, 0, TexelModel::player_body, at + glm::vec3(0, 0.42f, 0), {0.22f, 0.36f, 0.72f}, lit, out.late);
        part(e, 1, TexelModel::player_head, at + glm::vec3(0, 1.04f, 0), {0.9f, 0.72f, 0.56f}, lit, out.late);
        // Its silhouette where walls (or trees) hide it: body and head only (the backpack
        // behind the body would show through it).
        out.xray.push_back(box(at + glm::vec3(0, 0.42f, 0), {0.26f, 0.42f, 0.2f}, player_xray_colour, Material::glow));
        out.xray.push_back(box(at + glm::vec3(0, 1.04f, 0), {0.22f, 0.2f, 0.22f}, player_xray_colour, Material::glow));
        // Which way it faces: a small backpack on the other side.
        const glm::vec2 back = -p.facing * 0.2f;
        part(e, 2, TexelModel::backpack, at + glm::vec3(back.x * 1.3f, 0.55f, back.y * 1.3f), {0.45f, 0.3f, 0.15f}, lit,
             out.late);
        moving_parts = false;
    });

    // The cursor: a thin glowing frame on the tile (on the wall's top for a wall).
    if (ctx.cursor_tile) {
        const glm::vec2 c = glm::vec2(*ctx.cursor_tile) + 0.5f;
        const float y = ctx.cursor_on_wall ? h + 0.01f : 0.01f;
        const glm::vec3 color(1.0f, 0.95f, 0.7f);
        const float w = 0.035f;
        out.boxes.push_back(box({c.x, y, c.y - 0.5f + w}, {0.5f, 0.0f, w}, color, Material::glow, 0.9f, float(face_top)));
        out.boxes.push_back(box({c.x, y, c.y + 0.5f - w}, {0.5f, 0.0f, w}, color, Material::glow, 0.9f, float(face_top)));
        out.boxes.push_back(box({c.x - 0.5f + w, y, c.y}, {w, 0.0f, 0.5f}, color, Material::glow, 0.9f, float(face_top)));
        out.boxes.push_back(box({c.x + 0.5f - w, y, c.y}, {w, 0.0f, 0.5f}, color, Material::glow, 0.9f, float(face_top)));
    }
}

} // namespace lantern::game

namespace lantern::game {

void gather_texel_lights(ecs::World& world, const DrawContext& ctx, std::vector<texel::TexelLight>& out) {
    out.clear();
    if (!ctx.texel_lighting) return;
    const auto area = gi::visible_area(scene::ViewSpec{ctx.camera});
    if (!area) return;
    const glm::vec2 lo = area->min - 2.0f, hi = area->min + area->size + glm::vec2(2.0f, 2.0f + ctx.wall_height * 2.0f);
    const glm::vec2 centre = (lo + hi) * 0.5f;
    const auto reaches_view = [&](glm::vec2 p, float radius) { return glm::distance(p, glm::clamp(p, lo, hi)) <= radius; };
    // Each game light's ambient colour (the tables'), scaled with its intensity against the
    // table's (a torch's flicker); a scene file's own lights have none.
    const GameTables* world_tables = world.try_resource<GameTables>();
    const GameTables& tables = world_tables ? *world_tables : default_tables();
    const auto ambient = [](const ItemLight& item, float intensity) {
        return item.intensity > 0.0f ? item.ambient * (intensity / item.intensity) : item.ambient;
    };
    // Seed 001's static lights: a baked-mode light, while the frame uses a bake (as the GI
    // honours modes), is baked into the models' texels once (TexelWorld).
    const auto baked_mode = [&](scene::LightMode mode) { return ctx.probes && mode == scene::LightMode::baked; };
    std::vector<std::pair<float, texel::TexelLight>> near;
    world.view<PointLight>().each([&](ecs::Entity e, const PointLight& l) {
        if (!reaches_view(l.position, l.radius)) return;
        const Prop* prop = world.try_get<Prop>(e);
        const bool lamp = prop && prop->kind == PropKind::lamp_post;
        glm::vec3 fill(0.0f);
        if (lamp) fill = ambient(tables.lamp_post, l.intensity);
        else if (world.try_get<Torch>(e)) fill = ambient(tables.torch, l.intensity);
        else if (world.try_get<Player>(e)) fill = ambient(tables.player, l.intensity);
        texel::TexelLight light = texel::make_light({l.position.x, l.height, l.position.y}, l.color, l.intensity,
                                                    l.radius, lamp ? texel::ShadowType::blurred : texel::ShadowType::hard,
                                                    1.0f, 1.0f, fill);
        near.emplace_back(glm::distance(l.position, centre), baked_mode(l.mode) ? texel::as_baked(light) : light);
    });
    world.view<EmissiveLight>().each([&](ecs::Entity e, const EmissiveLight& l) {
        if (!reaches_view(l.position, l.radius)) return;
        const Prop* prop = world.try_get<Prop>(e);
        const glm::vec3 fill = prop && prop->kind == PropKind::crystal ? ambient(tables.crystal, l.intensity) : glm::vec3(0.0f);
        const texel::TexelLight light = texel::make_light({l.position.x, 0.3f, l.position.y}, l.color, l.intensity,
                                                          l.radius, texel::ShadowType::none, 1.0f, 1.0f, fill);
        near.emplace_back(glm::distance(l.position, centre), baked_mode(l.mode) ? texel::as_baked(light) : light);
    });
    constexpr std::size_t cap = 32;
    if (near.size() > cap) {
        std::nth_element(near.begin(), near.begin() + cap, near.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        near.resize(cap);
    }
    for (const auto& [d, l] : near) out.push_back(l);
}

} // namespace lantern::game
