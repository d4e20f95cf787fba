#include "lantern/game/world_setup.hpp"

#include "lantern/game/gameplay.hpp"
#include "lantern/scene/loader.hpp"
#include "lantern/systems/scene_world.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::game {
namespace {

std::uint32_t mix(std::uint32_t seed, int a, int b, std::uint32_t salt) {
    std::uint32_t h = seed * 0x9E3779B9u ^ std::uint32_t(a) * 0x85EBCA6Bu ^ std::uint32_t(b) * 0xC2B2AE35u ^ salt;
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    h ^= h >> 16;
    return h;
}

bool open_around(const systems::WorldSource& source, glm::ivec2 t, int clearance) {
    for (int dz = -clearance; dz <= clearance; ++dz)
        for (int dx = -clearance; dx <= clearance; ++dx)
            if (source.is_wall({t.x + dx, t.y + dz})) return false;
    return true;
}

bool next_to_wall(const systems::WorldSource& source, glm::ivec2 t) {
    return source.is_wall({t.x + 1, t.y}) || source.is_wall({t.x - 1, t.y}) || source.is_wall({t.x, t.y + 1}) ||
           source.is_wall({t.x, t.y - 1});
}

// Crystals grow in open tiles next to walls; one chance per `cell` x `cell` block.
void scatter_crystals(const systems::WorldSource& source, ecs::World& world, std::uint32_t seed, glm::ivec2 min,
                      glm::ivec2 max, int cell, float chance, const GameTables& tables) {
    // The tables' crystal colour, and two hues of the caves' own.
    const glm::vec3 colors[] = {tables.crystal.color, {0.35f, 1.0f, 0.55f}, {0.85f, 0.4f, 1.0f}};
    for (int cz = min.y / cell; cz < max.y / cell; ++cz)
        for (int cx = min.x / cell; cx < max.x / cell; ++cx) {
            const std::uint32_t h = mix(seed, cx, cz, 0xC0FFEEu);
            if (float(h & 0xFFFF) / 65535.0f >= chance) continue;
            for (int attempt = 0; attempt < 12; ++attempt) {
                const std::uint32_t r = mix(seed, cx, cz, 0x51u + std::uint32_t(attempt));
                const glm::ivec2 t(cx * cell + int(r % std::uint32_t(cell)), cz * cell + int((r >> 8) % std::uint32_t(cell)));
                if (source.is_wall(t) || !next_to_wall(source, t)) continue;
                const ecs::Entity e = spawn_prop(world, PropKind::crystal, glm::vec2(t) + 0.5f, tables);
                world.get<EmissiveLight>(e).color = colors[(r >> 20) % 3];
                break;
            }
        }
}

// Torches in open tiles, one chance per block.
void scatter_torches(const systems::WorldSource& source, ecs::World& world, std::uint32_t seed, glm::ivec2 min,
                     glm::ivec2 max, int cell, float chance, const GameTables& tables) {
    for (int cz = min.y / cell; cz < max.y / cell; ++cz)
        for (int cx = min.x / cell; cx < max.x / cell; ++cx) {
            const std::uint32_t h = mix(seed, cx, cz, 0x70C4u);
            if (float(h & 0xFFFF) / 65535.0f >= chance) continue;
            for (int attempt = 0; attempt < 12; ++attempt) {
                const std::uint32_t r = mix(seed, cx, cz, 0x99u + std::uint32_t(attempt));
                const glm::ivec2 t(cx * cell + int(r % std::uint32_t(cell)), cz * cell + int((r >> 8) % std::uint32_t(cell)));
                if (!open_around(source, t, 1)) continue;
                spawn_torch(world, glm::vec2(t) + 0.5f, float(r % 1000u) * 0.01f, tables);
                break;
            }
        }
}

// Lamp posts (a mixed light: its bounce baked) in open tiles with room around them.
void scatter_lamps(const systems::WorldSource& source, ecs::World& world, std::uint32_t seed, glm::ivec2 min,
                   glm::ivec2 max, int cell, float chance, const GameTables& tables) {
    for (int cz = min.y / cell; cz < max.y / cell; ++cz)
        for (int cx = min.x / cell; cx < max.x / cell; ++cx) {
            const std::uint32_t h = mix(seed, cx, cz, 0x1A3Bu);
            if (float(h & 0xFFFF) / 65535.0f >= chance) continue;
            for (int attempt = 0; attempt < 12; ++attempt) {
                const std::uint32_t r = mix(seed, cx, cz, 0x2C4u + std::uint32_t(attempt));
                const glm::ivec2 t(cx * cell + int(r % std::uint32_t(cell)), cz * cell + int((r >> 8) % std::uint32_t(cell)));
                if (!open_around(source, t, 1)) continue;
                spawn_prop(world, PropKind::lamp_post, glm::vec2(t) + 0.5f, tables);
                break;
            }
        }
}

ecs::Entity spawn_sun(ecs::World& world) {
    const ecs::Entity e = world.create();
    world.emplace<Sun>(e);
    const float t = world.has_resource<DayCycle>() ? world.resource<DayCycle>().time_of_day : DayCycle{}.time_of_day;
    world.emplace<DirectionalLight>(e, DirectionalLight{sun_direction(sun_step_time(t)), sun_light(sun_step_time(t)), 1.0f, 4.0f, 0.5f});
    return e;
}

ecs::Entity spawn_camera(ecs::World& world, glm::vec2 at) {
    const ecs::Entity e = world.create();
    const CameraRig rig = world.has_resource<CameraRig>() ? world.resource<CameraRig>() : CameraRig{};
    world.emplace<Camera>(e, Camera{follow_camera({at.x, 0.0f, at.y}, rig)});
    world.emplace<GICache>(e);
    return e;
}

} // namespace

