// One direction of the edge-aware blur: 5 taps, Gaussian sigma 1, only texels of the
// centre's conduction class, renormalised (brightness preserving). The class comes from the
// conduction texture (1 in air, 0 in walls: the tile under the texel centre), one byte per
// tap instead of a wall lookup. Parameters: BlurParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct BlurParams {
    int axis_x, axis_y; // (1, 0) horizontal, (0, 1) vertical
    int pad0, pad1, pad2, pad3, pad4, pad5;
};
#define GI_PASS_PARAMS BlurParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_conduction;
layout(binding = 1) uniform samplerBuffer u_src;
layout(std430, binding = 2) writeonly buffer Out { uvec2 texels[]; } o_dst;

const float KERNEL[5] = float[5](0.13533528, 0.60653066, 1.0, 0.60653066, 0.13533528);

bool air_texel(int x, int y) { return texelFetch(u_conduction, texel_index(x, y)).r > 0.5; }

vec4 blur(int x, int y) {
    ivec2 axis = ivec2(pc.pass.axis_x, pc.pass.axis_y);
    bool center_air = air_texel(x, y);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int k = -2; k <= 2; ++k) {
        int sx = x + axis.x * k, sy = y + axis.y * k;
        if (sx < 0 || sy < 0 || sx >= pc.size.x || sy >= pc.size.y) continue;
        if (air_texel(sx, sy) != center_air) continue;
        sum += texelFetch(u_src, texel_index(sx, sy)).rgb * KERNEL[k + 2];
        wsum += KERNEL[k + 2];
    }
    return vec4(sum / wsum, texelFetch(u_src, texel_index(x, y)).a);
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            o_dst.texels[texel_index(x, y)] = pack_rgba16f(x < pc.size.x ? blur(x, y) : vec4(0.0));
        }
    }
}
