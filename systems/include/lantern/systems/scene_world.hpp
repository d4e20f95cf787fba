// Scene files into the ECS world: one entity per light and shadow proxy, a camera entity
// (Camera + GICache) from the scene's view, the GI settings, and a world source over the
// scene's wall grid. lantern-render and the tests build their frames this way.
#pragma once

#include "lantern/ecs/world.hpp"
#include "lantern/scene/scene.hpp"
#include "lantern/systems/gi_frame.hpp"

#include <memory>

namespace lantern::systems {

struct SceneWorld {
    std::shared_ptr<const WorldSource> source;
    GiConfig config;
    ecs::Entity camera;
    std::vector<ecs::Entity> point_lights, emissive_lights, directional_lights, proxies; // scene order
};

SceneWorld populate_world(const scene::Scene& scene, ecs::World& world);

} // namespace lantern::systems
