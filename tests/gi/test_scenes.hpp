// The scenes the GPU-vs-reference tests and the stability suite run: small (tests run on
// lavapipe), each aimed at one part of the pipeline. Two more come from the real maps.
#pragma once

#include "gi_test_util.hpp"

#include "common/test_support.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/window.hpp"
#include "lantern/scene/loader.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace gi_test {

using lantern::scene::Scene;

// The frame inputs of a scene in its own GI window (the test fails when it has none).
inline lantern::gi::FrameInputs inputs_of(const Scene& s) {
    std::string why;
    auto w = lantern::gi::compute_window(s.view, s.gi, &why);
    EXPECT_TRUE(w) << why;
    return w ? lantern::gi::gather_frame_inputs(s, *w) : lantern::gi::FrameInputs{};
}
// The inputs point at the scene's walls (FrameInputs::walls): a temporary scene would leave
// them dangling.
lantern::gi::FrameInputs inputs_of(Scene&&) = delete;

inline lantern::scene::PointLight point(glm::vec2 p, glm::vec3 c, float intensity, float radius) {
    return {p, 1.0f, c, intensity, radius};
}
inline lantern::scene::EmissiveLight emissive(glm::vec2 p, glm::vec3 c, float intensity, float radius) {
    return {p, c, intensity, radius};
}

// Deterministic cave-like walls: random fill smoothed by a few cellular-automaton steps.
inline lantern::scene::WallGrid cave(int w, int h, std::uint32_t seed, float fill = 0.45f) {
    std::mt19937 rng(seed);
    std::vector<std::string> rows(std::size_t(h), std::string(std::size_t(w), '.'));
    for (auto& r : rows)
        for (auto& c : r) c = (rng() % 1000) < fill * 1000 ? '#' : '.';
    for (int step = 0; step < 3; ++step) {
        auto next = rows;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                int n = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        int xx = x + dx, yy = y + dy;
                        n += (xx < 0 || yy < 0 || xx >= w || yy >= h) ? 1 : rows[std::size_t(yy)][std::size_t(xx)] == '#';
                    }
                next[std::size_t(y)][std::size_t(x)] = n >= 5 ? '#' : '.';
            }
        rows = next;
    }
    return grid_from_rows(rows);
}

struct NamedScene {
    std::string name;
    Scene scene;
};

