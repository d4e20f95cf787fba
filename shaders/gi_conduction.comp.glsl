// Conduction mask (r8): 1 where light may exist (air), 0 in wall tiles.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(std430, binding = 2) writeonly buffer Out { uint texels[]; } o_conduction;

#include "lantern/gi_shadow.glsl"

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        vec4 v = vec4(0.0);
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            if (x >= pc.size.x) break;
            vec2 p = texel_center(x, y);
            v[k] = is_wall(ivec2(floor(p))) ? 0.0 : 1.0;
        }
        o_conduction.texels[texel_index(o.x, y) / 4] = pack_r8x4(v);
    }
}
