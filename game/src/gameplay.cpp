#include "lantern/game/gameplay.hpp"

#include "lantern/scene/day.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::game {
namespace {

// Does a circle at p overlap wall tile (x, z)?
bool overlaps(glm::vec2 p, float r, int x, int z) {
    const glm::vec2 closest(std::clamp(p.x, float(x), float(x) + 1.0f), std::clamp(p.y, float(z), float(z) + 1.0f));
    const glm::vec2 d = p - closest;
    return d.x * d.x + d.y * d.y < r * r;
}

bool blocked(glm::vec2 p, float r, const IsWall& is_wall) {
    for (int z = int(std::floor(p.y - r)); z <= int(std::floor(p.y + r)); ++z)
        for (int x = int(std::floor(p.x - r)); x <= int(std::floor(p.x + r)); ++x)
            if (is_wall(x, z) && overlaps(p, r, x, z)) return true;
    return false;
}

// Moves along one axis in small steps (never tunnels through a one-tile wall).
float slide(glm::vec2& p, glm::vec2 axis, float amount, float r, const IsWall& is_wall) {
    const int steps = std::max(1, int(std::ceil(std::abs(amount) / (r * 0.5f))));
    const float step = amount / float(steps);
    float moved = 0.0f;
    for (int i = 0; i < steps; ++i) {
        const glm::vec2 next = p + axis * step;
        if (blocked(next, r, is_wall)) {
            // Close the remaining gap to the wall by bisection (to 1/256 of a step).
            float lo = 0.0f, hi = 1.0f;
            for (int k = 0; k < 8; ++k) {
                const float mid = 0.5f * (lo + hi);
                (blocked(p + axis * (step * mid), r, is_wall) ? hi : lo) = mid;
            }
            p += axis * (step * lo);
            moved += step * lo;
            break;
        }
        p = next;
        moved += step;
    }
    return moved;
}

float hash01(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7FEB352Du;
    x ^= x >> 15;
    x *= 0x846CA68Bu;
    x ^= x >> 16;
    return float(x & 0xFFFFFF) / float(0xFFFFFF);
}

} // namespace

glm::vec2 move_with_collision(glm::vec2 position, glm::vec2 delta, float radius, const IsWall& is_wall) {
    glm::vec2 p = position;
    slide(p, {1.0f, 0.0f}, delta.x, radius, is_wall);
    slide(p, {0.0f, 1.0f}, delta.y, radius, is_wall);
    return p;
}

scene::PerspectiveCamera follow_camera(glm::vec3 player, const CameraRig& rig) {
    scene::PerspectiveCamera c;
    c.target = glm::vec3(player.x, 0.0f, player.z);
    // Looking towards -z: screen right is +x and screen up is -z, so a map reads as in
    // its file (columns to the right, rows down the screen).
    c.position = glm::vec3(player.x, rig.height, player.z + rig.back);
    c.fov_deg = rig.fov_deg;
    c.aspect = rig.aspect;
    return c;
}