inline std::vector<NamedScene> comparison_scenes() {
    std::vector<NamedScene> out;
    using lantern::scene::OrthoView;
    {   // 1. Open field, one point light.
        Scene s = open_scene({8, 8}, {16, 16}, 4);
        s.walls = grid_from_rows(std::vector<std::string>(16, std::string(16, '.')));
        s.point_lights.push_back(point({8.3f, 7.6f}, {1.0f, 0.6f, 0.3f}, 2.0f, 6.0f));
        out.push_back({"open_field", s});
    }
    {   // 2. Rooms and doorways, point lights and emissives; walls of four materials (red
        // rock, white, glowing lava and the default), which only the gather method reads.
        Scene s = open_scene({12, 10}, {24, 20}, 4);
        std::vector<std::string> rows(20, std::string(24, '.'));
        for (int x = 0; x < 24; ++x) rows[10][std::size_t(x)] = (x == 5 || x == 17) ? '.' : '#';
        for (int z = 0; z < 20; ++z) rows[std::size_t(z)][12] = (z == 4 || z == 15) ? '.' : '#';
        s.walls = grid_from_rows(rows);
        s.materials = {{"red_rock", {0.8f, 0.15f, 0.1f}, {}},
                       {"white", {0.9f, 0.9f, 0.9f}, {}},
                       {"lava", {0.3f, 0.1f, 0.05f}, {1.5f, 0.5f, 0.1f}}};
        for (int x = 0; x < 5; ++x) s.walls.cells[std::size_t(10 * 24 + x)] = lantern::scene::material_cell(0);
        for (int x = 6; x < 12; ++x) s.walls.cells[std::size_t(10 * 24 + x)] = lantern::scene::material_cell(1);
        for (int z = 0; z < 4; ++z) s.walls.cells[std::size_t(z * 24 + 12)] = lantern::scene::material_cell(2);
        s.point_lights.push_back(point({4.5f, 4.5f}, {1.0f, 0.8f, 0.5f}, 2.0f, 9.0f));
        s.point_lights.push_back(point({18.2f, 15.7f}, {0.3f, 0.6f, 1.0f}, 1.5f, 8.0f));
        s.emissive_lights.push_back(emissive({16.5f, 3.5f}, {0.2f, 1.0f, 0.4f}, 1.0f, 4.0f));
        s.gi.probe_rays = 32; // live probes: four materials, a glowing one
        out.push_back({"rooms", s});
    }
    {   // 3. Diagonal gaps: corners with both, one and no side walls.
        Scene s = open_scene({8, 8}, {16, 16}, 8);
        std::vector<std::string> rows(16, std::string(16, '.'));
        for (int i = 2; i < 14; i += 2) rows[std::size_t(i)][std::size_t(i)] = '#';
        for (int i = 3; i < 13; i += 4) rows[std::size_t(i)][std::size_t(i - 1)] = '#';
        rows[6][9] = rows[5][10] = '#';
        s.walls = grid_from_rows(rows);
        s.point_lights.push_back(point({1.5f, 1.5f}, {1, 1, 1}, 1.0f, 14.0f));
        s.point_lights.push_back(point({12.0f, 4.0f}, {1, 0.5f, 0.2f}, 1.0f, 8.0f)); // on grid corners
        out.push_back({"diagonal_gaps", s});
    }
    {   // 4. Shadow proxies: boxes and circles, every width and penumbra mode.
        Scene s = open_scene({10, 10}, {20, 20}, 4);
        s.walls = grid_from_rows(std::vector<std::string>(20, std::string(20, '.')));
        s.point_lights.push_back(point({10.0f, 10.0f}, {1, 1, 1}, 2.0f, 10.0f));
        int k = 0;
        for (auto shape : {lantern::scene::ProxyShape::box, lantern::scene::ProxyShape::circle})
            for (auto wm : {lantern::scene::WidthMode::projected, lantern::scene::WidthMode::max_axis})
                for (auto pm : {lantern::scene::PenumbraMode::inward, lantern::scene::PenumbraMode::outward,
                                lantern::scene::PenumbraMode::both}) {
                    lantern::scene::ShadowProxy p;
                    float a = float(k++) * 0.5236f;
                    p.position = glm::vec2(10.0f) + 4.0f * glm::vec2(std::cos(a), std::sin(a));
                    p.shape = shape;
                    p.size = {0.6f, 0.3f};
                    p.width_mode = wm;
                    p.penumbra_mode = pm;
                    p.end_cap_blend = 0.25f * float(k % 4);
                    p.penumbra_power = 1.0f + float(k % 3);
                    s.shadow_proxies.push_back(p);
                }
        out.push_back({"proxies", s});
    }
    {   // 5. A low sun over tall walls, with a proxy.
        Scene s = open_scene({10, 8}, {20, 16}, 4);
        s.walls = cave(20, 16, 5, 0.35f);
        s.wall_height = 3.0f;
        s.directional_lights.push_back({glm::normalize(glm::vec3(0.6f, -0.5f, 0.3f)), {1.0f, 0.9f, 0.7f}, 1.2f, 4.0f, 0.4f});
        lantern::scene::ShadowProxy tree;
        tree.position = {7.5f, 7.5f};
        s.shadow_proxies.push_back(tree);
        s.point_lights.push_back(point({5.5f, 5.5f}, {1, 0.5f, 0.2f}, 1.0f, 6.0f));
        out.push_back({"sun_and_walls", s});
    }
    {   // 6. Perspective camera over a cave.
        Scene s;
        s.walls = cave(40, 40, 11);
        s.view = lantern::scene::PerspectiveCamera{{20.0f, 14.0f, 8.0f}, {20.0f, 0.0f, 18.0f}, 40.0f, 16.0f / 9.0f};
        s.gi.resolution = 2;
        s.point_lights.push_back(point({18.5f, 17.5f}, {1, 0.7f, 0.4f}, 2.0f, 10.0f));
        s.point_lights.push_back(point({25.5f, 20.5f}, {0.5f, 0.7f, 1.0f}, 1.0f, 8.0f));
        s.gi.probe_rays = 24; // live probes at giRes 2, rays that do not divide 4096 evenly
        out.push_back({"camera_cave", s});
    }
    {   // 7. Lights and walls outside the window reaching in.
        Scene s = open_scene({8, 8}, {16, 16}, 4);
        std::vector<std::string> rows(16, std::string(24, '.'));
        for (int z = 3; z < 13; ++z) rows[std::size_t(z)][2] = '#';
        s.walls = grid_from_rows(rows, {-8, 0});
        s.point_lights.push_back(point({-7.5f, 8.5f}, {1, 1, 1}, 2.0f, 12.0f));
        s.point_lights.push_back(point({20.0f, 8.0f}, {1, 0.3f, 0.3f}, 1.0f, 7.0f));
        out.push_back({"outside_window", s});
    }
    {   // 8. A light inside a wall, one on a cell boundary, one on a grid corner.
        Scene s = open_scene({8, 8}, {16, 16}, 4);
        std::vector<std::string> rows(16, std::string(16, '.'));
        rows[8][8] = rows[8][9] = rows[4][4] = '#';
        s.walls = grid_from_rows(rows);
        s.point_lights.push_back(point({8.5f, 8.5f}, {1, 1, 1}, 1.0f, 6.0f));
        s.point_lights.push_back(point({5.0f, 4.5f}, {0.4f, 1.0f, 0.4f}, 1.0f, 6.0f));
        s.point_lights.push_back(point({10.0f, 10.0f}, {1, 0.4f, 0.9f}, 1.0f, 5.0f));
        out.push_back({"light_edge_cases", s});
    }
    {   // 9. Dense cave, many lights and emissives, AO dithered, soft falloff.
        Scene s = open_scene({16, 12}, {32, 24}, 2);
        s.walls = cave(32, 24, 23);
        s.gi.ao.dither = true;
        s.gi.light_softness = 2.0f;
        s.gi.wall_face_exponent = 3.0f;
        std::mt19937 rng(9);
        for (int i = 0; i < 12; ++i)
            s.point_lights.push_back(point({float(rng() % 32) + 0.5f, float(rng() % 24) + 0.5f},
                                           {0.5f + float(rng() % 50) / 100.0f, 0.6f, 0.4f}, 1.0f, 6.0f));
        for (int i = 0; i < 20; ++i)
            s.emissive_lights.push_back(emissive({float(rng() % 32) + 0.25f, float(rng() % 24) + 0.75f},
                                                 {0.2f, 0.4f, 1.0f}, 0.5f, 3.0f));
        out.push_back({"dense_cave", s});
    }
    {   // 10. Two suns (one below the horizon), angle scale, AO off.
        Scene s = open_scene({8, 8}, {16, 16}, 4);
        s.walls = cave(16, 16, 3, 0.3f);
        s.gi.ao.enabled = false;
        s.gi.directional_angle_scale = 0.5f;
        s.gi.wall_face_exponent = 0.5f;
        s.directional_lights.push_back({glm::normalize(glm::vec3(-0.3f, -0.8f, -0.5f)), {0.9f, 0.9f, 1.0f}, 1.0f, 6.0f, 0.5f});
        s.directional_lights.push_back({glm::normalize(glm::vec3(0.3f, 0.2f, 0.5f)), {1.0f, 0.5f, 0.2f}, 1.0f, 6.0f, 0.5f});
        out.push_back({"two_suns", s});
    }
    {   // 11. The game's fixed-camera culling and then some (-z and +x faces left out), AO on
        // wall faces, a sun and a proxy.
        Scene s = open_scene({8, 8}, {16, 16}, 4);
        s.walls = cave(16, 16, 31, 0.35f);
        s.gi.wall_faces.nz = false;
        s.gi.wall_faces.px = false;
        s.gi.ao.walls = true;
        s.gi.ao.strength = 0.9f;
        s.directional_lights.push_back({glm::normalize(glm::vec3(-0.5f, -0.6f, 0.4f)), {1.0f, 0.95f, 0.9f}, 0.8f, 5.0f, 0.3f});
        lantern::scene::ShadowProxy post;
        post.position = {6.5f, 9.5f};
        s.shadow_proxies.push_back(post);
        s.point_lights.push_back(point({8.5f, 8.5f}, {1, 0.6f, 0.3f}, 1.5f, 7.0f));
        s.emissive_lights.push_back(emissive({4.5f, 11.5f}, {0.3f, 0.5f, 1.0f}, 0.8f, 3.0f));
        s.gi.probe_rays = 16; // live probes with two faces not computed
        out.push_back({"culled_faces_wall_ao", s});
    }
    {   // 12. Wall lighting off: no face passes or textures; walls shade as (dark) ground.
        Scene s = open_scene({8, 8}, {16, 16}, 4);
        s.walls = cave(16, 16, 37, 0.3f);
        s.gi.wall_lighting = false;
        s.directional_lights.push_back({glm::normalize(glm::vec3(0.4f, -0.7f, -0.3f)), {0.9f, 0.9f, 1.0f}, 0.7f, 5.0f, 0.4f});
        s.point_lights.push_back(point({7.5f, 8.5f}, {1, 0.8f, 0.5f}, 1.5f, 8.0f));
        s.emissive_lights.push_back(emissive({11.5f, 4.5f}, {1.0f, 0.3f, 0.2f}, 0.8f, 3.0f));
        out.push_back({"no_wall_lighting", s});
    }
    {   // 13. The window locked to texels, not tiles (gi.window_snap): its origin 11 texels
        // (2.75 tiles) left of a tile boundary, so AO and every pass see texels whose tile
        // starts mid-window; full heat, AO dithered.
        Scene s = open_scene({8.55f, 7.8f}, {16, 16}, 4);
        s.walls = cave(16, 16, 41, 0.35f);
        s.gi.window_snap = lantern::scene::WindowSnap::texel;
        s.gi.ao.dither = true;
        s.directional_lights.push_back({glm::normalize(glm::vec3(0.3f, -0.7f, 0.5f)), {1.0f, 0.9f, 0.8f}, 0.6f, 5.0f, 0.3f});
        s.point_lights.push_back(point({6.3f, 9.1f}, {1, 0.7f, 0.4f}, 1.5f, 8.0f));
        s.emissive_lights.push_back(emissive({11.5f, 5.5f}, {0.4f, 1.0f, 0.5f}, 0.8f, 3.0f));
        s.gi.probe_rays = 16; // live probes in a window that starts mid-tile
        out.push_back({"texel_window", s});
    }
    {   // 14. The suns' shadows by the shadow map (gi.sun_shadow_method): a low sun along an
        // exact diagonal (rays through tile corners: the map's close calls), a high one off
        // the axes, tall walls, a proxy, a patch of checkerboard.
        Scene s = open_scene({10, 8}, {20, 16}, 4);
        s.walls = cave(20, 16, 43, 0.3f);
        for (int z = 2; z < 6; ++z)
            for (int x = 12; x < 17; ++x) s.walls.cells[std::size_t(z * 20 + x)] = std::uint8_t((x + z) % 2);
        s.wall_height = 2.0f;
        s.gi.sun_shadow_method = lantern::scene::SunShadowMethod::shadow_map;
        s.directional_lights.push_back({glm::normalize(glm::vec3(1.0f, -0.35f, 1.0f)), {1.0f, 0.8f, 0.6f}, 0.9f, 4.0f, 0.4f});
        s.directional_lights.push_back({glm::normalize(glm::vec3(-0.2f, -0.9f, 0.45f)), {0.5f, 0.6f, 1.0f}, 0.5f, 4.0f, 0.2f});
        lantern::scene::ShadowProxy tree;
        tree.position = {6.5f, 9.5f};
        s.shadow_proxies.push_back(tree);
        s.point_lights.push_back(point({4.5f, 4.5f}, {1, 0.6f, 0.3f}, 1.0f, 6.0f));
        out.push_back({"sun_map", s});
    }
    {   // 15. Proxy shadows unfolded up the walls (gi.proxy_wall_shadows): proxies before
        // walls, lit by point lights, an emissive and a sun; tall walls.
        Scene s = open_scene({8, 8}, {16, 16}, 4);
        std::vector<std::string> rows(16, std::string(16, '.'));
        for (int x = 2; x < 14; ++x) rows[11][std::size_t(x)] = '#';
        for (int z = 3; z < 9; ++z) rows[std::size_t(z)][12] = '#';
        rows[5][4] = '#';
        s.walls = grid_from_rows(rows);
        s.wall_height = 2.5f;
        s.gi.proxy_wall_shadows = lantern::scene::ProxyWallShadows::unfold;
        for (glm::vec2 at : {glm::vec2(6.5f, 8.5f), glm::vec2(9.5f, 6.0f), glm::vec2(10.0f, 9.7f)}) {
            lantern::scene::ShadowProxy p;
            p.position = at;
            p.max_length = 3.5f;
            p.penumbra_length = 0.5f;
            s.shadow_proxies.push_back(p);
        }
        lantern::scene::ShadowProxy crate;
        crate.position = {4.5f, 9.0f};
        crate.shape = lantern::scene::ProxyShape::box;
        crate.size = {0.4f, 0.3f};
        crate.penumbra_width = 0.0f;
        crate.penumbra_length = 0.0f;
        crate.max_length = 2.5f;
        s.shadow_proxies.push_back(crate);
        s.point_lights.push_back(point({6.0f, 5.0f}, {1, 0.8f, 0.5f}, 1.5f, 10.0f));
        s.point_lights.push_back(point({9.0f, 3.5f}, {0.5f, 0.7f, 1.0f}, 1.0f, 9.0f));
        s.emissive_lights.push_back(emissive({2.5f, 10.0f}, {1.0f, 0.3f, 0.2f}, 0.6f, 3.0f));
        s.directional_lights.push_back({glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f)), {1.0f, 0.9f, 0.7f}, 0.6f, 4.0f, 0.3f});
        out.push_back({"unfolded_proxies", s});
    }
    return out;
}

