// The sandbox game's rules: movement with wall collision, the following camera, picking
// tiles under the cursor, mining and placing, torch flicker, the day/night cycle. Pure
// functions (unit-tested) and the systems that apply them each frame.
#pragma once

#include "lantern/ecs/schedule.hpp"
#include "lantern/game/game_components.hpp"
#include "lantern/game/tables.hpp"
#include "lantern/systems/gi_frame.hpp"
#include "lantern/systems/streaming.hpp"

#include <functional>
#include <optional>

namespace lantern::game {

using IsWall = std::function<bool(int x, int z)>;

// Moves a circle of `radius` by `delta` (x, z), one axis at a time, stopping at wall tiles.
glm::vec2 move_with_collision(glm::vec2 position, glm::vec2 delta, float radius, const IsWall& is_wall);

// The camera that follows a player standing at `player` (world x, y, z).
scene::PerspectiveCamera follow_camera(glm::vec3 player, const CameraRig& rig);

struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f}; // normalised
};
// The ray through `ndc` ([0, 1]^2 over the view, y down) of a perspective camera, with the
// same basis as the GI window's footprint (gi::visible_area).
Ray camera_ray(const scene::PerspectiveCamera& camera, glm::vec2 ndc);
// Where a world point appears on the view: [0, 1]^2, y down (the inverse of camera_ray);
// nullopt behind the camera.
std::optional<glm::vec2> project_to_ndc(const scene::PerspectiveCamera& camera, glm::vec3 point);
// The first wall the ray meets below `wall_height` (walls are boxes from the ground up).
std::optional<glm::ivec2> pick_wall(const Ray& ray, float wall_height, const IsWall& is_wall, float max_distance = 200.0f);
// Where the ray meets the ground (y = 0): the point (x, z), and its tile.
std::optional<glm::vec2> ground_point(const Ray& ray);
std::optional<glm::ivec2> pick_ground(const Ray& ray);

// Torch flicker: a smooth deterministic factor in [0.8, 1.05].
float flicker(double time, float phase);

// The sun by time of day (0 midnight, 0.5 noon): travel direction, colour * intensity
// (scene::day_sun_direction and day_sun_light: the path a bake's sun keys follow).
glm::vec3 sun_direction(float time_of_day);
glm::vec3 sun_light(float time_of_day);
// The day cycle moves the sun in steps of 1/sun_steps_per_day of a day (half a degree):
// the time of day the sun shows, rounded down to its step. Between steps the suns' GI pass
// stays cached while torches flicker (docs/game.md, "The day cycle").
inline constexpr int sun_steps_per_day = 720;
float sun_step_time(float time_of_day);

// Adds the game systems (input-driven movement and camera, interaction, flicker, day
// cycle) to a GI frame's schedule; they run before the GI systems.
void add_gameplay_systems(ecs::Schedule& schedule);

// What a placed prop or torch is made of (its components), in one place for the world's
// set-up and the player's placing.
struct PropParts {
    Prop prop;
    std::optional<EmissiveLight> emissive;
    std::optional<ShadowProxy> proxy;
    std::optional<PointLight> light;
    std::optional<ProbeAnchor> anchor; // a tree: its base (its crown sways and overhangs)
};
PropParts prop_parts(PropKind kind, glm::vec2 position, const GameTables& tables = default_tables());
struct TorchParts {
    PointLight light;
    Torch torch;
};
TorchParts torch_parts(glm::vec2 position, float phase, const GameTables& tables = default_tables());

// Entity factories (used by interaction, world set-up and save files).
ecs::Entity spawn_torch(ecs::World& world, glm::vec2 position, float phase, const GameTables& tables = default_tables());
ecs::Entity spawn_prop(ecs::World& world, PropKind kind, glm::vec2 position,
                       const GameTables& tables = default_tables());
// The player; with `light`, it carries a small warm lantern (a PointLight that follows it).
ecs::Entity spawn_player(ecs::World& world, glm::vec2 position, bool light = true,
                         const GameTables& tables = default_tables());
// The tables into a running world: the GameTables resource, the caves' materials
// (`materials`: the world's are the tables', not a scene's) and the light of every torch,
// lamp post and the player's lantern, and every crystal's intensity and radius (its colour
// where it had the previous tables' colour: the caves' crystals keep their own hues);
// docs/game.md, "Game tables".
void apply_tables(ecs::World& world, const GameTables& tables, bool materials);

} // namespace lantern::game
