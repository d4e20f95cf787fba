// Where wall tiles come from: a seeded procedural cave world of unbounded size, or a finite
// grid (a scene's rows, a Moving AI map) surrounded by air (or by rock, the game's maps). The streaming system asks a
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
    // What lies beyond the grid: air (the GI's and scene files' convention, DESIGN.md), or
    // rock (the game's maps: the player cannot walk off the map).
    enum class Outside : std::uint8_t { air, rock };
    explicit GridSource(scene::WallGrid grid, Outside outside = Outside::air)
        : grid_(std::move(grid)), outside_(outside) {}
    void generate(glm::ivec2 coord, std::span<std::uint8_t> cells) const override;
    bool is_wall(glm::ivec2 tile) const override { return cell(tile) != 0; }
    std::uint8_t cell(glm::ivec2 tile) const override {
        const glm::ivec2 c = tile - grid_.origin;
        if (outside_ == Outside::rock && (c.x < 0 || c.y < 0 || c.x >= grid_.width || c.y >= grid_.height))
            return scene::default_wall_cell;
        return grid_.cell(tile.x, tile.y);
    }
    const scene::WallGrid& grid() const { return grid_; }

  private:
    scene::WallGrid grid_;
    Outside outside_;
};

} // namespace lantern::systems
