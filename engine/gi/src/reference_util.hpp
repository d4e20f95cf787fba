// Helpers the reference passes share (src only): rows in parallel on the reference's job
// system, four-channel loads and quantised stores, and air at a point.
#pragma once

#include "lantern/gi/reference.hpp"
#include "lantern/jobs/job_system.hpp"

#include <cmath>
#include <cstdint>

namespace lantern::gi::ref_util {

// Calls row(y) for every y in [0, height), on options.jobs when set.
template <typename F>
void for_each_row(int height, const RefOptions& options, F&& row) {
    if (options.jobs) {
        options.jobs->parallel_for("gi.reference", 0, std::uint32_t(height), 8,
                                   [&](std::uint32_t b, std::uint32_t e, std::uint32_t) {
                                       for (std::uint32_t y = b; y < e; ++y) row(int(y));
                                   });
    } else {
        for (int y = 0; y < height; ++y) row(y);
    }
}

inline glm::vec4 load4(const Texture& t, int x, int y) {
    const float* v = t.at(x, y);
    return {v[0], v[1], v[2], v[3]};
}
inline void store4(Texture& t, int x, int y, glm::vec4 v) {
    const float values[4] = {v.x, v.y, v.z, v.w};
    t.store(x, y, values);
}

inline bool air_at(const WallView& walls, glm::vec2 p) {
    return !walls.is_wall(int(std::floor(p.x)), int(std::floor(p.y)));
}

} // namespace lantern::gi::ref_util
