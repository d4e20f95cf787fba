// Tiled light culling for the direct pass. A bin is the footprint of one direct-pass
// workgroup (4 * group_x by BLOCK_H * group_y texels); bit i of a bin's mask is set when
// light i (point lights, then emissives) can reach a texel centre in the bin. The direct
// pass then visits only those lights, in ascending order (the reference's order). Likewise
// bit j of a bin's proxy mask is set when shadow proxy j can occlude a point the bin's
// texels ask about (texel centres, face points, and with unfolded proxy shadows points up
// to a wall height beyond them: `proxy_pad`); the others occlude nothing there. With
// `per_light` = B > 0, each point light in a bin also gets proxy masks of its own, one for
// each of the bin's B x BLOCK_W sub-bins: B bands of its rows by BLOCK_W strips of its
// columns [k * group_x, (k + 1) * group_x). The direct pass's invocation x computes columns
// x + k * group_x, so 8 neighbouring lanes ask about one strip, and one workgroup row about
// one band when B is its group_y. A proxy at distance D from the light shades only points
// farther than sqrt(D^2 - reach^2) from it (its shadow lies within `reach` of it, behind it
// as seen from the light), and only points inside a wedge round its direction from the
// light (`outside_shadow_wedge`); a sub-bin wholly nearer, or wholly outside the wedge, or
// beyond the proxy's reach, keeps none of its shadow. After those lists, a light mask per
// sub-bin: bit i set when point light i's list there is not empty (the direct pass visits the
// lights with an empty list in a loop of their own, without the proxy loop: lavapipe runs a
// loop's body at least once, masked, so an empty list costs what a proxy does).
// One workgroup per bin, BLOCK_W x some rows of invocations: the bin's masks first, shared,
// then invocation (k, b) the per-light masks of strip k in bands b, b + rows, ...
// size = texture (w, h, -, res); parameters: LightBinParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct LightBinParams {
    int bins_x, bins_y; // bins (direct-pass workgroups) in x and y
    int words;          // 32-bit mask words per bin
    int bin_w, bin_h;   // a bin's size in texels
    int proxy_words;    // 32-bit proxy-mask words per bin
    float proxy_pad;    // how far beyond its texel centres a bin's proxy queries reach
    int per_light;      // B > 0: masks per (bin, point light, band of B, strip) follow the bins' own
};
#define GI_PASS_PARAMS LightBinParams
#include "lantern/gi_common.glsl"

layout(constant_id = 4) const int MAX_LIGHTS = 2048;
// A bin's sub-bins: the direct pass's texel columns per invocation (gi_common.glsl BLOCK_W).
const int LIGHT_SUBS = int(BLOCK_W);

layout(std140, binding = 0) uniform LightBlock { GpuPointLight lights[MAX_LIGHTS]; } u_lights;
layout(std430, binding = 1) buffer Out { uint masks[]; } o_bins;
layout(std140, binding = 2) uniform ProxyBlock { GpuShadowProxy proxies[256]; } u_proxies;
layout(std430, binding = 3) buffer ProxyOut { uint masks[]; } o_proxy_bins; // bins' masks, then (bin, light)'s

// The widest perp distance from proxy p's shadow axis at which it occludes anything
// (proxy_occlusion: its widest half width, proxy_width, plus its penumbra width), with a
// margin for the float error of the passes that compute the occlusion and of this culling
// (outside_shadow_wedge), also at far coordinates.
float proxy_wedge_width(GpuShadowProxy p) {
    float w = abs(p.position_size.z) + abs(p.position_size.w) + max(p.lengths.z, 0.0);
    return w * 1.001 + 1e-3 + 1e-6 * (abs(p.position_size.x) + abs(p.position_size.y));
}

// A lower bound on rmin^2, the squared distance from a point light to any point that proxy
// p, at q = P - light (squared length d2), can occlude: an occluded point lies within the
// proxy's reach of P and beyond P along its shadow's axis, so farther than
// sqrt(d2 - reach^2) from the light (the horizon test in main). Bounds reach^2 from above
// without a root: along^2 + w^2 is its square (proxy_reach before its margin).
float proxy_horizon2(GpuShadowProxy p, float d2, float w) {
    float along = max(p.lengths.x + p.lengths.w, 0.0);
    return d2 * 0.999 - ((along * along + w * w) * 1.001 + 1e-3);
}

