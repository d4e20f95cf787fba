// Emission extraction (rgba16f): 1 - exp(-2 * maxChannel) roll-off, emission strength,
// saturation boost 1.2 around Rec.601 luma, negative channels clamped.
// Parameters: EmissionParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct EmissionParams {
    float strength; // gi.emission_strength
    int pad0, pad1, pad2, pad3, pad4, pad5, pad6;
};
#define GI_PASS_PARAMS EmissionParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_direct;
layout(std430, binding = 1) writeonly buffer Out { uvec2 texels[]; } o_emission;

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    const vec3 luma = vec3(0.299, 0.587, 0.114);
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int index = texel_index(o.x + k, y);
            vec4 d = texelFetch(u_direct, index);
            float max_channel = max(d.r, max(d.g, d.b));
            float curve = 1.0 - exp(-max_channel * 2.0);
            float scale = pc.pass.strength * curve / (max_channel + 0.001);
            vec4 e = d * scale;
            float lum = dot(e.rgb, luma);
            vec3 boosted = max(vec3(lum) + (e.rgb - lum) * 1.2, vec3(0.0));
            o_emission.texels[index] = pack_rgba16f(vec4(boosted, e.a));
        }
    }
}
