// GPU mirrors of engine/gi/include/lantern/gi/frame_inputs.hpp (vec4 members only, so
// std140 and std430 agree with the C++ layout).
#ifndef LANTERN_GI_TYPES_GLSL
#define LANTERN_GI_TYPES_GLSL

struct GpuPointLight {
    vec4 position_radius; // xy: world x, z; z: radius
    vec4 color;           // rgb: colour * intensity
};

struct GpuDirectionalLight {
    vec4 direction_base;   // xyz: normalised travel direction; w: base shadow distance
    vec4 color_multiplier; // rgb: colour * intensity; w: 1 / max(|dir.y|, 0.02)
    vec4 bounce;           // x: bounce intensity
};

struct GpuShadowProxy {
    vec4 position_size; // xy: position; zw: half extents (box) / radius in z (circle)
    vec4 lengths;       // max length, end-cap blend, penumbra width, penumbra length
    vec4 modes;         // penumbra power, shape (0 box, 1 circle), width mode, penumbra mode
};

#endif
