#include "lantern/game/gameplay.hpp"

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

Ray camera_ray(const scene::PerspectiveCamera& c, glm::vec2 ndc) {
    const glm::vec3 forward = glm::normalize(c.target - c.position);
    const glm::vec3 up_hint = std::abs(forward.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    const glm::vec3 right = glm::normalize(glm::cross(forward, up_hint));
    const glm::vec3 up = glm::cross(right, forward);
    const float half_h = std::tan(glm::radians(c.fov_deg) * 0.5f);
    const float half_w = half_h * c.aspect;
    const float sx = ndc.x * 2.0f - 1.0f, sy = 1.0f - ndc.y * 2.0f;
    return Ray{c.position, glm::normalize(forward + right * (sx * half_w) + up * (sy * half_h))};
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

std::optional<glm::ivec2> pick_ground(const Ray& ray) {
    if (ray.direction.y >= -1e-4f) return std::nullopt;
    const float t = -ray.origin.y / ray.direction.y;
    const glm::vec3 p = ray.origin + ray.direction * t;
    return glm::ivec2(int(std::floor(p.x)), int(std::floor(p.z)));
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

glm::vec3 sun_direction(float time_of_day) {
    // The sun rises in the east (+x), sets in the west, leaning south (-z).
    const float angle = (time_of_day - 0.25f) * 6.2831853f; // 0 at sunrise, pi at sunset
    const float elevation = std::sin(angle);
    return glm::normalize(glm::vec3(-std::cos(angle), -elevation, 0.35f));
}

glm::vec3 sun_light(float time_of_day) {
    const float elevation = -sun_direction(time_of_day).y;
    const float day = std::clamp(elevation * 3.0f, 0.0f, 1.0f);
    const glm::vec3 noon(1.0f, 0.95f, 0.85f), dusk(1.0f, 0.55f, 0.3f);
    return glm::mix(dusk, noon, std::clamp(elevation * 2.0f, 0.0f, 1.0f)) * day;
}

ecs::Entity spawn_torch(ecs::World& world, glm::vec2 position, float phase) {
    ecs::Entity e = world.create();
    world.emplace<PointLight>(e, PointLight{position, 1.2f, {1.0f, 0.62f, 0.28f}, 1.6f, 7.0f});
    world.emplace<Torch>(e, Torch{1.6f, phase});
    return e;
}

ecs::Entity spawn_prop(ecs::World& world, PropKind kind, glm::vec2 position) {
    ecs::Entity e = world.create();
    world.emplace<Prop>(e, Prop{kind, position});
    scene::ShadowProxy proxy;
    proxy.position = position;
    switch (kind) {
    case PropKind::crystal:
        world.emplace<EmissiveLight>(e, EmissiveLight{position, {0.3f, 0.6f, 1.0f}, 1.2f, 4.5f});
        break;
    case PropKind::tree:
        proxy.shape = scene::ProxyShape::circle;
        proxy.size = {0.45f, 0.45f};
        proxy.max_length = 3.0f;
        world.emplace<ShadowProxy>(e, ShadowProxy{proxy});
        break;
    case PropKind::lamp_post:
        proxy.shape = scene::ProxyShape::box;
        proxy.size = {0.15f, 0.15f};
        proxy.max_length = 2.0f;
        world.emplace<ShadowProxy>(e, ShadowProxy{proxy});
        world.emplace<PointLight>(e, PointLight{position + glm::vec2(0.0f, 0.4f), 2.5f, {1.0f, 0.9f, 0.7f}, 1.4f, 9.0f});
        break;
    }
    return e;
}

ecs::Entity spawn_player(ecs::World& world, glm::vec2 position) {
    ecs::Entity e = world.create();
    world.emplace<Transform>(e, Transform{glm::vec3(position.x, 0.0f, position.y)});
    world.emplace<Player>(e);
    return e;
}

namespace {

void move_player(ecs::SystemContext& ctx, systems::Streaming& streaming) {
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

void interact(ecs::SystemContext& ctx, systems::Streaming& streaming) {
    ecs::World& w = ctx.world;
    const Controls& c = w.resource<Controls>();
    const bool wants = c.mine || c.place_wall || c.place_torch || c.place_crystal || c.place_tree || c.place_lamp;
    if (!wants || !c.has_cursor) return;
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
    if (c.mine) {
        if (auto tile = pick_wall(ray, w.resource<systems::GiConfig>().wall_height, is_wall); tile && in_reach(*tile))
            streaming.set_wall(w, *tile, false);
        return;
    }
    const auto tile = pick_ground(ray);
    if (!tile || !in_reach(*tile) || streaming.is_wall(*tile)) return;
    const glm::vec2 center = glm::vec2(*tile) + 0.5f;
    if (c.place_wall) {
        // Never wall the player in.
        if (glm::distance(center, glm::vec2(player->x, player->z)) > 0.9f) streaming.set_wall(w, *tile, true);
    } else if (c.place_torch) {
        auto& cb = ctx.commands();
        ecs::Entity e = cb.create();
        cb.emplace<PointLight>(e, PointLight{center, 1.2f, {1.0f, 0.62f, 0.28f}, 1.6f, 7.0f});
        cb.emplace<Torch>(e, Torch{1.6f, float(tile->x * 13 + tile->y * 7) * 0.37f});
    } else {
        const PropKind kind = c.place_crystal ? PropKind::crystal : c.place_tree ? PropKind::tree : PropKind::lamp_post;
        auto& cb = ctx.commands();
        ecs::Entity e = cb.create();
        cb.emplace<Prop>(e, Prop{kind, center});
        scene::ShadowProxy proxy;
        proxy.position = center;
        if (kind == PropKind::crystal) {
            cb.emplace<EmissiveLight>(e, EmissiveLight{center, {0.3f, 0.6f, 1.0f}, 1.2f, 4.5f});
        } else {
            proxy.shape = kind == PropKind::tree ? scene::ProxyShape::circle : scene::ProxyShape::box;
            proxy.size = kind == PropKind::tree ? glm::vec2(0.45f) : glm::vec2(0.15f);
            proxy.max_length = kind == PropKind::tree ? 3.0f : 2.0f;
            cb.emplace<ShadowProxy>(e, ShadowProxy{proxy});
            if (kind == PropKind::lamp_post)
                cb.emplace<PointLight>(e, PointLight{center + glm::vec2(0.0f, 0.4f), 2.5f, {1.0f, 0.9f, 0.7f}, 1.4f, 9.0f});
        }
    }
}

} // namespace

void add_gameplay_systems(ecs::Schedule& schedule, systems::Streaming& streaming) {
    schedule.add("player_move", [&streaming](ecs::SystemContext& ctx) { move_player(ctx, streaming); })
        .reads_resource<Controls, GameClock, CameraRig>()
        .reads_resource<systems::Streaming>()
        .writes<Player, Transform, Camera>();
    schedule.add("interact", [&streaming](ecs::SystemContext& ctx) { interact(ctx, streaming); })
        .main_thread() // edits the wall mirror
        .reads_resource<Controls, systems::GiConfig>()
        .reads<Player, Transform, Camera>()
        .writes_resource<systems::Streaming>()
        .writes<WallChunk>();
    schedule.add("torch_flicker", [](ecs::SystemContext& ctx) {
        const double t = ctx.world.resource<GameClock>().time;
        ctx.world.view<Torch, PointLight>().patch_each<PointLight>(
            [&](const Torch& torch, PointLight& light) { light.intensity = torch.base_intensity * flicker(t, torch.phase); });
    }).reads_resource<GameClock>().reads<Torch>().writes<PointLight>();
    schedule.add("day_cycle", [](ecs::SystemContext& ctx) {
        ecs::World& w = ctx.world;
        DayCycle& day = w.resource<DayCycle>();
        if (w.resource<Controls>().toggle_day_cycle) day.running = !day.running;
        if (!day.running) return;
        day.time_of_day = std::fmod(day.time_of_day + w.resource<GameClock>().dt / day.day_length, 1.0f);
        w.view<Sun, DirectionalLight>().patch_each<DirectionalLight>([&](const Sun&, DirectionalLight& d) {
            d.direction = sun_direction(day.time_of_day);
            d.color = sun_light(day.time_of_day);
            d.intensity = 1.0f;
        });
    }).reads_resource<Controls, GameClock>().writes_resource<DayCycle>().writes<DirectionalLight>();
}

} // namespace lantern::game
