// Tiled light culling for the direct pass. A bin is the footprint of one direct-pass
// workgroup (4 * group_x by BLOCK_H * group_y texels); bit i of a bin's mask is set when
// light i (point lights, then emissives) can reach a texel centre in the bin. The direct
// pass then visits only those lights, in ascending order (the reference's order).
// One invocation per bin. size = texture (w, h, -, res); parameters: LightBinParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct LightBinParams {
    int bins_x, bins_y; // bins (direct-pass workgroups) in x and y
    int words;          // 32-bit mask words per bin
    int bin_w, bin_h;   // a bin's size in texels
    int pad0, pad1, pad2;
};
#define GI_PASS_PARAMS LightBinParams
#include "lantern/gi_common.glsl"

layout(constant_id = 4) const int MAX_LIGHTS = 2048;

layout(std140, binding = 0) uniform LightBlock { GpuPointLight lights[MAX_LIGHTS]; } u_lights;
layout(std430, binding = 1) writeonly buffer Out { uint masks[]; } o_bins;

void main() {
    ivec2 bin = ivec2(gl_GlobalInvocationID.xy);
    ivec2 bins = ivec2(pc.pass.bins_x, pc.pass.bins_y);
    if (bin.x >= bins.x || bin.y >= bins.y) return;
    int words = pc.pass.words;
    ivec2 bin_size = ivec2(pc.pass.bin_w, pc.pass.bin_h);
    ivec2 first = bin * bin_size;
    ivec2 last = min(first + bin_size, pc.size.xy) - 1;
    vec2 lo = texel_center(first.x, first.y), hi = texel_center(max(last.x, first.x), max(last.y, first.y));
    int n = pc.counts.x + pc.counts.y;
    int base = (bin.y * bins.x + bin.x) * words;
    for (int w = 0; w < words; ++w) {
        uint bits = 0u;
        for (int b = 0; b < 32; ++b) {
            int i = w * 32 + b;
            if (i >= n) break;
            vec4 l = u_lights.lights[i].position_radius;
            vec2 d = max(max(lo - l.xy, l.xy - hi), vec2(0.0));
            // Conservative: the direct pass still tests each texel's exact distance.
            if (sqrt(d.x * d.x + d.y * d.y) <= l.z * 1.0001 + 1e-4) bits |= 1u << uint(b);
        }
        o_bins.masks[base + w] = bits;
    }
}
