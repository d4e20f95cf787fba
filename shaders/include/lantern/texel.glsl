// Per-texel lighting of models (seed 001): the GLSL twin of engine/texel/src/reference.cpp,
// operation for operation. Every step is `precise` (no fused multiply-adds) and divisions
// and roots go through gi_exact.glsl, so inside tests, cell steps and occluder hits decide
// as the reference does. Structs: engine/texel/include/lantern/texel/texel.hpp.
#ifndef LANTERN_TEXEL_GLSL
#define LANTERN_TEXEL_GLSL

#include "gi_exact.glsl"

struct TexelTriangle {
    vec4 p1, p2, p3;
    vec4 uv12; // xy uv of p1, zw uv of p2
    vec4 uv3;  // xy uv of p3, z its placement, w 1 when it moves (texel::Placement::moves)
    vec4 normal, tangent, binormal;
};
struct TexelPlacement {
    uvec4 ranges; // first triangle, triangle count, first texel, texture size
    vec4 bounds;  // sphere: xyz centre, w radius
};
struct TexelSurface {
    vec4 position_used;
    vec4 normal_triangle;
    vec4 geo_normal;
};
struct TexelLight {
    vec4 position_range;
    vec4 color_type; // rgb colour x intensity, w shadow type (0 none, 1 hard, 2 blurred)
    vec4 blur;       // x multiplier, y power
    vec4 ambient;
};

// texel_passes.cpp TexelPush.
layout(push_constant) uniform TexelPush {
    ivec4 walls;  // the wall patch: origin x, z, width, height
    vec4 params;  // x wall height
    uvec4 counts; // x texels, y placements, z lights, w mode (light pass: 0 bake, 1 realtime)
    uvec4 span;   // uv_to_world: x first texel, y texels
} pc;

const float TEXEL_INSIDE_EPS = 1e-3;

float texel_dot(vec3 a, vec3 b) {
    precise float d = a.x * b.x + a.y * b.y + a.z * b.z;
    return d;
}
float texel_length(vec3 v) {
    precise float squared = v.x * v.x + v.y * v.y + v.z * v.z;
    return gi_sqrt(squared);
}
vec3 texel_div(vec3 v, float d) { return vec3(gi_div(v.x, d), gi_div(v.y, d), gi_div(v.z, d)); }

bool texel_inside(float v, float w) {
    precise float s = v + w;
    return -TEXEL_INSIDE_EPS <= v && -TEXEL_INSIDE_EPS <= w && s <= 1.0 + TEXEL_INSIDE_EPS;
}

#endif
