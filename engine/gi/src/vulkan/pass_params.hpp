// C++ mirror of the GiPassParams push-constant block in shaders/include/lantern/gi_common.glsl.
#pragma once

#include <glm/vec4.hpp>

namespace lantern::gi::vk {

struct alignas(16) GiPassParams {
    glm::vec4 camera_view; // min_x, min_z, width, height (world units)
    glm::ivec4 size;       // texture width, height, pitch (texels), resolution (texels per unit)
    glm::ivec4 grid;       // wall grid width, height, origin x, origin z (world tile of cell row/col 0)
    glm::ivec4 counts;     // point lights, emissives, directional lights, proxies
    glm::vec4 params0;     // pass-specific
    glm::vec4 params1;     // pass-specific
    glm::ivec4 grid_phase; // toroidal phase of the wall grid (x, z), 0, 0
};
static_assert(sizeof(GiPassParams) == 112, "GiPassParams must match the GLSL push-constant block");

// Specialisation constant ids shared by the GI shaders.
enum SpecId : unsigned {
    spec_block_h = 0,
    spec_group_x = 1,
    spec_group_y = 2,
    spec_has_proxies = 3,
    spec_max_lights = 4,
    spec_has_walls = 5,
    spec_per_channel = 6,
    spec_segment_check = 7,
};

inline constexpr int max_gpu_lights = 2048;   // point lights + emissives: one 64 KiB UBO
inline constexpr int max_gpu_proxies = 256;
inline constexpr int max_gpu_suns = 8;

} // namespace lantern::gi::vk
