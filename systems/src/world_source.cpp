#include "lantern/systems/world_source.hpp"

namespace lantern::systems {

void CaveSource::generate(glm::ivec2 coord, std::span<std::uint8_t> cells) const {
    for (int r = 0; r < chunk_size; ++r)
        for (int c = 0; c < chunk_size; ++c)
            cells[std::size_t(r * chunk_size + c)] =
                scene::cave_wall(coord.x * chunk_size + c, coord.y * chunk_size + r, params_) ? 1 : 0;
}

void GridSource::generate(glm::ivec2 coord, std::span<std::uint8_t> cells) const {
    for (int r = 0; r < chunk_size; ++r)
        for (int c = 0; c < chunk_size; ++c)
            cells[std::size_t(r * chunk_size + c)] =
                grid_.is_wall_tile(coord.x * chunk_size + c, coord.y * chunk_size + r) ? 1 : 0;
}

} // namespace lantern::systems
