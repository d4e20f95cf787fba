#include "lantern/gi/frame_inputs.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace lantern::gi {
namespace {

GpuPointLight pack_light(glm::vec2 position, glm::vec3 color, float intensity, float radius) {
    return GpuPointLight{glm::vec4(position, radius, 0.0f), glm::vec4(color * intensity, 0.0f)};
}

GpuShadowProxy pack_proxy(const scene::ShadowProxy& p) {
    return GpuShadowProxy{
        glm::vec4(p.position, p.size),
        glm::vec4(p.max_length, p.end_cap_blend, p.penumbra_width, p.penumbra_length),
        glm::vec4(p.penumbra_power, float(p.shape), float(p.width_mode), float(p.penumbra_mode))};
}

float proxy_reach(const scene::ShadowProxy& p) {
    return std::max(p.size.x, p.size.y) + p.max_length + std::max(p.penumbra_width, p.penumbra_length);
}

// Indices of `items` passing `keep`, ordered by (distance to `center`, index), first `cap`.
template <typename T, typename Keep>
std::vector<std::uint32_t> select(const std::vector<T>& items, Keep keep, glm::vec2 center, std::size_t cap) {
    std::vector<std::uint32_t> ids;
    for (std::uint32_t i = 0; i < items.size(); ++i)
        if (keep(items[i])) ids.push_back(i);
    if (ids.size() > cap) {
        std::stable_sort(ids.begin(), ids.end(), [&](std::uint32_t a, std::uint32_t b) {
            return glm::distance(items[a].position, center) < glm::distance(items[b].position, center);
        });
        ids.resize(cap);
        std::sort(ids.begin(), ids.end()); // keep scene order for the GPU (stable sums)
    }
    return ids;
}

} // namespace

float distance_to_window(const GiWindow& w, glm::vec2 p) {
    const glm::vec2 lo(w.view.min_x, w.view.min_z);
    const glm::vec2 hi = lo + glm::vec2(w.view.width, w.view.height);
    return glm::length(glm::max(glm::max(lo - p, p - hi), glm::vec2(0.0f)));
}

GpuDirectionalLight pack_directional(const scene::DirectionalLight& l) {
    const glm::vec3 dir = glm::normalize(l.direction);
    const float multiplier = 1.0f / std::max(std::abs(dir.y), 0.02f);
    return GpuDirectionalLight{glm::vec4(dir, l.base_shadow_distance),
                               glm::vec4(l.color * l.intensity, multiplier),
                               glm::vec4(l.bounce_intensity, 0.0f, 0.0f, 0.0f)};
}

FrameInputs gather_frame_inputs(const scene::Scene& s, const GiWindow& window) {
    FrameInputs in;
    in.window = window;
    in.walls = WallView::of(s.walls);
    in.wall_height = s.wall_height;
    in.settings = s.gi;
    const glm::vec2 center = window.center();
    auto reaches = [&](const auto& light) { return distance_to_window(window, light.position) <= light.radius; };

    in.point_light_ids = select(s.point_lights, reaches, center, std::size_t(std::max(0, s.gi.max_lights)));
    for (std::uint32_t i : in.point_light_ids) {
        const auto& l = s.point_lights[i];
        in.point_lights.push_back(pack_light(l.position, l.color, l.intensity, l.radius));
    }
    in.emissive_ids = select(s.emissive_lights, reaches, center, s.emissive_lights.size());
    for (std::uint32_t i : in.emissive_ids) {
        const auto& l = s.emissive_lights[i];
        in.emissive_lights.push_back(pack_light(l.position, l.color, l.intensity, l.radius));
    }
    for (const auto& d : s.directional_lights) in.directional_lights.push_back(pack_directional(d));
    in.proxy_ids = select(
        s.shadow_proxies, [&](const scene::ShadowProxy& p) { return distance_to_window(window, p.position) <= proxy_reach(p); },
        center, std::size_t(std::max(0, s.gi.max_shadow_proxies)));
    for (std::uint32_t i : in.proxy_ids) in.proxies.push_back(pack_proxy(s.shadow_proxies[i]));
    return in;
}

} // namespace lantern::gi
