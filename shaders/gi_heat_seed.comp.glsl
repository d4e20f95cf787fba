// Heat seed on the heat grid (window / scale): box average of the emission (rgb) and of
// the direct visibility max(R, G) (alpha, carried through the rounds untouched).
// params1 = (full width, full height, full pitch, scale).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_emission;
layout(binding = 1) uniform samplerBuffer u_shadow;
layout(std430, binding = 2) writeonly buffer Out { uvec2 texels[]; } o_heat;

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    int full_w = int(pc.params1.x), full_h = int(pc.params1.y), full_pitch = int(pc.params1.z);
    int scale = int(pc.params1.w);
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