namespace {

struct CameraBasis {
    glm::vec3 forward, right, up;
    float half_w, half_h;
};

CameraBasis basis(const scene::PerspectiveCamera& c) {
    CameraBasis b;
    b.forward = glm::normalize(c.target - c.position);
    const glm::vec3 up_hint = std::abs(b.forward.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    b.right = glm::normalize(glm::cross(b.forward, up_hint));
    b.up = glm::cross(b.right, b.forward);
    b.half_h = std::tan(glm::radians(c.fov_deg) * 0.5f);
    b.half_w = b.half_h * c.aspect;
    return b;
}

} // namespace

Ray camera_ray(const scene::PerspectiveCamera& c, glm::vec2 ndc) {
    const CameraBasis b = basis(c);
    const float sx = ndc.x * 2.0f - 1.0f, sy = 1.0f - ndc.y * 2.0f;
    return Ray{c.position, glm::normalize(b.forward + b.right * (sx * b.half_w) + b.up * (sy * b.half_h))};
}

std::optional<glm::vec2> project_to_ndc(const scene::PerspectiveCamera& c, glm::vec3 point) {
    const CameraBasis b = basis(c);
    const glm::vec3 d = point - c.position;
    const float depth = glm::dot(d, b.forward);
    if (depth <= 1e-4f) return std::nullopt;
    const float sx = glm::dot(d, b.right) / depth / b.half_w, sy = glm::dot(d, b.up) / depth / b.half_h;
    return glm::vec2(sx * 0.5f + 0.5f, 0.5f - sy * 0.5f);
}

std::optional<glm::ivec2> pick_wall(const Ray& ray, float wall_height, const IsWall& is_wall, float max_distance) {
    // March in small steps: the first sample inside a wall box is the wall under the cursor.
    for (float t = 0.0f; t < max_distance; t += 0.02f) {
        const glm::vec3 p = ray.origin + ray.direction * t;
        if (p.y < 0.0f) return std::nullopt;
        if (p.y > wall_height) continue;
        const glm::ivec2 tile(int(std::floor(p.x)), int(std::floor(p.z)));
        if (is_wall(tile.x, tile.y)) return tile;
    }
    return std::nullopt;
}

std::optional<glm::vec2> ground_point(const Ray& ray) {
    if (ray.direction.y >= -1e-4f) return std::nullopt;
    const float t = -ray.origin.y / ray.direction.y;
    const glm::vec3 p = ray.origin + ray.direction * t;
    return glm::vec2(p.x, p.z);
}

std::optional<glm::ivec2> pick_ground(const Ray& ray) {
    const auto p = ground_point(ray);
    if (!p) return std::nullopt;
    return glm::ivec2(int(std::floor(p->x)), int(std::floor(p->y)));
}

float flicker(double time, float phase) {
    // Value noise at 7 Hz plus a slower 1.3 Hz sway, smoothly interpolated.
    auto noise = [&](double t, std::uint32_t salt) {
        const double f = std::floor(t);
        const float a = hash01(std::uint32_t(std::int64_t(f)) * 747796405u + salt);
        const float b = hash01(std::uint32_t(std::int64_t(f) + 1) * 747796405u + salt);
        const float u = float(t - f);
        return a + (b - a) * (u * u * (3.0f - 2.0f * u));
    };
    const std::uint32_t salt = std::uint32_t(phase * 1000.0f);
    return 0.8f + 0.17f * noise(time * 7.0 + phase, salt) + 0.08f * noise(time * 1.3 + phase, salt + 17u);
}

glm::vec3 sun_direction(float time_of_day) { return scene::day_sun_direction(time_of_day); }

glm::vec3 sun_light(float time_of_day) { return scene::day_sun_light(time_of_day); }

float sun_step_time(float time_of_day) {
    const float steps = float(sun_steps_per_day);
    return std::floor(time_of_day * steps) / steps;
}

// A lamp post's light hangs from its arm, a little towards +z of the post.
const glm::vec2 lamp_light_offset{0.0f, 0.4f};

PropParts prop_parts(PropKind kind, glm::vec2 position, const GameTables& tables) {
    PropParts out;
    out.prop = Prop{kind, position};
    scene::ShadowProxy proxy;
    proxy.position = position;
    switch (kind) {
    case PropKind::crystal: {
        // Baked (with baked light in use): a crystal stays put.
        const ItemLight& l = tables.crystal;
        out.emissive = EmissiveLight{position, l.color, l.intensity, l.radius, scene::LightMode::baked};
        break;
    }
    case PropKind::tree:
        proxy.shape = scene::ProxyShape::circle;
        proxy.size = {0.45f, 0.45f};
        proxy.max_length = 3.0f;
        out.proxy = ShadowProxy{proxy};
        // Its parts take the baked light's probes where it stands: the crown sways (so its
        // own centre would drift between probes frame by frame) and overhangs rock or shade.
        out.anchor = ProbeAnchor{position};
        break;
    case PropKind::lamp_post: {
        proxy.shape = scene::ProxyShape::box;
        proxy.size = {0.15f, 0.15f};
        proxy.max_length = 2.0f;
        out.proxy = ShadowProxy{proxy};
        // Mixed: its direct light live, its bounce from the bake (with baked light in use).
        const ItemLight& l = tables.lamp_post;
        out.light = PointLight{position + lamp_light_offset, l.height, l.color, l.intensity, l.radius, scene::LightMode::mixed};
        break;
    }
    }
    return out;
}

TorchParts torch_parts(glm::vec2 position, float phase, const GameTables& tables) {
    const ItemLight& l = tables.torch;
    return {PointLight{position, l.height, l.color, l.intensity, l.radius}, Torch{l.intensity, phase}};
}

ecs::Entity spawn_torch(ecs::World& world, glm::vec2 position, float phase, const GameTables& tables) {
    const TorchParts parts = torch_parts(position, phase, tables);
    ecs::Entity e = world.create();
    world.emplace<PointLight>(e, parts.light);
    world.emplace<Torch>(e, parts.torch);
    return e;
}

ecs::Entity spawn_prop(ecs::World& world, PropKind kind, glm::vec2 position, const GameTables& tables) {
    const PropParts parts = prop_parts(kind, position, tables);
    ecs::Entity e = world.create();
    world.emplace<Prop>(e, parts.prop);
    if (parts.emissive) world.emplace<EmissiveLight>(e, *parts.emissive);
    if (parts.proxy) world.emplace<ShadowProxy>(e, *parts.proxy);
    if (parts.light) world.emplace<PointLight>(e, *parts.light);
    if (parts.anchor) world.emplace<ProbeAnchor>(e, *parts.anchor);
    return e;
}

ecs::Entity spawn_player(ecs::World& world, glm::vec2 position, bool light, const GameTables& tables) {
    ecs::Entity e = world.create();
    world.emplace<Transform>(e, Transform{glm::vec3(position.x, 0.0f, position.y)});
    world.emplace<Player>(e);
    const ItemLight& l = tables.player;
    if (light) world.emplace<PointLight>(e, PointLight{position, l.height, l.color, l.intensity, l.radius});
    return e;
}

void apply_tables(ecs::World& world, const GameTables& tables, bool materials) {
    const GameTables* before = world.try_resource<GameTables>();
    const glm::vec3 old_crystal = before ? before->crystal.color : default_tables().crystal.color;
    if (materials && world.has_resource<systems::GiConfig>()) world.resource<systems::GiConfig>().materials = tables.materials;
    const auto point = [](PointLight& p, const ItemLight& l) {
        p.color = l.color;
        p.intensity = l.intensity;
        p.radius = l.radius;
        p.height = l.height;
    };
    // Written through patch(): the light gathering looks only at what changed.
    std::vector<std::pair<ecs::Entity, const ItemLight*>> points;
    std::vector<ecs::Entity> crystals;
    world.view<Torch, PointLight>().each([&](ecs::Entity e, const Torch&, const PointLight&) { points.push_back({e, &tables.torch}); });
    world.view<Player, PointLight>().each([&](ecs::Entity e, const Player&, const PointLight&) { points.push_back({e, &tables.player}); });
    world.view<Prop>().each([&](ecs::Entity e, const Prop& prop) {
        if (prop.kind == PropKind::crystal && world.try_get<EmissiveLight>(e)) crystals.push_back(e);
        if (prop.kind == PropKind::lamp_post && world.try_get<PointLight>(e)) points.push_back({e, &tables.lamp_post});
    });
    for (const auto& [e, l] : points) {
        point(world.patch<PointLight>(e), *l);
        if (Torch* torch = world.try_get<Torch>(e)) torch->base_intensity = l->intensity; // the flicker scales it
    }
    for (ecs::Entity e : crystals) {
        EmissiveLight& c = world.patch<EmissiveLight>(e);
        if (c.color == old_crystal) c.color = tables.crystal.color; // the caves' own crystals keep their hues
        c.intensity = tables.crystal.intensity;
        c.radius = tables.crystal.radius;
    }
    world.set_resource<GameTables>(tables);
}

namespace {

void move_player(ecs::SystemContext& ctx) {
    const systems::Streaming& streaming = ctx.world.resource<systems::Streaming>();
    ecs::World& w = ctx.world;
    const Controls& controls = w.resource<Controls>();
    const float dt = w.resource<GameClock>().dt;
    const IsWall is_wall = [&](int x, int z) { return streaming.is_wall({x, z}); };
    w.view<Player, Transform>().each([&](ecs::Entity e, Player& player, Transform&) {
        glm::vec2 move = controls.move;
        if (glm::length(move) > 1.0f) move = glm::normalize(move);
        if (move == glm::vec2(0.0f)) return;
        player.facing = glm::normalize(move);
        Transform& t = w.patch<Transform>(e);
        const glm::vec2 p = move_with_collision({t.position.x, t.position.z}, move * player.speed * dt, player.radius, is_wall);
        t.position = glm::vec3(p.x, 0.0f, p.y);
        if (w.try_get<PointLight>(e)) w.patch<PointLight>(e).position = p; // the player's lantern
    });
    // The camera follows the first player.
    const CameraRig& rig = w.resource<CameraRig>();
    w.view<Player, Transform>().each([&](const Player&, const Transform& t) {
        w.view<Camera>().each([&](ecs::Entity cam, Camera& c) {
            const auto follow = follow_camera(t.position, rig);
            auto* current = std::get_if<scene::PerspectiveCamera>(&c.view);
            if (!current || current->position != follow.position || current->target != follow.target ||
                current->aspect != follow.aspect)
                w.patch<Camera>(cam).view = follow;
        });
    });
}

std::optional<glm::vec3> player_position(ecs::World& w) {
    std::optional<glm::vec3> out;
    w.view<Player, Transform>().each([&](const Player&, const Transform& t) {
        if (!out) out = t.position;
    });
    return out;
}

void interact(ecs::SystemContext& ctx) {
    systems::Streaming& streaming = ctx.world.resource<systems::Streaming>();
    ecs::World& w = ctx.world;
    const Controls& c = w.resource<Controls>();
    const bool wants = c.mine || c.place_wall || c.place_torch || c.place_crystal || c.place_tree || c.place_lamp;
    if (!wants || !c.has_cursor || !w.has_resource<Inventory>()) return;
    Inventory& inventory = w.resource<Inventory>();
    const auto player = player_position(w);
    std::optional<scene::PerspectiveCamera> camera;
    w.view<Camera>().each([&](const Camera& cam) {
        if (!camera)
            if (auto* p = std::get_if<scene::PerspectiveCamera>(&cam.view)) camera = *p;
    });
    if (!player || !camera) return;
    const Ray ray = camera_ray(*camera, c.cursor_ndc);
    const IsWall is_wall = [&](int x, int z) { return streaming.is_wall({x, z}); };
    auto in_reach = [&](glm::ivec2 tile) {
        return glm::distance(glm::vec2(tile) + 0.5f, glm::vec2(player->x, player->z)) <= interaction_range;
    };
    // What is mined drops where it was, for the player to collect (collect_items).
    const auto drop = [&](Item item, glm::vec2 at) {
        auto& cb = ctx.commands();
        const ecs::Entity e = cb.create();
        cb.emplace<DroppedItem>(e, DroppedItem{item, 1, at, 0.0f});
    };
    const auto edited = [&](SoundCue cue, glm::ivec2 tile) {
        if (w.has_resource<WorldEdits>()) ++w.resource<WorldEdits>().count;
        if (w.has_resource<SoundCues>()) w.resource<SoundCues>().entries.push_back({cue, glm::vec2(tile) + 0.5f});
    };
    if (c.mine) {
        // The wall under the cursor drops its block; on open ground, a torch or prop placed
        // on that tile drops as an item (the scene's own lights are not the player's).
        if (auto tile = pick_wall(ray, w.resource<systems::GiConfig>().wall_height, is_wall)) {
            if (in_reach(*tile)) {
                streaming.set_wall(w, *tile, false);
                drop(Item::wall, glm::vec2(*tile) + 0.5f);
                edited(SoundCue::dig, *tile);
            }
            return;
        }
        const auto ground = pick_ground(ray);
        if (!ground || !in_reach(*ground)) return;
        const auto on_tile = [&](glm::vec2 p) { return glm::ivec2(glm::floor(p)) == *ground; };
        struct Found {
            ecs::Entity entity;
            Item item;
            glm::vec2 at;
        };
        std::optional<Found> found;
        w.view<Torch, PointLight>().each([&](ecs::Entity e, const Torch&, const PointLight& l) {
            if (!found && on_tile(l.position)) found = Found{e, Item::torch, l.position};
        });
        w.view<Prop>().each([&](ecs::Entity e, const Prop& p) {
            if (found || !on_tile(p.position)) return;
            found = Found{e, p.kind == PropKind::crystal ? Item::crystal : p.kind == PropKind::tree ? Item::tree : Item::lamp_post,
                          p.position};
        });
        if (found) {
            ctx.commands().destroy(found->entity);
            drop(found->item, found->at);
            edited(SoundCue::dig, *ground);
        }
        return;
    }
    const Item item = c.place_wall      ? Item::wall
                      : c.place_torch   ? Item::torch
                      : c.place_crystal ? Item::crystal
                      : c.place_tree    ? Item::tree
                                        : Item::lamp_post;
    if (inventory[item] <= 0) return; // nothing of it left: mine or pick some up
    const auto tile = pick_ground(ray);
    if (!tile || !in_reach(*tile) || streaming.is_wall(*tile)) return;
    const glm::vec2 center = glm::vec2(*tile) + 0.5f;
    const GameTables* world_tables = w.try_resource<GameTables>();
    const GameTables& tables = world_tables ? *world_tables : default_tables();
    if (c.place_wall) {
        // Never wall the player in.
        if (glm::distance(center, glm::vec2(player->x, player->z)) <= 0.9f) return;
        streaming.set_wall(w, *tile, true);
    } else if (c.place_torch) {
        const TorchParts parts = torch_parts(center, float(tile->x * 13 + tile->y * 7) * 0.37f, tables);
        auto& cb = ctx.commands();
        ecs::Entity e = cb.create();
        cb.emplace<PointLight>(e, parts.light);
        cb.emplace<Torch>(e, parts.torch);
    } else {
        const PropKind kind = c.place_crystal ? PropKind::crystal : c.place_tree ? PropKind::tree : PropKind::lamp_post;
        const PropParts parts = prop_parts(kind, center, tables);
        auto& cb = ctx.commands();
        ecs::Entity e = cb.create();
        cb.emplace<Prop>(e, parts.prop);
        if (parts.emissive) cb.emplace<EmissiveLight>(e, *parts.emissive);
        if (parts.proxy) cb.emplace<ShadowProxy>(e, *parts.proxy);
        if (parts.light) cb.emplace<PointLight>(e, *parts.light);
        if (parts.anchor) cb.emplace<ProbeAnchor>(e, *parts.anchor);
    }
    --inventory[item];
    edited(SoundCue::place, *tile);
}

// Dropped items age; near the player they glide to it and go into the inventory.
void collect_items(ecs::SystemContext& ctx) {
    ecs::World& w = ctx.world;
    const float dt = w.resource<GameClock>().dt;
    const auto player = player_position(w);
    Inventory* inventory = w.try_resource<Inventory>();
    w.view<DroppedItem>().each([&](ecs::Entity e, const DroppedItem&) {
        DroppedItem& d = w.patch<DroppedItem>(e);
        d.age = std::min(d.age + dt, 60.0f); // (bounded: only its first moments show)
        if (!player || !inventory || d.age < item_pickup_delay) return;
        const glm::vec2 to = glm::vec2(player->x, player->z) - d.position;
        const float distance = glm::length(to);
        if (!(distance <= item_magnet_radius)) return;
        int& carried = (*inventory)[d.item];
        if (carried >= Inventory::max_stack) return; // no room: it stays where it is
        if (distance > item_collect_radius) {
            d.position += to * std::min(1.0f, item_magnet_speed * dt / distance);
            return;
        }
        const int taken = std::min(d.count, Inventory::max_stack - carried);
        carried += taken;
        if (w.has_resource<WorldEdits>()) ++w.resource<WorldEdits>().count;
        if (w.has_resource<SoundCues>()) w.resource<SoundCues>().entries.push_back({SoundCue::pick_up, d.position});
        if (taken == d.count) ctx.commands().destroy(e);
        else d.count -= taken;
    });
}

} // namespace

void add_gameplay_systems(ecs::Schedule& schedule) {
    schedule.add("player_move", [](ecs::SystemContext& ctx) { move_player(ctx); })
        .reads_resource<Controls, GameClock, CameraRig>()
        .reads_resource<systems::Streaming>()
        .writes<Player, Transform, Camera, PointLight>();
    schedule.add("interact", [](ecs::SystemContext& ctx) { interact(ctx); })
        .main_thread() // edits the wall mirror
        .reads_resource<Controls, systems::GiConfig>()
        .reads_resource<GameTables>() // what a placed torch or prop gives
        .reads<Player, Transform, Camera, Torch, PointLight, Prop>() // what it picks up
        .writes_resource<systems::Streaming, Inventory, WorldEdits, SoundCues>()
        .writes<WallChunk>();
    schedule.add("collect_items", [](ecs::SystemContext& ctx) { collect_items(ctx); })
        .reads_resource<GameClock>()
        .reads<Player, Transform>()
        .writes<DroppedItem>()
        .writes_resource<Inventory, WorldEdits, SoundCues>()
        .after("player_move")  // where the player stands this frame
        .after("interact");    // both write the inventory, edits and cues: what is mined first
    schedule.add("torch_flicker", [](ecs::SystemContext& ctx) {
        const double t = ctx.world.resource<GameClock>().time;
        ctx.world.view<Torch, PointLight>().patch_each<PointLight>(
            [&](const Torch& torch, PointLight& light) { light.intensity = torch.base_intensity * flicker(t, torch.phase); });
    })
        .reads_resource<GameClock>()
        .reads<Torch>()
        .writes<PointLight>()
        .after("player_move"); // both write PointLight (torches here, the player's light there)
    schedule.add("day_cycle", [](ecs::SystemContext& ctx) {
        ecs::World& w = ctx.world;
        DayCycle& day = w.resource<DayCycle>();
        if (w.resource<Controls>().toggle_day_cycle) {
            day.running = !day.running;
            day.drives_sun = true;
        }
        if (!day.drives_sun) return; // a scene's own suns, until the cycle is switched on
        if (day.running) day.time_of_day = std::fmod(day.time_of_day + w.resource<GameClock>().dt / day.day_length, 1.0f);
        // The sun follows the time of day (also when it was set directly, e.g. from the HUD),
        // in steps; an unchanged sun is not touched, so its GI passes stay cached.
        const float t = sun_step_time(day.time_of_day);
        const glm::vec3 direction = sun_direction(t), color = sun_light(t);
        w.view<Sun, DirectionalLight>().each([&](ecs::Entity e, const Sun&, const DirectionalLight& d) {
            if (d.direction == direction && d.color == color && d.intensity == 1.0f) return;
            DirectionalLight& p = w.patch<DirectionalLight>(e);
            p.direction = direction;
            p.color = color;
            p.intensity = 1.0f;
        });
    }).reads_resource<Controls, GameClock>().reads<Sun>().writes_resource<DayCycle>().writes<DirectionalLight>();
}

} // namespace lantern::game
