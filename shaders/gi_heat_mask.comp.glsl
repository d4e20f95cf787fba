// Which heat taps each heat texel may use, once per frame (walls and window fixed): bit t
// set when tap t lands on an air texel and, if it skips over a texel and the segment check
// is on, the straight segment to it crosses no wall; bit 31 set on wall texels (they keep
// their value). The rounds then never touch the wall grid.
// camera_view.xy = heat grid origin; size = heat (w, h, pitch, -);
// Parameters: HeatMaskParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct HeatMaskParams {
    float texels_per_unit; // heat texels per world unit
    float distance;        // diffusion distance in heat texels
    float segment_radius;  // the segment check's DDA radius (world units)
    int pad0, pad1, pad2, pad3, pad4;
};
#define GI_PASS_PARAMS HeatMaskParams
#include "lantern/gi_common.glsl"

layout(constant_id = 7) const bool SEGMENT_CHECK = true;

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(std430, binding = 2) writeonly buffer Out { uint masks[]; } o_mask;

#include "lantern/gi_shadow.glsl"
#include "lantern/gi_heat_taps.glsl"

vec2 heat_center(int i, int j) { return grid_texel_center(i, j, pc.pass.texels_per_unit); }

uint tap_mask(int i, int j) {
    vec2 center = heat_center(i, j);
    if (is_wall(ivec2(floor(center)))) return 0x80000000u; // wall: keeps its heat
    float distance = pc.pass.distance;
    uint mask = 0u;
    for (int t = 0; t < heat_tap_count(distance); ++t) {
        ivec2 k = heat_tap_offset(t, distance);
        int ti = clamp(i + k.x, 0, pc.size.x - 1), tj = clamp(j + k.y, 0, pc.size.y - 1);
        vec2 tap = heat_center(ti, tj);
        if (is_wall(ivec2(floor(tap)))) continue;
        if (SEGMENT_CHECK && heat_tap_skips(k) && shadow_dda(center, tap, pc.pass.segment_radius) == 0.0) continue;
        mask |= 1u << uint(t);
    }
    return mask;
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int j = o.y + int(r);
        if (j >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int i = o.x + k;
            o_mask.masks[texel_index(i, j)] = i < pc.size.x ? tap_mask(i, j) : 0u;
        }
    }
}
