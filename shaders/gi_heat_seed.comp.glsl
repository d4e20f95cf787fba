// Heat seed on the heat grid (window / scale): box average of the emission (rgb) and of
// the direct visibility max(R, G) (alpha, carried through the rounds untouched).
// Parameters: HeatSeedParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct HeatSeedParams {
    int full_width, full_height, full_pitch; // the window-sized emission and shadow textures
    int scale;                               // 1, 2 or 4 window texels per heat texel
    int pad0, pad1, pad2, pad3;
};
#define GI_PASS_PARAMS HeatSeedParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_emission;
layout(binding = 1) uniform samplerBuffer u_shadow;
layout(std430, binding = 2) writeonly buffer Out { uvec2 texels[]; } o_heat;

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    int full_w = pc.pass.full_width, full_h = pc.pass.full_height, full_pitch = pc.pass.full_pitch;
    int scale = pc.pass.scale;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int j = o.y + int(r);
        if (j >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int i = o.x + k;
            vec3 sum = vec3(0.0);
            float visibility = 0.0;
            int n = 0;
            for (int y = j * scale; y < min((j + 1) * scale, full_h); ++y)
                for (int x = i * scale; x < min((i + 1) * scale, full_w); ++x) {
                    int index = y * full_pitch + x;
                    sum += texelFetch(u_emission, index).rgb;
                    vec2 s = texelFetch(u_shadow, index).rg;
                    visibility += max(s.r, s.g);
                    ++n;
                }
            vec4 value = n > 0 ? vec4(sum / float(n), visibility / float(n)) : vec4(0.0);
            o_heat.texels[texel_index(i, j)] = pack_rgba16f(value);
        }
    }
}
