// The worlds the sandbox game plays in: the seeded procedural caves (default), a Moving AI
// map (`T` cells become trees with proxy shadows), or a scene file. create_world() builds
// the wall source and GI settings and spawns the starting entities: the player, the camera
// that follows it, the sun, and the world's lights and props.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/ecs/world.hpp"
#include "lantern/game/tables.hpp"
#include "lantern/systems/gi_frame.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lantern::game {

enum class WorldKind : std::uint8_t { caves, map, scene };

// What a world is made from; saved with the game so a save reopens the same world.
struct WorldSpec {
    WorldKind kind = WorldKind::caves;
    std::string path;       // map or scene file
    std::uint32_t seed = 1; // caves, and where the decoration is placed
    float cave_threshold = 0.47f; // caves: noise above it is wall (lower: more walls; scene::CaveParams)

    friend bool operator==(const WorldSpec&, const WorldSpec&) = default;
};

const char* world_kind_name(WorldKind kind);

struct GameWorld {
    WorldSpec spec;
    std::shared_ptr<const systems::WorldSource> source;
    systems::GiConfig config; // the scene's GI settings; the game's defaults elsewhere
    ecs::Entity player;
    ecs::Entity camera;
    glm::vec2 spawn{0.0f};
    std::string description; // one line for logs and the HUD
    // Scene worlds: the entity of each of the scene's point lights, emissive lights and shadow
    // proxies, in the scene's order (the scene editor moves and recolours them in place).
    std::vector<ecs::Entity> scene_point_lights, scene_emissive_lights, scene_proxies;
    // A scene world whose file has a "bake" block: the world's own bake settings (the game's
    // background baker starts from them instead of its own; docs/baked.md, "In the game").
    std::optional<scene::BakeSettings> bake;
};

struct WorldOptions {
    scene::GiSettings gi;    // GI settings for caves and maps (scenes bring their own)
    float wall_height = 2.0f; // caves and maps
    bool decorate = true;     // torches and crystals (caves, maps); off for a bare world
    bool player_light = true; // the player carries a small light
    // Scenes: this parsed scene instead of reading spec.path (hot reload parses the file
    // once, checks it, and builds from what it checked).
    const scene::Scene* scene = nullptr;
    // The game's tables (--tables; nullptr: the defaults): the caves' materials, the lights
    // of what the world is decorated with and the player carries. Set as a world resource.
    const GameTables* tables = nullptr;
};

// Builds the world in `world` (which must hold no game entities yet). Errors (a missing or
// malformed map or scene file) carry the file, line and column.
Result<GameWorld> create_world(const WorldSpec& spec, ecs::World& world, const WorldOptions& options);

// The open tile nearest `from` (searched in growing squares up to `max_radius` tiles) whose
// (2 * clearance + 1)^2 neighbourhood is free of walls; `from` itself when none is.
glm::ivec2 find_open_tile(const systems::WorldSource& source, glm::ivec2 from, int clearance, int max_radius = 64);

} // namespace lantern::game