const char* world_kind_name(WorldKind kind) {
    switch (kind) {
    case WorldKind::caves: return "caves";
    case WorldKind::map: return "map";
    case WorldKind::scene: return "scene";
    }
    return "?";
}

glm::ivec2 find_open_tile(const systems::WorldSource& source, glm::ivec2 from, int clearance, int max_radius) {
    // Ring by ring (the square's rim at Chebyshev distance r), the closest open tile of the
    // first ring that has one; ties go to the first in row-major order. Only the rim is
    // visited: O(r) per ring, linear in the area scanned.
    for (int r = 0; r <= max_radius; ++r) {
        std::optional<glm::ivec2> best;
        float best_d = 0.0f;
        auto consider = [&](int dx, int dz) {
            const glm::ivec2 t = from + glm::ivec2(dx, dz);
            if (!open_around(source, t, clearance)) return;
            const float d = float(dx * dx + dz * dz);
            if (!best || d < best_d) best = t, best_d = d;
        };
        for (int dz = -r; dz <= r; ++dz) {
            if (dz == -r || dz == r) {
                for (int dx = -r; dx <= r; ++dx) consider(dx, dz);
            } else {
                consider(-r, dz);
                consider(r, dz);
            }
        }
        if (best) return *best;
    }
    return from;
}

