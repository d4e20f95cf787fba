#include "problem.hpp"

#include <cmath>
#include <limits>

namespace lantern::transport {
namespace {

// The scene's sources without Lantern's per-frame caps: the reference is the truth the
// capped frame approximates. Walls are left out (the copy is not what inputs.walls views).
scene::Scene uncapped_sources(const scene::Scene& s) {
    scene::Scene out;
    out.wall_height = s.wall_height;
    out.gi = s.gi;
    out.gi.max_lights = std::numeric_limits<int>::max();
    out.gi.max_shadow_proxies = std::numeric_limits<int>::max();
    out.point_lights = s.point_lights;
    out.emissive_lights = s.emissive_lights;
    out.directional_lights = s.directional_lights;
    out.shadow_proxies = s.shadow_proxies;
    return out;
}

gi::GiWindow domain_window(const gi::GiWindow& w, int margin) {
    const int res = w.resolution;
    const int tiles_x = (w.width + res - 1) / res + 2 * margin;
    const int tiles_z = (w.height + res - 1) / res + 2 * margin;
    gi::GiWindow d;
    d.resolution = res;
    d.width = tiles_x * res;
    d.height = tiles_z * res;
    d.view = {w.view.min_x - float(margin), w.view.min_z - float(margin), float(tiles_x),
              float(tiles_z)};
    return d;
}

Domain make_domain(const gi::GiWindow& window, const gi::GiWindow& dw, const gi::WallView& walls,
                   int margin) {
    Domain d;
    d.resolution = dw.resolution;
    d.min_tile = {int(std::floor(dw.view.min_x)), int(std::floor(dw.view.min_z))};
    d.width = dw.width;
    d.height = dw.height;
    d.offset = margin * dw.resolution;
    d.window_width = window.width;
    d.window_height = window.height;
    d.wall.resize(std::size_t(d.width) * std::size_t(d.height));
    for (int y = 0; y < d.height; ++y)
        for (int x = 0; x < d.width; ++x)
            d.wall[std::size_t(y) * std::size_t(d.width) + std::size_t(x)] =
                walls.cell(d.min_tile.x + x / d.resolution, d.min_tile.y + y / d.resolution);
    return d;
}

} // namespace

Result<Problem> make_problem(const scene::Scene& scene, const TransportSettings& settings) {
    std::string why;
    auto window = gi::compute_window(scene.view, scene.gi.padding, settings.resolution, &why);
    if (!window) return make_error("transport: the view has no GI window: " + why);
    Problem p;
    p.window = *window;
    const gi::GiWindow dw = domain_window(*window, settings.margin);
    // Walls from the caller's scene (so inputs.walls views memory that outlives the solve),
    // sources from the uncapped copy.
    p.inputs = gi::gather_frame_inputs(scene, dw);
    gi::FrameInputs sources = gi::gather_frame_inputs(uncapped_sources(scene), dw);
    p.inputs.point_lights = std::move(sources.point_lights);
    p.inputs.point_light_ids = std::move(sources.point_light_ids);
    p.inputs.emissive_lights = std::move(sources.emissive_lights);
    p.inputs.emissive_ids = std::move(sources.emissive_ids);
    p.inputs.proxies = std::move(sources.proxies);
    p.inputs.proxy_ids = std::move(sources.proxy_ids);
    p.domain = make_domain(*window, dw, p.inputs.walls, settings.margin);
    p.inputs.settings.wall_albedo = settings.albedo; // the default wall's
    p.materials = gi::material_table(p.inputs);
    return p;
}

} // namespace lantern::transport
