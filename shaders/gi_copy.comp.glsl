// Baseline for the benchmarks: copies an rgba16f texture (texel-buffer read, one 64-bit
// word written per texel), the same access pattern and bytes as a GI pass's output.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_src;
layout(std430, binding = 1) writeonly buffer Out { uvec2 texels[]; } o_dst;

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int index = texel_index(o.x + k, y);
            o_dst.texels[index] = pack_rgba16f(texelFetch(u_src, index));
        }
    }
}
