// A pass from outside the engine (docs/gi.md, "A new pass"): the indirect light times a
// colour, repeated with a colour per iteration (iteration 0 reads `indirect`, later ones
// the tinted texture itself, in place). Parameters: TintParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct TintParams {
    float r, g, b; // this iteration's colour
    int pad0, pad1, pad2, pad3, pad4;
};
#define GI_PASS_PARAMS TintParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_source;
layout(std430, binding = 1) buffer Out { uvec2 texels[]; } o_tinted;

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    const vec3 tint = vec3(pc.pass.r, pc.pass.g, pc.pass.b);
    for (uint row = 0; row < BLOCK_H; ++row) {
        int y = o.y + int(row);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int index = texel_index(o.x + k, y);
            vec4 v = texelFetch(u_source, index);
            o_tinted.texels[index] = pack_rgba16f(vec4(v.rgb * tint, v.a));
        }
    }
}
