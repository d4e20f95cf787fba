#include "accuracy_scenes.hpp"

#include "lantern/scene/loader.hpp"
#include "lantern/scene/procedural.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <filesystem>

namespace lantern::bench {
namespace {

constexpr glm::vec2 view_size{30.0f, 16.875f};
constexpr float padding = 1.4f;

scene::Scene base_scene(scene::WallGrid walls, glm::vec2 center, std::string source) {
    scene::Scene s;
    s.source = std::move(source);
    s.walls = std::move(walls);
    s.view = scene::OrthoView{center, view_size};
    s.gi.padding = padding;
    return s;
}

// The floor tile centre nearest to p (searching rings of growing radius), or p itself.
glm::vec2 nearest_floor(const scene::WallGrid& g, glm::vec2 p) {
    const glm::ivec2 t(int(std::floor(p.x)), int(std::floor(p.y)));
    for (int r = 0; r < 12; ++r)
        for (int dz = -r; dz <= r; ++dz)
            for (int dx = -r; dx <= r; ++dx)
                if (std::max(std::abs(dx), std::abs(dz)) == r &&
                    !g.is_wall_tile(t.x + dx, t.y + dz))
                    return glm::vec2(t + glm::ivec2(dx, dz)) + 0.5f;
    return p;
}

// n positions on a jittered grid over the padded view, each moved to the nearest floor.
std::vector<glm::vec2> spread(const scene::WallGrid& g, glm::vec2 center, int n,
                              std::uint32_t salt) {
    std::vector<glm::vec2> out;
    const glm::vec2 size = view_size * padding, lo = center - size * 0.5f;
    const int cols = std::max(1, int(std::ceil(std::sqrt(float(n) * size.x / size.y))));
    const int rows = (n + cols - 1) / cols;
    for (int i = 0; i < n; ++i) {
        const std::uint32_t h = std::uint32_t(i) * 2654435761u + salt;
        const glm::vec2 jitter(float(h & 0xFF) / 255.0f - 0.5f,
                               float((h >> 8) & 0xFF) / 255.0f - 0.5f);
        const glm::vec2 cell(float(i % cols) + 0.5f + 0.6f * jitter.x,
                             float(i / cols) + 0.5f + 0.6f * jitter.y);
        out.push_back(nearest_floor(g, lo + cell * size / glm::vec2(float(cols), float(rows))));
    }
    return out;
}

glm::vec3 warm_or_cool(int i) {
    static constexpr glm::vec3 palette[4] = {
        {1.0f, 0.62f, 0.32f}, {0.45f, 0.65f, 1.0f}, {1.0f, 0.9f, 0.7f}, {0.6f, 1.0f, 0.5f}};
    return palette[i % 4];
}

void add_points(scene::Scene& s, glm::vec2 center, int n, float intensity, float radius,
                std::uint32_t salt) {
    int k = 0;
    for (glm::vec2 p : spread(s.walls, center, n, salt))
        s.point_lights.push_back({p, 1.0f, warm_or_cool(k++), intensity, radius});
}

void add_emissives(scene::Scene& s, glm::vec2 center, int n, std::uint32_t salt) {
    for (glm::vec2 p : spread(s.walls, center, n, salt))
        s.emissive_lights.push_back({p + glm::vec2(0.2f, -0.1f), {0.3f, 0.6f, 1.0f}, 0.3f, 3.0f});
}

// Six rooms (3 x 2) with doorways, lights in three of them: light must turn corners to
// reach the others.
AccuracyScene rooms() {
    const int w = 48, h = 30;
    std::vector<std::uint8_t> cells(std::size_t(w * h), 0);
    auto wall = [&](int x, int z) { cells[std::size_t(z * w + x)] = 1; };
    for (int x = 0; x < w; ++x) wall(x, 0), wall(x, h - 1), wall(x, 15);
    for (int z = 0; z < h; ++z) wall(0, z), wall(w - 1, z), wall(16, z), wall(32, z);
    for (int z : {6, 7, 22, 23})
        cells[std::size_t(z * w + 16)] = cells[std::size_t(z * w + 32)] = 0; // doors
    for (int x : {8, 9, 40, 41}) cells[std::size_t(15 * w + x)] = 0;
    scene::WallGrid g{w, h, {0, 0}, cells};
    scene::Scene s = base_scene(g, {24.0f, 15.0f}, "rooms");
    s.point_lights.push_back({{7.5f, 7.5f}, 1.0f, {1.0f, 0.62f, 0.32f}, 1.5f, 10.0f});
    s.point_lights.push_back({{40.5f, 22.5f}, 1.0f, {0.45f, 0.65f, 1.0f}, 1.5f, 10.0f});
    s.point_lights.push_back({{24.5f, 21.0f}, 1.0f, {1.0f, 0.9f, 0.7f}, 1.2f, 8.0f});
    return {"rooms", "six rooms with doorways, three point lights (radius 8-10)", s};
}

// The seed table's world (procedural caves), where open floor meets a large wall mass;
// radius-10 point lights spread out, emissives.
AccuracyScene caves() {
    const glm::vec2 center{100.0f, 44.0f};
    scene::Scene s = base_scene(
        scene::generate_caves({0, 0}, {192, 128}, scene::CaveParams{7, 0.56f}), center, "caves");
    add_points(s, center, 5, 0.5f, 10.0f, 17u);
    add_emissives(s, center, 16, 91u);
    return {"caves",
            "procedural caves (the seed table's world), 5 point lights radius 10, 16 emissives", s};
}

AccuracyScene sun() {
    const glm::vec2 center{104.0f, 48.0f};
    scene::Scene s = base_scene(
        scene::generate_caves({0, 0}, {160, 96}, scene::CaveParams{3, 0.62f}), center, "sun");
    s.directional_lights.push_back(
        {glm::normalize(glm::vec3(0.7f, -0.35f, 0.35f)), {1.0f, 0.9f, 0.75f}, 0.6f, 4.0f, 0.5f});
    add_points(s, center, 2, 0.8f, 9.0f, 5u);
    return {"sun",
            "open caves and a wall block under a low sun (shadows 4.5 tiles long, bounce 0.5), 2 "
            "point lights",
            s};
}

bool add_map(std::vector<AccuracyScene>& out, std::vector<std::string>& notes,
             const std::string& maps_dir, const char* map, glm::vec2 center, int points,
             int emissives) {
    const std::string path = (std::filesystem::path(maps_dir) / "dao" / map).string();
    auto imported = scene::import_moving_ai_map(path);
    if (!imported) {
        notes.push_back(std::string(map) + " skipped: " + imported.error().message);
        return false;
    }
    const std::string name = std::filesystem::path(map).stem().string();
    scene::Scene s = base_scene(std::move(imported->walls), center, path);
    add_points(s, center, points, 0.8f, 9.0f, 29u);
    if (emissives > 0) add_emissives(s, center, emissives, 43u);
    out.push_back({name,
                   "Dragon Age map " + std::string(map) + " (trees as walls), " +
                       std::to_string(points) + " point lights radius 9" +
                       (emissives ? ", " + std::to_string(emissives) + " emissives" : ""),
                   std::move(s)});
    return true;
}

} // namespace

std::vector<AccuracyScene> accuracy_scenes(const std::string& maps_dir, bool quick,
                                           std::vector<std::string>& notes) {
    std::vector<AccuracyScene> out{rooms()};
    if (quick) return out;
    out.push_back(caves());
    out.push_back(sun());
    if (!std::filesystem::is_directory(maps_dir)) {
        notes.push_back("real maps skipped: " + maps_dir +
                        " not found (run from the repository root, or --maps DIR)");
        return out;
    }
    add_map(out, notes, maps_dir, "den312d.map", {32.0f, 40.0f}, 6, 0);
    add_map(out, notes, maps_dir, "lak303d.map", {36.0f, 84.0f}, 6, 16);
    return out;
}

} // namespace lantern::bench
