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
    vec4 bounce;           // x: bounce intensity; y: 1 for a mixed sun (frame_inputs.hpp is_mixed_sun)
};

struct GpuShadowProxy {
    vec4 position_size; // xy: position; zw: half extents (box) / radius in z (circle)
    vec4 lengths;       // max length, end-cap blend, penumbra width, penumbra length
    vec4 modes;         // penumbra power, shape (0 box, 1 circle), width mode, penumbra mode
    vec4 fade;          // x: strength in [0, 1] multiplying the occlusion (frame_inputs.hpp)
};

// Beyond this distance from its position proxy p occludes nothing (reference_shadow.cpp
// proxy_reach): its shadow is at most max_length + penumbra_length long and its width plus
// penumbra_width wide.
float proxy_reach(GpuShadowProxy p) {
    float along = max(p.lengths.x + p.lengths.w, 0.0);
    float across = abs(p.position_size.z) + abs(p.position_size.w) + max(p.lengths.z, 0.0);
    return sqrt(along * along + across * across) * 1.0001 + 1e-3;
}

#endif
