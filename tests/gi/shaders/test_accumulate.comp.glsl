// A converging pass from outside the engine: the emission accumulated over `frames` frames
// (history 0 starts afresh), a stand-in for temporal accumulation and bounce feedback.
// Parameters: AccumulateParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct AccumulateParams {
    float weight; // 1 / frames
    int history;  // frames accumulated before this one
    int pad0, pad1, pad2, pad3, pad4, pad5;
};
#define GI_PASS_PARAMS AccumulateParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_emission;
layout(binding = 1) uniform samplerBuffer u_previous;
layout(std430, binding = 2) buffer Out { uvec2 texels[]; } o_accumulated;

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint row = 0; row < BLOCK_H; ++row) {
        int y = o.y + int(row);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int index = texel_index(o.x + k, y);
            vec4 previous = pc.pass.history == 0 ? vec4(0.0) : texelFetch(u_previous, index);
            vec4 add = texelFetch(u_emission, index) * pc.pass.weight;
            o_accumulated.texels[index] = pack_rgba16f(previous + add);
        }
    }
}
