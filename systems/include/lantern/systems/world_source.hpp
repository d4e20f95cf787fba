// Where wall tiles come from: a seeded procedural cave world of unbounded size, or a finite
// grid (a scene's rows, a Moving AI map) surrounded by air. The streaming system asks a
// source for whole chunks from background jobs, so generate() must be thread-safe and
// deterministic.
#pragma once

#include "lantern/components/components.hpp"
#include "lantern/scene/procedural.hpp"

#include <memory>
#include <span>

namespace lantern::systems {

inline constexpr int chunk_size = WallChunk::size;

class WorldSource {
  public:
    virtual ~WorldSource() = default;
    // Fills `cells` (chunk_size^2, row-major: 0 air, 1 rock, 2 + k material k) with chunk `coord`.
    virtual void generate(glm::ivec2 coord, std::span<std::uint8_t> cells) const = 0;
    // One tile of the source (the default generates its chunk).
    virtual bool is_wall(glm::ivec2 tile) const;
    // Its cell value: 0 air, 1 rock, 2 + k material k (the default generates its chunk).
    virtual std::uint8_t cell(glm::ivec2 tile) const;
};

class CaveSource final : public WorldSource {
  public:
    explicit CaveSource(const scene::CaveParams& params) : params_(params) {}
    void generate(glm::ivec2 coord, std::span<std::uint8_t> cells) const override;
    bool is_wall(glm::ivec2 tile) const override { return scene::cave_wall(tile.x, tile.y, params_); }
    std::uint8_t cell(glm::ivec2 tile) const override { return scene::cave_cell(tile.x, tile.y, params_); }
    const scene::CaveParams& params() const { return params_; }

  private:
    scene::CaveParams params_;
};

class GridSource final : public WorldSource {
  public:
    explicit GridSource(scene::WallGrid grid) : grid_(std::move(grid)) {}
    void generate(glm::ivec2 coord, std::span<std::uint8_t> cells) const override;
    bool is_wall(glm::ivec2 tile) const override { return grid_.is_wall_tile(tile.x, tile.y); }
    std::uint8_t cell(glm::ivec2 tile) const override { return grid_.cell(tile.x, tile.y); }
    const scene::WallGrid& grid() const { return grid_; }

  private:
    scene::WallGrid grid_;
};

} // namespace lantern::systems
