#include "lantern/systems/scene_world.hpp"

namespace lantern::systems {

SceneWorld populate_world(const scene::Scene& s, ecs::World& world) {
    SceneWorld out;
    out.source = std::make_shared<GridSource>(s.walls);
    out.config.settings = s.gi;
    out.config.wall_height = s.wall_height;
    out.config.materials = s.materials;
    out.camera = world.create();
    world.emplace<Camera>(out.camera, Camera{s.view});
    world.emplace<GICache>(out.camera);
    for (const scene::PointLight& l : s.point_lights) {
        ecs::Entity e = world.create();
        world.emplace<PointLight>(e, PointLight{l.position, l.height, l.color, l.intensity, l.radius, l.mode});
        out.point_lights.push_back(e);
    }
    for (const scene::EmissiveLight& l : s.emissive_lights) {
        ecs::Entity e = world.create();
        world.emplace<EmissiveLight>(e, EmissiveLight{l.position, l.color, l.intensity, l.radius, l.mode});
        out.emissive_lights.push_back(e);
    }
    for (const scene::DirectionalLight& l : s.directional_lights) {
        ecs::Entity e = world.create();
        world.emplace<DirectionalLight>(
            e, DirectionalLight{l.direction, l.color, l.intensity, l.base_shadow_distance, l.bounce_intensity, l.mode});
        out.directional_lights.push_back(e);
    }
    for (const scene::ShadowProxy& p : s.shadow_proxies) {
        ecs::Entity e = world.create();
        world.emplace<ShadowProxy>(e, ShadowProxy{p});
        out.proxies.push_back(e);
    }
    return out;
}

} // namespace lantern::systems
