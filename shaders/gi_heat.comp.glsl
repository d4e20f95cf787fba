// One heat-transfer round on the heat grid: conduction-weighted neighbour diffusion over
// the taps gi_heat_mask allowed (adaptive hierarchical rings, see gi_heat_taps.glsl),
// stylised per-channel or physical weights, shadow-dependent blend, dark-area range boost,
// intensity multiplier, soft cap 2. The GLSL side of reference_indirect.cpp's heat_texel.
//
// size = (heat w, heat h, heat pitch, -);
// Parameters: HeatRoundParams.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
struct HeatRoundParams {
    float texels_per_unit;      // heat texels per world unit
    float distance;             // diffusion distance in heat texels
    float rate;                 // gi.diffusion_rate
    float range_boost;          // gi.range_boost
    float intensity_multiplier; // gi.intensity_multiplier
    int pad0, pad1, pad2;
};
#define GI_PASS_PARAMS HeatRoundParams
#include "lantern/gi_common.glsl"
#include "lantern/gi_heat_taps.glsl"

layout(constant_id = 6) const bool PER_CHANNEL = true;

layout(binding = 0) uniform usamplerBuffer u_mask;
layout(binding = 1) uniform samplerBuffer u_heat_in;
layout(std430, binding = 2) writeonly buffer Out { uvec2 texels[]; } o_heat;

const vec3 LUMA = vec3(0.299, 0.587, 0.114);

// FEATURES bit 0: three rings (24 taps; the distance exceeds 2.5 heat texels), else 8.
// The tap loop is unrolled with every tap's offset and weight uniform across the
// invocations, and a tap the mask refuses weighs 0 (its fetch stays in range): no per-lane
// loop over the mask's bits and no private arrays indexed per lane, which llvmpipe runs as
// scattered stack loads. Adding the refused taps' exact zeros leaves the sums unchanged.
const int HEAT_TAPS = (FEATURES & 1u) != 0u ? 24 : 8;

vec4 heat_texel(int i, int j, uint mask) {
    vec4 center = texelFetch(u_heat_in, texel_index(i, j));
    float rate = pc.pass.rate;
    float distance = pc.pass.distance;
    vec3 accum = vec3(0.0), wsum = vec3(0.0);
    [[unroll]] for (int t = 0; t < HEAT_TAPS; ++t) {
        ivec2 k = heat_tap_offset(t, distance);
        int ti = clamp(i + k.x, 0, pc.size.x - 1), tj = clamp(j + k.y, 0, pc.size.y - 1);
        float weight = ((mask >> uint(t)) & 1u) != 0u ? heat_tap_weight(t, distance) * rate : 0.0;
        vec3 n = texelFetch(u_heat_in, texel_index(ti, tj)).rgb;
        vec3 w = PER_CHANNEL ? weight * clamp(n + 0.1, 0.0, 1.0) : vec3(weight);
        accum += n * w;
        wsum += w;
    }
    accum /= max(wsum, vec3(1e-4));
    float in_shadow = 1.0 - center.a;
    float blend = mix(0.5, 0.8, in_shadow) * rate;
    vec3 next = mix(center.rgb, accum, blend);
    float darkness = 1.0 - clamp(dot(center.rgb, LUMA), 0.0, 1.0);
    next *= 1.0 + pc.pass.range_boost * darkness * in_shadow;
    next *= pc.pass.intensity_multiplier;
    float max_channel = max(next.r, max(next.g, next.b));
    if (max_channel > 2.0) next *= 2.0 / max_channel;
    return vec4(next, center.a);
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int j = o.y + int(r);
        if (j >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int i = o.x + k;
            vec4 value = vec4(0.0);
            if (i < pc.size.x) {
                uint mask = texelFetch(u_mask, texel_index(i, j)).r;
                // Bit 31 marks wall texels, which keep their value.
                value = (mask & 0x80000000u) != 0u ? texelFetch(u_heat_in, texel_index(i, j)) : heat_texel(i, j, mask);
            }
            o_heat.texels[texel_index(i, j)] = pack_rgba16f(value);
        }
    }
}
