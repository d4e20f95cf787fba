// Small scenes built in code for the GI tests.
#pragma once

#include "lantern/gi/frame_inputs.hpp"
#include "lantern/scene/scene.hpp"

#include <glm/geometric.hpp>

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

} // namespace gi_test
