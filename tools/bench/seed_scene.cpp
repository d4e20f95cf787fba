#include "seed_scene.hpp"

#include "lantern/scene/procedural.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::bench {
namespace {

constexpr glm::vec2 view_center{96.0f, 64.0f};
constexpr glm::vec2 view_size{30.0f, 16.875f};
constexpr float padding = 1.4f;

// n positions spread over the padded window on a jittered grid, moved to the nearest floor.
std::vector<glm::vec2> spread(const scene::WallGrid& g, int n, std::uint32_t salt) {
    std::vector<glm::vec2> out;
    if (n <= 0) return out;
    const glm::vec2 size = view_size * padding;
    const glm::vec2 lo = view_center - size * 0.5f;
    const int cols = std::max(1, int(std::ceil(std::sqrt(float(n) * size.x / size.y))));
    const int rows = (n + cols - 1) / cols;
    for (int i = 0; i < n; ++i) {
        const int cx = i % cols, cz = i / cols;
        std::uint32_t h = std::uint32_t(i) * 2654435761u + salt;
        const float jx = float(h & 0xFF) / 255.0f - 0.5f, jz = float((h >> 8) & 0xFF) / 255.0f - 0.5f;
        glm::vec2 p = lo + glm::vec2((float(cx) + 0.5f + 0.5f * jx) * size.x / float(cols),
                                     (float(cz) + 0.5f + 0.5f * jz) * size.y / float(rows));
        // Nearest floor tile centre in a small spiral.
        glm::ivec2 t(int(std::floor(p.x)), int(std::floor(p.y)));
        for (int r = 0; r < 8 && g.is_wall_tile(t.x, t.y); ++r)
            for (int dz = -r; dz <= r && g.is_wall_tile(t.x, t.y); ++dz)
                for (int dx = -r; dx <= r; ++dx)
                    if (!g.is_wall_tile(int(std::floor(p.x)) + dx, int(std::floor(p.y)) + dz)) {
                        t = {int(std::floor(p.x)) + dx, int(std::floor(p.y)) + dz};
                        break;
                    }
        out.push_back(glm::vec2(t) + 0.5f);
    }
    return out;
}

} // namespace

std::string SeedRow::label() const {
    const char* s = scale == scene::HeatScale::full ? "full" : scale == scene::HeatScale::half ? "half" : "quarter";
    return "giRes " + std::to_string(resolution) + " " + s + ", " + std::to_string(points) + " point, " +
           std::to_string(emissives) + " emissive, " + std::to_string(directionals) + " directional" +
           (method == scene::GiMethod::radiosity ? ", radiosity"
            : method == scene::GiMethod::gather  ? ", gather " + std::to_string(bounces) + " bounces"
                                                 : "");
}

std::vector<SeedRow> seed_rows() {
    using scene::HeatScale;
    return {
        {16, HeatScale::full, 1, 0, 0},     {16, HeatScale::full, 1, 0, 1},    {16, HeatScale::full, 1, 256, 0},
        {16, HeatScale::full, 32, 256, 0},  {16, HeatScale::full, 64, 256, 0}, {16, HeatScale::half, 64, 256, 0},
        {16, HeatScale::quarter, 64, 256, 0}, {8, HeatScale::full, 64, 256, 0}, {8, HeatScale::half, 64, 256, 0},
        {8, HeatScale::quarter, 64, 256, 0},
        // Many lights (issue 15): the cost of one more light, from the slope between rows.
        {8, HeatScale::quarter, 256, 256, 0}, {8, HeatScale::quarter, 1024, 256, 0},
        // Seed 003's radiosity beside the heat rows above (issue 16): the same scene and lights.
        {16, HeatScale::quarter, 64, 256, 0, scene::GiMethod::radiosity},
        {8, HeatScale::full, 64, 256, 0, scene::GiMethod::radiosity},
        {8, HeatScale::half, 64, 256, 0, scene::GiMethod::radiosity},
        {8, HeatScale::quarter, 64, 256, 0, scene::GiMethod::radiosity},
        // The gather method (physical, issue 17) at its defaults (32 + 32 rays, margin 4), and
        // with one bounce more and one less a frame: the cost of a bounce.
        {8, HeatScale::half, 64, 256, 0, scene::GiMethod::gather, 1},
        {8, HeatScale::half, 64, 256, 0, scene::GiMethod::gather, 2},
        {8, HeatScale::half, 64, 256, 0, scene::GiMethod::gather, 3},
        {8, HeatScale::quarter, 64, 256, 0, scene::GiMethod::gather, 2},
    };
}

scene::Scene seed_scene(const SeedRow& row) {
    scene::Scene s;
    s.source = "seed table: " + row.label();
    s.walls = scene::generate_caves({0, 0}, {192, 128}, scene::CaveParams{7, 0.56f});
    s.view = scene::OrthoView{view_center, view_size};
    s.gi.resolution = row.resolution;
    s.gi.padding = padding;
    s.gi.heat_rounds = 20;
    s.gi.heat_scale = row.scale;
    s.gi.method = row.method;
    s.gi.radiosity.scale = row.scale;
    s.gi.gather.scale = row.scale;
    s.gi.gather.bounces = row.bounces;
    s.gi.max_lights = std::max(256, row.points + row.emissives);
    s.gi.max_shadow_proxies = 64;
    int k = 0;
    for (glm::vec2 p : spread(s.walls, row.points, 17u)) {
        const float hue = float(k++ % 5) / 5.0f;
        s.point_lights.push_back({p, 1.0f, {1.0f, 0.55f + 0.3f * hue, 0.3f + 0.5f * (1.0f - hue)}, 1.5f, 10.0f});
    }
    for (glm::vec2 p : spread(s.walls, row.emissives, 91u))
        s.emissive_lights.push_back({p + glm::vec2(0.2f, -0.1f), {0.3f, 0.6f, 1.0f}, 0.4f, 3.0f});
    for (glm::vec2 p : spread(s.walls, 38, 53u)) {
        scene::ShadowProxy proxy;
        proxy.position = p + glm::vec2(0.25f, 0.1f);
        proxy.shape = (k++ % 2) ? scene::ProxyShape::circle : scene::ProxyShape::box;
        proxy.size = {0.4f, 0.3f};
        s.shadow_proxies.push_back(proxy);
    }
    if (row.directionals > 0)
        s.directional_lights.push_back({glm::normalize(glm::vec3(0.4f, -0.6f, 0.2f)), {1.0f, 0.95f, 0.8f}, 1.0f, 4.0f, 0.5f});
    return s;
}

} // namespace lantern::bench
