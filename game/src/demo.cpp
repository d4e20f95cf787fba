#include "lantern/game/demo.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>

namespace lantern::game {
namespace {

constexpr glm::ivec2 steps4[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};

bool at(int frame, int frames, float fraction) { return frame == int(float(frames) * fraction); }

} // namespace

DemoScript::DemoScript(const IsWall& is_wall, glm::vec2 spawn, int frames, float wall_height, int max_path)
    : frames_(frames), wall_height_(wall_height) {
    // Breadth-first search over open tiles; the walk goes to the farthest tile reached.
    const glm::ivec2 start(int(std::floor(spawn.x)), int(std::floor(spawn.y)));
    auto key = [](glm::ivec2 t) { return std::pair<int, int>(t.x, t.y); };
    std::map<std::pair<int, int>, glm::ivec2> parent;
    std::deque<std::pair<glm::ivec2, int>> queue{{start, 0}};
    parent[key(start)] = start;
    glm::ivec2 farthest = start;
    int farthest_d = 0;
    while (!queue.empty()) {
        const auto [t, d] = queue.front();
        queue.pop_front();
        if (d > farthest_d) farthest = t, farthest_d = d;
        if (d == max_path) continue;
        for (glm::ivec2 s : steps4) {
            const glm::ivec2 n = t + s;
            if (is_wall(n.x, n.y) || parent.count(key(n))) continue;
            parent[key(n)] = t;
            queue.push_back({n, d + 1});
        }
    }
    for (glm::ivec2 t = farthest;; t = parent[key(t)]) {
        path_.push_back(t);
        if (t == start) break;
    }
    std::reverse(path_.begin(), path_.end());
}

float DemoScript::day_length() const {
    // From night (0.85) to the next dusk (0.75 + 1) over the last 45 % of the run.
    return std::max(1.0f, 0.45f * float(frames_) / 60.0f / 0.9f);
}

bool DemoScript::is_walking(int frame) const {
    const float t = float(frame) / float(std::max(frames_, 1));
    return (t >= 0.08f && t < 0.45f) || t >= 0.57f;
}

std::optional<std::pair<glm::vec2, glm::ivec2>> DemoScript::cursor_on_wall(glm::vec2 player,
                                                                           const scene::PerspectiveCamera& camera,
                                                                           const IsWall& is_wall) const {
    // The nearest wall within reach whose top the cursor can point at.
    const glm::ivec2 p(int(std::floor(player.x)), int(std::floor(player.y)));
    std::optional<std::pair<glm::vec2, glm::ivec2>> best;
    float best_d = 1e9f;
    for (int dz = -3; dz <= 3; ++dz)
        for (int dx = -3; dx <= 3; ++dx) {
            const glm::ivec2 t = p + glm::ivec2(dx, dz);
            if (!is_wall(t.x, t.y)) continue;
            const glm::vec3 top(float(t.x) + 0.5f, wall_height_ * 0.999f, float(t.y) + 0.5f);
            const float d = glm::distance(glm::vec2(top.x, top.z), player);
            if (d >= best_d || d > interaction_range - 0.5f) continue;
            const auto ndc = project_to_ndc(camera, top);
            if (!ndc || ndc->x < 0.0f || ndc->x > 1.0f || ndc->y < 0.0f || ndc->y > 1.0f) continue;
            // Only a wall the cursor ray meets first (not hidden behind another).
            const auto hit = pick_wall(camera_ray(camera, *ndc), wall_height_, is_wall);
            if (!hit || *hit != t) continue;
            best = std::pair{*ndc, t}, best_d = d;
        }
    return best;
}

std::optional<glm::vec2> DemoScript::cursor_on_ground(glm::vec2 player, glm::vec2 facing,
                                                      const scene::PerspectiveCamera& camera,
                                                      const IsWall& is_wall) const {
    // An open tile 2 tiles ahead (or the nearest open tile around), not the player's own.
    const glm::ivec2 own(int(std::floor(player.x)), int(std::floor(player.y)));
    std::optional<glm::vec2> best;
    float best_score = 1e9f;
    for (int dz = -3; dz <= 3; ++dz)
        for (int dx = -3; dx <= 3; ++dx) {
            const glm::ivec2 t = own + glm::ivec2(dx, dz);
            if (t == own || is_wall(t.x, t.y)) continue;
            const glm::vec2 c = glm::vec2(t) + 0.5f;
            const float d = glm::distance(c, player);
            if (d < 1.2f || d > 3.0f) continue;
            const glm::vec2 ahead = player + facing * 2.0f;
            const float score = glm::distance(c, ahead);
            if (score >= best_score) continue;
            const auto ndc = project_to_ndc(camera, glm::vec3(c.x, 0.0f, c.y));
            if (!ndc || ndc->x < 0.0f || ndc->x > 1.0f || ndc->y < 0.0f || ndc->y > 1.0f) continue;
            const auto hit = pick_ground(camera_ray(camera, *ndc));
            if (!hit || *hit != t || pick_wall(camera_ray(camera, *ndc), wall_height_, is_wall)) continue;
            best = *ndc, best_score = score;
        }
    return best;
}

Controls DemoScript::controls(int frame, glm::vec2 player, const scene::PerspectiveCamera& camera, const IsWall& is_wall) {
    Controls c;
    const float t = float(frame) / float(std::max(frames_, 1));
    // Collecting: a mined wall's block lies on its tile (DroppedItem); the walk first goes to
    // it, until the block glides over (or two seconds pass), then back to the path.
    while (!pickups_.empty() && (frame - pickups_.front().second > 120 ||
                                 glm::distance(glm::vec2(pickups_.front().first) + 0.5f, player) < 1.0f))
        pickups_.pop_front();
    if (is_walking(frame) && !pickups_.empty()) {
        const glm::vec2 d = glm::vec2(pickups_.front().first) + 0.5f - player;
        if (glm::length(d) > 0.05f) {
            c.move = glm::normalize(d);
            last_facing_ = c.move;
        }
    }
    // Walking: out along the path, then back to the start.
    else if (is_walking(frame) && path_.size() > 1) {
        const bool out = t < 0.5f;
        const int last = int(path_.size()) - 1;
        if (out && progress_ < 1) progress_ = 1;
        glm::vec2 target = glm::vec2(path_[std::size_t(std::clamp(progress_, 0, last))]) + 0.5f;
        if (glm::distance(target, player) < 0.25f) {
            progress_ = std::clamp(progress_ + (out ? 1 : -1), 0, last);
            target = glm::vec2(path_[std::size_t(progress_)]) + 0.5f;
        }
        const glm::vec2 d = target - player;
        if (glm::length(d) > 0.05f) {
            c.move = glm::normalize(d);
            last_facing_ = c.move;
        }
    }
    // Actions, each on one frame (a click).
    auto mine = [&] {
        if (auto target = cursor_on_wall(player, camera, is_wall)) {
            c.has_cursor = true;
            c.cursor_ndc = target->first;
            c.mine = true;
            pickups_.push_back({target->second, frame});
        }
    };
    auto place = [&](bool Controls::*what) {
        if (auto ndc = cursor_on_ground(player, last_facing_, camera, is_wall)) {
            c.has_cursor = true;
            c.cursor_ndc = *ndc;
            c.*what = true;
        }
    };
    for (float m : {0.25f, 0.35f, 0.75f})
        for (int k = 0; k < 3; ++k)
            if (frame == int(float(frames_) * m) + k * 5) mine();
    if (at(frame, frames_, 0.04f) || at(frame, frames_, 0.2f) || at(frame, frames_, 0.65f)) place(&Controls::place_torch);
    if (at(frame, frames_, 0.40f)) place(&Controls::place_crystal);
    if (at(frame, frames_, 0.47f)) place(&Controls::place_lamp);
    if (at(frame, frames_, 0.52f)) place(&Controls::place_tree);
    if (at(frame, frames_, 0.85f)) place(&Controls::place_wall);
    if (at(frame, frames_, 0.55f)) c.toggle_day_cycle = true;
    if (!c.has_cursor) {
        c.has_cursor = true; // the cursor rests at the centre of the view
        c.cursor_ndc = {0.5f, 0.5f};
    }
    return c;
}

} // namespace lantern::game
