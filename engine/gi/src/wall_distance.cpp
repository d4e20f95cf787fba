// WallDistance (wall_distance.hpp): the distance field's reference passes, queried by position.
#include "lantern/gi/wall_distance.hpp"

#include <cmath>
#include <limits>

namespace lantern::gi {

WallDistance WallDistance::build(const FrameInputs& in, const RefOptions& options) {
    WallDistance d;
    d.grid_ = radiosity_grid(in);
    Texture jfa = reference_jump_flood_seed(in);
    for (int offset : jump_flood_offsets({d.grid_.width, d.grid_.height}))
        jfa = reference_jump_flood_pass(jfa, offset, options);
    d.field_ = reference_distance_field(jfa, options).field;
    return d;
}

bool WallDistance::texel_of(glm::vec2 p, int& i, int& j) const {
    if (empty()) return false;
    const glm::vec2 u = (p - grid_.origin) * grid_.texels_per_unit;
    if (!(u.x >= 0.0f && u.y >= 0.0f)) return false; // also NaN
    i = int(std::floor(u.x));
    j = int(std::floor(u.y));
    return i < field_.width && j < field_.height;
}

bool WallDistance::covers(glm::vec2 p) const {
    int i = 0, j = 0;
    return texel_of(p, i, j);
}

float WallDistance::distance(glm::vec2 p) const {
    int i = 0, j = 0;
    if (!texel_of(p, i, j)) return std::numeric_limits<float>::infinity();
    const float texels = field_.at(i, j)[0];
    if (texels >= max_half) return std::numeric_limits<float>::infinity();
    return texels / grid_.texels_per_unit;
}

glm::vec2 WallDistance::direction(glm::vec2 p) const {
    int i = 0, j = 0;
    if (!texel_of(p, i, j)) return {0.0f, 0.0f};
    const float* v = field_.at(i, j);
    return {v[1], v[2]};
}

} // namespace lantern::gi