Result<GameWorld> create_world(const WorldSpec& spec, ecs::World& world, const WorldOptions& options) {
    GameWorld out;
    out.spec = spec;
    const GameTables& tables = options.tables ? *options.tables : default_tables();
    world.set_resource<GameTables>(tables);
    out.config.settings = options.gi;
    out.config.wall_height = options.wall_height;
    glm::ivec2 spawn_from(0);
    switch (spec.kind) {
    case WorldKind::caves: {
        // Lava and crystal veins in the rock: the caves' baked emitters (docs/baked.md).
        auto source = std::make_shared<systems::CaveSource>(scene::CaveParams{spec.seed, spec.cave_threshold, true});
        out.source = source;
        out.config.materials = tables.materials;
        spawn_from = find_open_tile(*source, {0, 0}, 2, 96);
        if (options.decorate) {
            scatter_crystals(*source, world, spec.seed, spawn_from - 160, spawn_from + 160, 11, 0.55f, tables);
            // A few torches around the start, more scattered through the caves.
            for (glm::ivec2 offset : {glm::ivec2(4, 3), glm::ivec2(-5, -2)}) {
                const glm::ivec2 t = find_open_tile(*source, spawn_from + offset, 0, 4);
                spawn_torch(world, glm::vec2(t) + 0.5f, float(offset.x * 7 + offset.y) * 0.31f, tables);
            }
            scatter_torches(*source, world, spec.seed, spawn_from - 160, spawn_from + 160, 23, 0.45f, tables);
            scatter_lamps(*source, world, spec.seed, spawn_from - 160, spawn_from + 160, 31, 0.35f, tables);
        }
        out.description = "procedural caves, seed " + std::to_string(spec.seed);
        break;
    }
    case WorldKind::map: {
        scene::MapImportOptions import;
        import.trees = scene::TreeMode::proxy;
        auto map = scene::import_moving_ai_map(spec.path, import);
        if (!map) return map.error();
        for (glm::ivec2 t : map->trees) spawn_prop(world, PropKind::tree, glm::vec2(t) + 0.5f, tables);
        const glm::ivec2 size(map->walls.width, map->walls.height);
        // Rock beyond the map's edge (the player cannot walk off it; the GI sees rock there too).
        auto source = std::make_shared<systems::GridSource>(std::move(map->walls), systems::GridSource::Outside::rock);
        out.source = source;
        spawn_from = find_open_tile(*source, size / 2, 1, std::max(size.x, size.y));
        if (options.decorate) {
            scatter_torches(*source, world, spec.seed, {0, 0}, size, 19, 0.5f, tables);
            scatter_crystals(*source, world, spec.seed, {0, 0}, size, 29, 0.3f, tables);
        }
        out.description = "map " + spec.path + " (" + std::to_string(size.x) + "x" + std::to_string(size.y) + ", " +
                          std::to_string(map->trees.size()) + " trees)";
        break;
    }
    case WorldKind::scene: {
        auto scene = options.scene ? Result<scene::Scene>(*options.scene) : scene::load_scene(spec.path);
        if (!scene) return scene.error();
        const systems::SceneWorld sw = systems::populate_world(*scene, world);
        out.source = sw.source;
        out.config = sw.config;
        out.camera = sw.camera;
        out.scene_point_lights = sw.point_lights;
        out.scene_emissive_lights = sw.emissive_lights;
        out.scene_proxies = sw.proxies;
        if (scene->bake_given) out.bake = scene->bake;
        // The scene's suns follow the day cycle once it is switched on.
        for (ecs::Entity e : sw.directional_lights) world.emplace<Sun>(e);
        glm::vec2 center(0.0f);
        if (auto* o = std::get_if<scene::OrthoView>(&scene->view)) center = o->center;
        if (auto* p = std::get_if<scene::PerspectiveCamera>(&scene->view)) center = {p->target.x, p->target.z};
        spawn_from = find_open_tile(*out.source, glm::ivec2(glm::floor(center)), 0, 64);
        out.description = "scene " + spec.path;
        break;
    }
    }
    out.spawn = glm::vec2(spawn_from) + 0.5f;
    out.player = spawn_player(world, out.spawn, options.player_light, tables);
    if (out.camera.is_null())
        out.camera = spawn_camera(world, out.spawn);
    else
        world.get<Camera>(out.camera).view = follow_camera({out.spawn.x, 0.0f, out.spawn.y},
                                                           world.has_resource<CameraRig>() ? world.resource<CameraRig>() : CameraRig{});
    bool has_sun = false;
    world.view<Sun>().each([&](const Sun&) { has_sun = true; });
    if (!has_sun) spawn_sun(world);
    return out;
}

} // namespace lantern::game
