// C++ mirror of the push-constant block of every GI shader (shaders/include/lantern/
// gi_common.glsl): the fields all passes share, and the pass's own parameters, a struct of
// eight 4-byte scalars named in the shader with GI_PASS_PARAMS. Each pass's C++ struct
// lives beside its row (src/rows/*.cpp); when a pipeline is created the shader's reflected
// block is checked against GiPush<P>: its size, and each parameter's offset and scalar type
// (float, int, uint) in order (PassRecorder::pipeline<P>).
#pragma once

#include "lantern/gpu/reflect.hpp"

#include <glm/vec4.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace lantern::gi::vk {

template <typename P>
struct alignas(16) GiPush {
    glm::vec4 camera_view; // min_x, min_z, width, height (world units)
    glm::ivec4 size;       // texture width, height, pitch (texels), resolution (texels per unit)
    glm::ivec4 grid;       // wall grid width, height, origin x, origin z (world tile of cell row/col 0)
    glm::ivec4 counts;     // point lights, emissives, directional lights, proxies
    P pass{};              // the pass's own parameters
    glm::ivec4 grid_phase; // toroidal phase of the wall grid (x, z), 0, 0
};

// For passes without parameters of their own (GiNoParams in the shaders).
struct NoParams {
    std::int32_t unused0 = 0, unused1 = 0, unused2 = 0, unused3 = 0, unused4 = 0, unused5 = 0, unused6 = 0,
                 unused7 = 0;
};
using GiPassParams = GiPush<NoParams>;

inline constexpr std::uint32_t pass_params_offset = 64; // where `pass` starts in the block
static_assert(sizeof(GiPassParams) == 112, "GiPush must match the GLSL push-constant block");

template <typename T>
constexpr gpu::ScalarKind scalar_kind() {
    if constexpr (std::is_same_v<T, float>) return gpu::ScalarKind::f32;
    else if constexpr (std::is_same_v<T, std::int32_t>) return gpu::ScalarKind::i32;
    else if constexpr (std::is_same_v<T, std::uint32_t>) return gpu::ScalarKind::u32;
    else return gpu::ScalarKind::other;
}

// The scalar type of each of P's eight fields, in declaration order (a struct with another
// number of fields does not compile here).
template <typename P>
constexpr std::array<gpu::ScalarKind, 8> field_kinds() {
    static_assert(sizeof(P) == 32 && std::is_aggregate_v<P>, "pass parameters: eight 4-byte fields");
    P p{};
    auto& [a, b, c, d, e, f, g, h] = p;
    return {scalar_kind<std::remove_cvref_t<decltype(a)>>(), scalar_kind<std::remove_cvref_t<decltype(b)>>(),
            scalar_kind<std::remove_cvref_t<decltype(c)>>(), scalar_kind<std::remove_cvref_t<decltype(d)>>(),
            scalar_kind<std::remove_cvref_t<decltype(e)>>(), scalar_kind<std::remove_cvref_t<decltype(f)>>(),
            scalar_kind<std::remove_cvref_t<decltype(g)>>(), scalar_kind<std::remove_cvref_t<decltype(h)>>()};
}

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
    spec_features = 8, // a pass's own compile-time switches (FEATURES in gi_common.glsl)
    spec_faces = 9,    // computed_faces (FACES)
    spec_exact_rounding = 10, // gi_exact.glsl EXACT_ROUNDING: 0 the driver's own, 1 Dekker, 2 fused fma
    spec_linear_penumbra = 11, // gi_common.glsl LINEAR_PENUMBRA: every proxy's penumbra power is 1
    spec_proxy_registers = 12, // gi_common.glsl PROXY_REGISTERS: the proxy loops keep their masks in registers
};

// The most shadow proxies whose masks the proxy loops keep in registers (PROXY_REGISTERS),
// and the most point lights in the frame for which they do: measured on lavapipe the
// registers take 9-17 % off the direct pass at 64 and 256 point lights and add 9 % at 1024
// (seed-table rows 7, 10, 11; docs/performance.md, "Proxy lists in registers").
inline constexpr std::size_t proxy_register_count = 64;
inline constexpr std::size_t proxy_register_lights = 256;

inline constexpr int max_gpu_lights = 2048;   // point lights + emissives: one 64 KiB UBO
inline constexpr int max_gpu_proxies = 256;
inline constexpr int max_gpu_suns = 8;

} // namespace lantern::gi::vk