// Whether the box [lo, hi] (relative to point light L) lies outside every point that proxy
// p, at q = P - L from L (squared length dist2), can occlude for L. Such a point x = L + r d
// has perp distance below w (proxy_wedge_width) from the proxy's shadow axis, which runs
// through P along a direction s between d and a = q / |q| (point_shadow_axis: the end-cap
// blend of the two). With phi the angle between d and a, that perp distance is
// r sin(angle(d, s)) + |q| sin(angle(s, a)), concave in the split, so at least
// min(r, |q|) sin(phi) while phi is below 90 degrees (`along` > 0 and `ahead` > 0 hold only
// when both parts are below 90 degrees, so beyond it at least min(r, |q|)); and both r and
// |q| exceed rmin = sqrt(proxy_horizon2). So x lies within the wedge of half-angle
// asin(w / rmin) round a. That wedge is the cone of its two edge rays (the half-angle is
// below 90 degrees), tested against the box on the cone's two edge normals and the box's two
// axes (separating axes), the box's side given a margin for the float error.
bool outside_shadow_wedge(GpuShadowProxy p, vec2 q, float dist2, vec2 lo, vec2 hi) {
    float w = proxy_wedge_width(p);
    float rmin2 = proxy_horizon2(p, dist2, w);
    if (!(rmin2 > 0.0)) return false;
    float s2 = w * w / rmin2; // sin^2 of the half-angle
    if (!(s2 < 0.9)) return false;
    float s = sqrt(s2), c = sqrt(1.0 - s2);
    vec2 a = q / sqrt(dist2);
    vec2 e1 = vec2(c * a.x + s * a.y, c * a.y - s * a.x); // a turned by -half-angle
    vec2 e2 = vec2(c * a.x - s * a.y, c * a.y + s * a.x); // and by +half-angle
    // The cone: cross(e1, v) >= 0 and cross(v, e2) >= 0, i.e. n1.v >= 0 and n2.v >= 0.
    vec2 n1 = vec2(-e1.y, e1.x), n2 = vec2(e2.y, -e2.x);
    float slack = 1e-4 * (1.0 + max(max(abs(lo.x), abs(lo.y)), max(abs(hi.x), abs(hi.y))));
    float m1 = max(n1.x * lo.x, n1.x * hi.x) + max(n1.y * lo.y, n1.y * hi.y);
    float m2 = max(n2.x * lo.x, n2.x * hi.x) + max(n2.y * lo.y, n2.y * hi.y);
    if (m1 < -slack || m2 < -slack) return true;
    // The cone's extent on each axis: one side of the apex when both edges point to it.
    if (e1.x >= 0.0 && e2.x >= 0.0 && hi.x < -slack) return true;
    if (e1.x <= 0.0 && e2.x <= 0.0 && lo.x > slack) return true;
    if (e1.y >= 0.0 && e2.y >= 0.0 && hi.y < -slack) return true;
    if (e1.y <= 0.0 && e2.y <= 0.0 && lo.y > slack) return true;
    return false;
}

// The bin's masks, shared by its invocations' per-light lists.
shared uint s_lights[MAX_LIGHTS / 32];
shared uint s_proxies[8]; // 256 proxies

