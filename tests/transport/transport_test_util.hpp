// Small scenes for the transport tests: a window of 64 x 64 texels (the GI minimum) over a
// grid drawn with characters, '#' for walls.
#pragma once

#include "lantern/scene/scene.hpp"
#include "lantern/transport/solver.hpp"

#include <string>
#include <vector>

namespace transport_test {

// rows[0] is z = 0; '#' is a wall.
inline lantern::scene::WallGrid grid(const std::vector<std::string>& rows) {
    lantern::scene::WallGrid g;
    g.height = int(rows.size());
    g.width = int(rows[0].size());
    g.cells.resize(std::size_t(g.width) * std::size_t(g.height));
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c)
            g.cells[std::size_t(c + r * g.width)] = rows[std::size_t(r)][std::size_t(c)] == '#';
    return g;
}

// A top-down view of `size` tiles centred on `center`, no padding.
inline lantern::scene::Scene scene(const std::vector<std::string>& rows, glm::vec2 center,
                                   glm::vec2 size) {
    lantern::scene::Scene s;
    s.walls = grid(rows);
    s.view = lantern::scene::OrthoView{center, size};
    s.gi.padding = 1.0f;
    return s;
}

// 16 x 16 tiles with a closed 8 x 8 room (walls one tile thick) at tiles 4..11.
inline std::vector<std::string> closed_room() {
    std::vector<std::string> rows(16, std::string(16, '.'));
    for (int i = 4; i <= 11; ++i)
        rows[4][std::size_t(i)] = rows[11][std::size_t(i)] = rows[std::size_t(i)][4] =
            rows[std::size_t(i)][11] = '#';
    return rows;
}

// Settings for fast tests: resolution 4 (16 x 16 tiles = 64 x 64 texels), small batches.
inline lantern::transport::TransportSettings quick(float albedo, std::uint32_t photons = 1u << 14) {
    lantern::transport::TransportSettings t;
    t.albedo = albedo;
    t.resolution = 4;
    t.margin = 2;
    t.photons_per_batch = photons;
    t.min_batches = 8;
    t.max_batches = 8;
    t.target_relative_error = 0.5;
    return t;
}

} // namespace transport_test