// A window of a real map with lights spread over its floor (skipped without ../shared).
// One of comparison_scenes() by its name; throws (the test fails with the name) when absent,
// so tests never depend on the scenes' order.
inline NamedScene comparison_scene(const std::string& name) {
    for (NamedScene& s : comparison_scenes())
        if (s.name == name) return std::move(s);
    throw std::out_of_range("no comparison scene named '" + name + "'");
}

inline std::vector<std::string> comparison_scene_names() {
    std::vector<std::string> names;
    for (const NamedScene& s : comparison_scenes()) names.push_back(s.name);
    return names;
}

// The shadow-map stability grids (sun_map_test, point_map_test): a checkerboard (rays through
// tile corners everywhere), one-tile corridors at giRes 1, all walls, no walls, and the rooms
// at giRes 32. `dense` is true for the first two, which deserve more rays.
struct GridScene {
    NamedScene named;
    bool dense = false;
};
inline std::vector<GridScene> shadow_stability_grids() {
    auto grid = [](int w, int h, char fill) { return std::vector<std::string>(std::size_t(h), std::string(std::size_t(w), fill)); };
    std::vector<GridScene> out;
    {
        auto rows = grid(16, 16, '.');
        for (int z = 0; z < 16; ++z)
            for (int x = 0; x < 16; ++x) rows[std::size_t(z)][std::size_t(x)] = (x + z) % 2 ? '#' : '.';
        Scene s = open_scene({8, 8}, {16, 16}, 4);
        s.walls = grid_from_rows(rows);
        out.push_back({{"checkerboard", s}, true});
    }
    {
        auto rows = grid(64, 64, '#');
        for (int x = 1; x < 63; ++x) rows[10][std::size_t(x)] = '.';
        for (int z = 10; z < 40; ++z) rows[std::size_t(z)][62] = '.';
        for (int x = 5; x < 63; ++x) rows[40][std::size_t(x)] = '.';
        Scene s = open_scene({32, 32}, {64, 64}, 1);
        s.walls = grid_from_rows(rows);
        out.push_back({{"one-tile corridors", s}, true});
    }
    Scene s = open_scene({8, 8}, {16, 16}, 4);
    s.walls = grid_from_rows(grid(16, 16, '#'));
    out.push_back({{"all walls", s}, false});
    s.walls = grid_from_rows(grid(16, 16, '.'));
    out.push_back({{"no walls", s}, false});
    Scene fine = comparison_scene("rooms").scene;
    fine.gi.resolution = 32;
    fine.view = lantern::scene::OrthoView{{6.0f, 5.0f}, {8.0f, 6.0f}};
    out.push_back({{"rooms at giRes 32", fine}, false});
    return out;
}

inline std::optional<NamedScene> map_scene(const std::string& file, glm::vec2 center, std::uint32_t seed) {
    auto shared = lantern::test::shared_dir();
    if (shared.empty()) return std::nullopt;
    lantern::scene::MapImportOptions options;
    options.extra_floor_chars = "st";
    auto map = lantern::scene::import_moving_ai_map((shared / "maps" / "dao" / file).string(), options);
    if (!map) return std::nullopt;
    Scene s = open_scene(center, {30.0f, 16.875f}, 4);
    s.walls = map->walls;
    std::mt19937 rng(seed);
    for (int placed = 0, tries = 0; placed < 8 && tries < 1000; ++tries) {
        glm::vec2 p = center + glm::vec2(float(rng() % 30) - 15.0f, float(rng() % 17) - 8.0f) + 0.5f;
        if (s.walls.is_wall_tile(int(std::floor(p.x)), int(std::floor(p.y)))) continue;
        s.point_lights.push_back(point(p, {1.0f, 0.7f, 0.4f}, 1.5f, 8.0f));
        ++placed;
    }
    return NamedScene{file, s};
}

} // namespace gi_test
