// The fog pass: open ground's indirect light blended towards a fog colour, the more the
// farther the texel is from the window's centre (walls stay zero). Parameters: FogParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct FogParams {
    float r, g, b;   // the fog's colour
    float density;   // the blend at the window's edge
    int pad0, pad1, pad2, pad3;
};
#define GI_PASS_PARAMS FogParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(binding = 2) uniform samplerBuffer u_indirect;
layout(std430, binding = 3) writeonly buffer Out { uvec2 texels[]; } o_fogged;

#include "lantern/gi_shadow.glsl"

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    const vec3 fog = vec3(pc.pass.r, pc.pass.g, pc.pass.b);
    const vec2 centre = pc.camera_view.xy + 0.5 * pc.camera_view.zw;
    for (uint row = 0; row < BLOCK_H; ++row) {
        int y = o.y + int(row);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            int index = texel_index(x, y);
            vec2 p = texel_center(x, y);
            vec4 v = texelFetch(u_indirect, index);
            // Distance from the centre over half the window's diagonal: 0 at the centre.
            precise vec2 d = (p - centre) / (0.5 * pc.camera_view.zw);
            precise float t = clamp(sqrt(d.x * d.x + d.y * d.y) * 0.70710678, 0.0, 1.0) * pc.pass.density;
            vec3 c = is_wall(ivec2(floor(p))) ? vec3(0.0) : mix(v.rgb, fog, t);
            o_fogged.texels[index] = pack_rgba16f(vec4(c, 1.0));
        }
    }
}
