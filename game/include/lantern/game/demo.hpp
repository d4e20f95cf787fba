// The headless demo's script: what a player would do in the first seconds of a game, as
// Controls frame by frame, so the demo runs through exactly the code a player drives
// (movement, picking under a cursor, mining, placing, the day cycle).
//
// The script is planned from the world around the spawn (a walk along open tiles found by
// breadth-first search) and reacts to where the player actually is, so it works in any
// world. It is deterministic: same world, same frames, same controls.
//
//   0 - 8 %    stand at night; a torch is placed next to the player
//   8 - 45 %   walk out along the path; mine the walls beside it at 25 % and 35 %, going
//              to each mined tile until its block glides over (collected: DroppedItem)
//   40 - 55 %  place a crystal, a lamp post and a tree near the path
//   55 %       the day cycle starts (fast: a night-day-dusk turn over the rest of the run)
//   55 - 100 % walk back towards the start, mining once more
#pragma once

#include "lantern/game/game_components.hpp"
#include "lantern/game/gameplay.hpp"

#include <deque>
#include <utility>
#include <vector>

namespace lantern::game {

class DemoScript {
  public:
    // Plans the walk: up to `max_path` tiles of open ground from `spawn`.
    DemoScript(const IsWall& is_wall, glm::vec2 spawn, int frames, float wall_height = 2.0f, int max_path = 40);

    // The controls of frame `frame` (0-based) for a player at `player` seen by `camera`.
    Controls controls(int frame, glm::vec2 player, const scene::PerspectiveCamera& camera, const IsWall& is_wall);

    // How long a day lasts once the script starts the cycle (seconds at 60 frames/s).
    float day_length() const;
    const std::vector<glm::ivec2>& path() const { return path_; }
    int frames() const { return frames_; }
    bool is_walking(int frame) const;

  private:
    // The cursor on the nearest minable wall, and its tile.
    std::optional<std::pair<glm::vec2, glm::ivec2>> cursor_on_wall(glm::vec2 player, const scene::PerspectiveCamera& camera,
                                                                   const IsWall& is_wall) const;
    std::optional<glm::vec2> cursor_on_ground(glm::vec2 player, glm::vec2 facing, const scene::PerspectiveCamera& camera,
                                              const IsWall& is_wall) const;

    std::vector<glm::ivec2> path_; // tiles, spawn first
    int frames_ = 0;
    float wall_height_ = 2.0f;
    int progress_ = 0; // the path tile the walk heads for
    glm::vec2 last_facing_{0.0f, -1.0f};
    std::deque<std::pair<glm::ivec2, int>> pickups_; // mined tiles whose blocks to collect, and when
};

} // namespace lantern::game
