#include "lantern/systems/world_source.hpp"

#include "lantern/systems/streaming.hpp"

namespace lantern::systems {

bool WorldSource::is_wall(glm::ivec2 tile) const { return cell(tile) != 0; }

std::uint8_t WorldSource::cell(glm::ivec2 tile) const {
    std::uint8_t cells[chunk_size * chunk_size];
    generate({floor_div(tile.x, chunk_size), floor_div(tile.y, chunk_size)}, cells);
    return cells[pmod(tile.y, chunk_size) * chunk_size + pmod(tile.x, chunk_size)];
}

void CaveSource::generate(glm::ivec2 coord, std::span<std::uint8_t> cells) const {
    for (int r = 0; r < chunk_size; ++r)
        for (int c = 0; c < chunk_size; ++c)
            cells[std::size_t(r * chunk_size + c)] = scene::cave_cell(coord.x * chunk_size + c, coord.y * chunk_size + r, params_);
}

void GridSource::generate(glm::ivec2 coord, std::span<std::uint8_t> cells) const {
    for (int r = 0; r < chunk_size; ++r)
        for (int c = 0; c < chunk_size; ++c)
            cells[std::size_t(r * chunk_size + c)] = cell({coord.x * chunk_size + c, coord.y * chunk_size + r}); // material kept
}

} // namespace lantern::systems
