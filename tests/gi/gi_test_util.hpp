// Small scenes built in code for the GI tests.
#pragma once

#include "lantern/gi/baked_light.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/scene/scene.hpp"

#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace gi_test {

// '#' wall, anything else floor. rows[0] is z = origin.z.
inline lantern::scene::WallGrid grid_from_rows(const std::vector<std::string>& rows, glm::ivec2 origin = {0, 0}) {
    lantern::scene::WallGrid g;
    g.height = int(rows.size());
    g.width = rows.empty() ? 0 : int(rows[0].size());
    g.origin = origin;
    g.cells.resize(std::size_t(g.width) * std::size_t(g.height));
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c) g.cells[std::size_t(c + r * g.width)] = rows[std::size_t(r)][std::size_t(c)] == '#';
    return g;
}

inline lantern::gi::WallView view_of(const lantern::scene::WallGrid& g) { return lantern::gi::WallView::of(g); }

inline lantern::scene::Scene open_scene(glm::vec2 center, glm::vec2 size, int resolution = 4) {
    lantern::scene::Scene s;
    s.view = lantern::scene::OrthoView{center, size};
    s.gi.resolution = resolution;
    s.gi.padding = 1.0f;
    return s;
}

// A smooth, coloured baked light over tiles [origin, origin + tiles) at `res` texels a tile:
// every layer a different pattern, open where the walls say (as bake::runtime_light does).
// With `pulsing`, five more layers: a pulsing part (seed 004's pulsing emission).
inline std::shared_ptr<const lantern::gi::BakedLight> synthetic_bake(const lantern::gi::WallView& walls, glm::ivec2 origin, glm::ivec2 tiles, int res,
                                                 float eps, std::uint64_t key, bool pulsing = false, int sun_keys = 0) {
    std::vector<lantern::gi::Field> layers(std::size_t(lantern::gi::baked_layers * ((pulsing ? 2 : 1) + sun_keys)));
    static constexpr glm::ivec2 across[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int layer = 0; layer < int(layers.size()); ++layer) {
        const int l = layer % lantern::gi::baked_layers;
        lantern::gi::Field& f = layers[std::size_t(layer)];
        f = lantern::gi::Field(tiles.x * res, tiles.y * res);
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const glm::ivec2 tile = origin + glm::ivec2(x / res, y / res);
                const bool wall = walls.is_wall(tile.x, tile.y);
                const std::size_t i = std::size_t(y) * std::size_t(f.width) + std::size_t(x);
                f.air[i] = l == 0 ? !wall
                                  : wall && !walls.is_wall(tile.x + across[l - 1].x, tile.y + across[l - 1].y);
                const float u = float(x) / float(res), v = float(y) / float(res);
                f.rgb[i * 3 + 0] = 0.6f + 0.5f * std::sin(0.31f * u + float(layer));
                f.rgb[i * 3 + 1] = 0.4f + 0.3f * std::cos(0.23f * v - 0.5f * float(layer));
                f.rgb[i * 3 + 2] = 0.05f * float(layer + 1) + 0.02f * u;
            }
    }
    return std::make_shared<const lantern::gi::BakedLight>(
        lantern::gi::make_baked_light(origin, res, layers, eps, key, lantern::gi::brick_levels - 1, {}, sun_keys));
}


} // namespace gi_test