void main() {
    ivec2 bin = ivec2(gl_WorkGroupID.xy);
    ivec2 bins = ivec2(pc.pass.bins_x, pc.pass.bins_y);
    int words = pc.pass.words;
    ivec2 bin_size = ivec2(pc.pass.bin_w, pc.pass.bin_h);
    ivec2 first = bin * bin_size;
    ivec2 last = min(first + bin_size, pc.size.xy) - 1;
    vec2 lo = texel_center(first.x, first.y), hi = texel_center(max(last.x, first.x), max(last.y, first.y));
    int n = pc.counts.x + pc.counts.y;
    int base = (bin.y * bins.x + bin.x) * words;
    const int threads = int(gl_WorkGroupSize.x * gl_WorkGroupSize.y);
    int t = int(gl_LocalInvocationIndex);
    // The bin's light mask, a word per invocation in turn.
    for (int w = t; w < words; w += threads) {
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
        s_lights[w] = bits;
    }
    int proxy_base = (bin.y * bins.x + bin.x) * pc.pass.proxy_words;
    vec2 plo = lo - pc.pass.proxy_pad, phi = hi + pc.pass.proxy_pad;
    for (int w = t; w < pc.pass.proxy_words; w += threads) {
        uint bits = 0u;
        for (int b = 0; b < 32; ++b) {
            int i = w * 32 + b;
            if (i >= pc.counts.w) break;
            GpuShadowProxy p = u_proxies.proxies[i];
            vec2 d = max(max(plo - p.position_size.xy, p.position_size.xy - phi), vec2(0.0));
            if (sqrt(d.x * d.x + d.y * d.y) <= proxy_reach(p)) bits |= 1u << uint(b);
        }
        o_proxy_bins.masks[proxy_base + w] = bits;
        s_proxies[w] = bits;
    }
    int bands = pc.pass.per_light;
    if (bands == 0) return;
    barrier();
    // Per (bin, point light, band, column strip): invocation (k, b) takes strip k and bands
    // b, b + group_y, ... Band `band` holds the bin's texel rows
    // [band * bin_h / bands, (band + 1) * bin_h / bands) (the direct pass's invocation rows
    // [band * gy / bands, ...)), strip k its columns [k * sub_w, (k + 1) * sub_w); a sub-bin
    // past the window's edge has no texel and empty masks. Every invocation of the workgroup
    // walks the same lights and proxies (the bin's masks).
    int points = pc.counts.x;
    int bins_total = bins.x * bins.y;
    int point_words = (points + 31) >> 5;
    int has_base = bins_total * pc.pass.proxy_words * (1 + points * bands * LIGHT_SUBS);
    int sub_w = bin_size.x / LIGHT_SUBS, sub_h = bin_size.y / bands;
    int k = int(gl_LocalInvocationID.x);
    for (int band = int(gl_LocalInvocationID.y); band < bands; band += int(gl_WorkGroupSize.y)) {
        int x0 = first.x + k * sub_w, x1 = min(x0 + sub_w, pc.size.x) - 1;
        int y0 = first.y + band * sub_h, y1 = min(y0 + sub_h, pc.size.y) - 1;
        bool empty = x0 > last.x || y0 > last.y;
        vec2 slo = texel_center(x0, y0) - pc.pass.proxy_pad;
        vec2 shi = texel_center(max(x1, x0), max(y1, y0)) + pc.pass.proxy_pad;
        int has_at = has_base + (((bin.y * bins.x + bin.x) * bands + band) * LIGHT_SUBS + k) * point_words;
        // The bin's point lights alone, by the bits of its mask: a loop over every light that
        // skipped the others with `continue` ran the whole body for each of them, masked.
        for (int lw = 0; lw < point_words; ++lw) {
            uint has = 0u; // the lights of word lw whose list is not empty
            uint in_bin = s_lights[lw] & (lw < (points >> 5) ? ~0u : (1u << uint(points & 31)) - 1u);
            for (; in_bin != 0u; in_bin &= in_bin - 1u) {
                int i = lw * 32 + findLSB(in_bin);
                vec2 l = u_lights.lights[i].position_radius.xy;
                vec2 far_d = max(abs(slo - l), abs(shi - l));
                float far2 = far_d.x * far_d.x + far_d.y * far_d.y;
                int out_base = (bins_total + (((bin.y * bins.x + bin.x) * points + i) * bands + band) * LIGHT_SUBS + k) *
                               pc.pass.proxy_words;
                uint any = 0u;
                for (int w = 0; w < pc.pass.proxy_words; ++w) {
                    uint kept = 0u;
                    for (uint bits = s_proxies[w]; bits != 0u; bits &= bits - 1u) {
                        int j = w * 32 + findLSB(bits);
                        GpuShadowProxy p = u_proxies.proxies[j];
                        vec2 q = p.position_size.xy - l;
                        float reach = proxy_reach(p);
                        float dist2 = q.x * q.x + q.y * q.y;
                        float horizon2 = dist2 - reach * reach;
                        bool shades = !(far2 < horizon2 * 0.9999 - 1e-3) &&
                                      !outside_shadow_wedge(p, q, dist2, slo - l, shi - l);
                        // Within the sub-bin's own reach of the proxy, as the bin's mask is.
                        vec2 d = max(max(slo - p.position_size.xy, p.position_size.xy - shi), vec2(0.0));
                        shades = shades && !(sqrt(d.x * d.x + d.y * d.y) > reach);
                        kept |= shades && !empty ? (1u << uint(j & 31)) : 0u;
                    }
                    o_proxy_bins.masks[out_base + w] = kept;
                    any |= kept;
                }
                has |= any != 0u ? 1u << uint(i & 31) : 0u;
            }
            o_proxy_bins.masks[has_at + lw] = has;
        }
    }
}
