// Indirect light at full resolution from the heat grid: a copy at scale 1, else bilinear
// over the conductive heat texels around the texel centre (nearest when none conducts).
// FEATURES bit 0 (the heat grid's): which grid texels are walls comes from the heat row's
// tap masks (bit 31: the tile under the texel centre is a wall, the same test), one fetch
// instead of a wall lookup per tap; else from the wall grid.
// size = full (w, h, pitch, res); parameters: UpsampleParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct UpsampleParams {
    int heat_width, heat_height, heat_pitch;
    float texels_per_unit; // heat texels per world unit
    int scale;             // 1: a copy; 2 or 4: bilinear upsampling
    int pad0, pad1, pad2;
};
#define GI_PASS_PARAMS UpsampleParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(binding = 2) uniform samplerBuffer u_heat;
layout(std430, binding = 3) writeonly buffer Out { uvec2 texels[]; } o_indirect;
layout(binding = 4) uniform usamplerBuffer u_grid_mask; // FEATURES bit 0

#include "lantern/gi_shadow.glsl"

const bool GRID_MASK = (FEATURES & 1u) != 0u;

bool grid_wall(int hi, int hj) {
    if (GRID_MASK) return (texelFetch(u_grid_mask, hj * pc.pass.heat_pitch + hi).r & 0x80000000u) != 0u;
    return is_wall(ivec2(floor(grid_texel_center(hi, hj, pc.pass.texels_per_unit))));
}

vec3 heat_at(int i, int j) { return texelFetch(u_heat, j * pc.pass.heat_pitch + i).rgb; }

vec3 upsample(int x, int y) {
    int hw = pc.pass.heat_width, hh = pc.pass.heat_height;
    if (pc.pass.scale == 1) return heat_at(x, y);
    float tpu = pc.pass.texels_per_unit;
    vec2 origin = pc.camera_view.xy;
    vec2 u = (texel_center(x, y) - origin) * tpu - 0.5;
    ivec2 i0 = ivec2(floor(u));
    vec2 f = u - vec2(i0);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
            int hi = clamp(i0.x + dx, 0, hw - 1), hj = clamp(i0.y + dy, 0, hh - 1);
            if (grid_wall(hi, hj)) continue;
            float wt = (dx == 1 ? f.x : 1.0 - f.x) * (dy == 1 ? f.y : 1.0 - f.y);
            sum += heat_at(hi, hj) * wt;
            wsum += wt;
        }
    if (wsum > 0.0) return sum / wsum;
    int ni = clamp(int(floor(u.x + 0.5)), 0, hw - 1), nj = clamp(int(floor(u.y + 0.5)), 0, hh - 1);
    return heat_at(ni, nj);
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            vec4 value = x < pc.size.x ? vec4(upsample(x, y), 1.0) : vec4(0.0);
            o_indirect.texels[texel_index(x, y)] = pack_rgba16f(value);
        }
    }
}
