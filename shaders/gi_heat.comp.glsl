// One heat-transfer round on the heat grid: conduction-weighted 8-neighbour diffusion with
// adaptive hierarchical taps (near 1.5 texels 30 %, mid half distance 30 %, far full
// distance 40 % when the distance exceeds 2.5 texels), stylised per-channel or physical
// weights, shadow-dependent blend, dark-area range boost, intensity multiplier, soft cap 2.
// The GLSL side of reference_indirect.cpp's heat_texel.
//
// camera_view.xy = heat grid origin; size = (heat w, heat h, heat pitch, -);
// params0 = (heat texels per world unit, diffusion distance in heat texels, rate, range boost);
// params1 = (intensity multiplier, segment radius, -, -).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "lantern/gi_common.glsl"

layout(constant_id = 6) const bool PER_CHANNEL = true;
layout(constant_id = 7) const bool SEGMENT_CHECK = true;

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(binding = 2) uniform samplerBuffer u_heat_in;
layout(std430, binding = 3) writeonly buffer Out { uvec2 texels[]; } o_heat;

#include "lantern/gi_shadow.glsl"

const vec2 DIRECTIONS[8] = vec2[8](vec2(-1, -1), vec2(0, -1), vec2(1, -1), vec2(-1, 0), vec2(1, 0), vec2(-1, 1),
                                   vec2(0, 1), vec2(1, 1));
const float DIRECTION_WEIGHTS[8] = float[8](0.70710678, 1.0, 0.70710678, 1.0, 1.0, 0.70710678, 1.0, 0.70710678);
const vec3 LUMA = vec3(0.299, 0.587, 0.114);

vec2 heat_center(int i, int j) {
    float tpu = pc.params0.x;
    return vec2(pc.camera_view.x + (float(i) + 0.5) / tpu, pc.camera_view.y + (float(j) + 0.5) / tpu);
}
bool air_at(vec2 p) { return !is_wall(ivec2(floor(p))); }

void add_ring(int i, int j, vec2 center_pos, float distance, float share, inout vec3 accum, inout vec3 wsum) {
    float rate = pc.params0.z;
    for (int d = 0; d < 8; ++d) {
        vec2 offset = DIRECTIONS[d] * distance;
        int ti = clamp(int(floor(float(i) + 0.5 + offset.x)), 0, pc.size.x - 1);
        int tj = clamp(int(floor(float(j) + 0.5 + offset.y)), 0, pc.size.y - 1);
        vec2 tap_pos = heat_center(ti, tj);
        if (!air_at(tap_pos)) continue;
        vec2 k = floor(offset + 0.5);
        bool skips = abs(k.x) > 1.0 || abs(k.y) > 1.0;
        if (SEGMENT_CHECK && skips && shadow_dda(center_pos, tap_pos, pc.params1.y) == 0.0) continue;
        float weight = DIRECTION_WEIGHTS[d] * share * rate;
        vec3 n = texelFetch(u_heat_in, tj * pc.size.z + ti).rgb;
        vec3 w = PER_CHANNEL ? weight * clamp(n + 0.1, 0.0, 1.0) : vec3(weight);
        accum += n * w;
        wsum += w;
    }
}

vec4 heat_texel(int i, int j) {
    vec4 center = texelFetch(u_heat_in, j * pc.size.z + i);
    vec2 center_pos = heat_center(i, j);
    if (!air_at(center_pos)) return center;
    float in_shadow = 1.0 - center.a;
    float d = pc.params0.y;
    vec3 accum = vec3(0.0), wsum = vec3(0.0);
    if (d > 2.5) {
        add_ring(i, j, center_pos, 1.5, 0.3, accum, wsum);
        add_ring(i, j, center_pos, d * 0.5, 0.3, accum, wsum);
        add_ring(i, j, center_pos, d, 0.4, accum, wsum);
    } else {
        add_ring(i, j, center_pos, d, 1.0, accum, wsum);
    }
    accum /= max(wsum, vec3(1e-4));
    float blend = mix(0.5, 0.8, in_shadow) * pc.params0.z;
    vec3 next = mix(center.rgb, accum, blend);
    float darkness = 1.0 - saturate(dot(center.rgb, LUMA));
    next *= 1.0 + pc.params0.w * darkness * in_shadow;
    next *= pc.params1.x;
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
            vec4 value = i < pc.size.x ? heat_texel(i, j) : vec4(0.0);
            o_heat.texels[texel_index(i, j)] = pack_rgba16f(value);
        }
    }
}
