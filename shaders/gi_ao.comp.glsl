// Ambient occlusion (r8): distance-weighted share of wall tiles within the AO radius.
// params0 = (radius, power, strength, dither on/off).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(std430, binding = 2) writeonly buffer Out { uint texels[]; } o_ao;

#include "lantern/gi_shadow.glsl"

const float BAYER4[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

float ao_texel(int x, int y) {
    float radius = max(pc.params0.x, 0.01);
    int range = int(ceil(radius));
    float power = max(pc.params0.y, 0.01);
    vec2 p = texel_center(x, y);
    ivec2 base = ivec2(floor(p));
    float occluded = 0.0, total = 0.0;
    for (int dy = -range; dy <= range; ++dy) {
        for (int dx = -range; dx <= range; ++dx) {
            vec2 center = vec2(float(base.x + dx) + 0.5, float(base.y + dy) + 0.5);
            vec2 d = p - center;
            float dist = sqrt(d.x * d.x + d.y * d.y);
            if (dist > radius) continue;
            float weight = pow(1.0 - saturate(dist / radius), power);
            total += weight;
            if (is_wall(base.x + dx, base.y + dy)) occluded += weight;
        }
    }
    float occlusion = total > 0.0 ? occluded / total : 0.0;
    float value = 1.0 - saturate(pc.params0.z) * occlusion;
    if (pc.params0.w > 0.5) value += ((BAYER4[(y & 3) * 4 + (x & 3)] + 0.5) / 16.0 - 0.5) / 255.0;
    return value;
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        vec4 v = vec4(0.0);
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            if (x < pc.size.x) v[k] = ao_texel(x, y);
        }
        o_ao.texels[texel_index(o.x, y) / 4] = pack_r8x4(v);
    }
}
