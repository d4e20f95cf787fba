// Baked light at run time (baked_light.hpp).
#include "lantern/gi/baked_light.hpp"

#include "lantern/core/assert.hpp"

namespace lantern::gi {

glm::vec3 BakedLight::sample(int layer, glm::vec2 p) const {
    const glm::vec2 g = grid(p);
    if (!(g.x >= 0.0f && g.y >= 0.0f && g.x < float(width) && g.y < float(height))) return glm::vec3(0.0f);
    return sample_bricks(bricks, g.x, g.y, layer);
}

int BakedLight::level(int layer, glm::vec2 p) const {
    const glm::vec2 g = grid(p);
    if (!(g.x >= 0.0f && g.y >= 0.0f && g.x < float(width) && g.y < float(height))) return -1;
    return brick_level(bricks, g.x, g.y, layer);
}

BakedLight make_baked_light(glm::ivec2 origin, int resolution, std::span<const Field> layers, float eps,
                            std::uint64_t key, int max_level, std::span<const std::uint8_t> finest_level) {
    BakedLight out;
    out.origin = origin;
    out.resolution = resolution;
    out.width = layers[0].width;
    out.height = layers[0].height;
    LANTERN_ASSERT(layers.size() == std::size_t(baked_layers) || layers.size() == std::size_t(2 * baked_layers),
                   "make_baked_light: five layers, or ten with the pulsing part");
    out.pulsing = layers.size() == std::size_t(2 * baked_layers);
    out.bricks = build_bricks(layers, eps, baked_bricks_per_row, max_level, finest_level);
    out.key = key;
    return out;
}

} // namespace lantern::gi
