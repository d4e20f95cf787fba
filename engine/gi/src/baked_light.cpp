// Baked light at run time (baked_light.hpp).
#include "lantern/gi/baked_light.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/scene/day.hpp"

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
                            std::uint64_t key, int max_level, std::span<const std::uint8_t> finest_level, int sun_keys) {
    BakedLight out;
    out.origin = origin;
    out.resolution = resolution;
    out.width = layers[0].width;
    out.height = layers[0].height;
    const std::size_t parts = layers.size() / std::size_t(baked_layers) - std::size_t(sun_keys);
    LANTERN_ASSERT(sun_keys >= 0 && layers.size() % std::size_t(baked_layers) == 0 && (parts == 1 || parts == 2),
                   "make_baked_light: five layers a part: the steady part, the pulsing one if any, each sun key's");
    out.pulsing = parts == 2;
    out.sun_keys = sun_keys;
    out.bricks = build_bricks(layers, eps, baked_bricks_per_row, max_level, finest_level);
    out.key = key;
    return out;
}

BakedSun baked_sun_of(const FrameInputs& in) {
    if (!in.baked || in.baked->sun_keys < 2) return {};
    for (const GpuDirectionalLight& sun : in.directional_lights)
        if (is_mixed_sun(sun)) {
            const scene::SunKeyBlend b = scene::sun_key_blend(glm::vec3(sun.direction_base), in.baked->sun_keys);
            return {b.key, b.blend, glm::vec3(sun.color_multiplier)};
        }
    return {};
}

} // namespace lantern::gi
