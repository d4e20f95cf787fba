// Tiled light culling for the direct pass. A bin is the footprint of one direct-pass
// workgroup (4 * group_x by BLOCK_H * group_y texels); bit i of a bin's mask is set when
// light i (point lights, then emissives) can reach a texel centre in the bin. The direct
// pass then visits only those lights, in ascending order (the reference's order). Likewise
// bit j of a bin's proxy mask is set when shadow proxy j can occlude a point the bin's
// texels ask about (texel centres, face points, and with unfolded proxy shadows points up
// to a wall height beyond them: `proxy_pad`); the others occlude nothing there. With
// `per_light`, each point light in a bin also gets its own proxy mask: a proxy at distance
// D from the light shades only points farther than sqrt(D^2 - reach^2) from it (its shadow
// lies within `reach` of it, behind it as seen from the light), so a bin nearer than that
// keeps none of its shadow.
// One invocation per bin. size = texture (w, h, -, res); parameters: LightBinParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct LightBinParams {
    int bins_x, bins_y; // bins (direct-pass workgroups) in x and y
    int words;          // 32-bit mask words per bin
    int bin_w, bin_h;   // a bin's size in texels
    int proxy_words;    // 32-bit proxy-mask words per bin
    float proxy_pad;    // how far beyond its texel centres a bin's proxy queries reach
    int per_light;      // 1: masks per (bin, point light) follow the bins' own
};
#define GI_PASS_PARAMS LightBinParams
#include "lantern/gi_common.glsl"

layout(constant_id = 4) const int MAX_LIGHTS = 2048;

layout(std140, binding = 0) uniform LightBlock { GpuPointLight lights[MAX_LIGHTS]; } u_lights;
layout(std430, binding = 1) buffer Out { uint masks[]; } o_bins;
uint o_bins_read(int at) { return o_bins.masks[at]; }
layout(std140, binding = 2) uniform ProxyBlock { GpuShadowProxy proxies[256]; } u_proxies;
layout(std430, binding = 3) buffer ProxyOut { uint masks[]; } o_proxy_bins; // bins' masks, then (bin, light)'s

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
    int proxy_base = (bin.y * bins.x + bin.x) * pc.pass.proxy_words;
    vec2 plo = lo - pc.pass.proxy_pad, phi = hi + pc.pass.proxy_pad;
    for (int w = 0; w < pc.pass.proxy_words; ++w) {
        uint bits = 0u;
        for (int b = 0; b < 32; ++b) {
            int i = w * 32 + b;
            if (i >= pc.counts.w) break;
            GpuShadowProxy p = u_proxies.proxies[i];
            vec2 d = max(max(plo - p.position_size.xy, p.position_size.xy - phi), vec2(0.0));
            if (sqrt(d.x * d.x + d.y * d.y) <= proxy_reach(p)) bits |= 1u << uint(b);
        }
        o_proxy_bins.masks[proxy_base + w] = bits;
    }
    if (pc.pass.per_light == 0) return;
    int points = pc.counts.x;
    int bins_total = bins.x * bins.y;
    for (int i = 0; i < points; ++i) {
        if ((o_bins_read(base + (i >> 5)) & (1u << uint(i & 31))) == 0u) continue;
        vec2 l = u_lights.lights[i].position_radius.xy;
        vec2 far_d = max(abs(plo - l), abs(phi - l));
        float far2 = far_d.x * far_d.x + far_d.y * far_d.y;
        int out_base = (bins_total + (bin.y * bins.x + bin.x) * points + i) * pc.pass.proxy_words;
        for (int w = 0; w < pc.pass.proxy_words; ++w) {
            uint bits = o_proxy_bins.masks[proxy_base + w], kept = 0u;
            for (; bits != 0u; bits &= bits - 1u) {
                int j = w * 32 + findLSB(bits);
                GpuShadowProxy p = u_proxies.proxies[j];
                vec2 q = p.position_size.xy - l;
                float reach = proxy_reach(p);
                float horizon2 = q.x * q.x + q.y * q.y - reach * reach;
                bool shades = !(far2 < horizon2 * 0.9999 - 1e-3);
                kept |= shades ? (1u << uint(j & 31)) : 0u;
            }
            o_proxy_bins.masks[out_base + w] = kept;
        }
    }
}
