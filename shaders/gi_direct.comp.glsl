// Direct light from point lights (DDA-shadowed, proxy-shadowed) and emissives (no
// shadows, no cap): ground colour (rgba16f), shadow map R (rg8), and per-face wall light
// (4 x rgba16f) on wall texels. Each workgroup visits only the lights gi_light_bins listed
// for its footprint. Grid shadows by the lights' shadow maps (gi_point_map.glsl) or the
// DDA. With SUNS, the realtime suns' own textures (gi_directional.comp's) are added as
// each texel is written (C++ reference: reference_passes.cpp reference_direct's `suns`).
// Parameters: DirectParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct DirectParams {
    float light_softness; // falloff exponent (gi.light_softness)
    float face_exponent;  // gi.wall_face_exponent
    int pad_f;            // (the faces computed are FACES, a specialisation constant)
    float wall_height;    // unfolded proxy shadows: the face's height
    int proxy_per_light;  // B > 0: gi_light_bins wrote proxy masks per (bin, point light, band of B, strip)
    int bins_x, bins_y;   // the workgroup grid (LIST: the bins, one workgroup per listed bin)
    int list_first;       // LIST: workgroup i computes bin u_dirty.bins[list_first + i]
};
#define GI_PASS_PARAMS DirectParams
#include "lantern/gi_common.glsl"

const bool UPPER = (FEATURES & 1u) != 0u;     // unfolded proxy shadows: write the upper-face textures
const bool POINT_MAP = (FEATURES & 4u) != 0u; // gi.shadow_method = shadow_map: grid shadows by the lights' maps
// gi.light_softness is 1 (the default): the falloff is linear, no pow. lavapipe evaluates
// pow as exp2(log2) per (texel, light) pair: about 40 % of the emissives' cost.
const bool LINEAR_FALLOFF = (FEATURES & 8u) != 0u;
// gi.wall_face_exponent is 1 (the default): the face weights without pow (wall_facing).
const bool LINEAR_FACES = (FEATURES & 256u) != 0u;
// Dirty light bins (docs/gi.md): workgroup i computes bin u_dirty.bins[list_first + i]
// (row-major in a bins_x x bins_y grid) and the other bins keep what they hold.
const bool LIST = (FEATURES & 16u) != 0u;
// Bins no light reaches: what every texel holds without light, with the light loops compiled
// out (lavapipe runs a loop's body at least once, masked, so an empty bin costs a light).
const bool NO_LIGHTS = (FEATURES & 32u) != 0u;
// The realtime suns' textures (bindings 17-26) added to what this pass writes.
const bool SUNS = (FEATURES & 128u) != 0u;

layout(constant_id = 4) const int MAX_LIGHTS = 2048; // point lights + emissives (64 KiB UBO)

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[256]; } u_proxies;
layout(std140, binding = 2) uniform LightBlock { GpuPointLight lights[MAX_LIGHTS]; } u_lights; // w: gi_point_map.glsl
layout(std430, binding = 3) writeonly buffer DirectOut { uvec2 texels[]; } o_direct;
layout(std430, binding = 4) writeonly buffer ShadowOut { uvec2 texels[]; } o_shadow; // 4 rg8 texels each
layout(std430, binding = 5) writeonly buffer FacePX { uvec2 texels[]; } o_face_px;
layout(std430, binding = 6) writeonly buffer FaceNX { uvec2 texels[]; } o_face_nx;
layout(std430, binding = 7) writeonly buffer FacePZ { uvec2 texels[]; } o_face_pz;
layout(std430, binding = 8) writeonly buffer FaceNZ { uvec2 texels[]; } o_face_nz;
layout(std430, binding = 9) readonly buffer Bins { uint masks[]; } u_bins; // gi_light_bins
layout(std430, binding = 10) writeonly buffer UpperPX { uvec2 texels[]; } o_upper_px;
layout(std430, binding = 11) writeonly buffer UpperNX { uvec2 texels[]; } o_upper_nx;
layout(std430, binding = 12) writeonly buffer UpperPZ { uvec2 texels[]; } o_upper_pz;
layout(std430, binding = 13) writeonly buffer UpperNZ { uvec2 texels[]; } o_upper_nz;
layout(std430, binding = 14) readonly buffer PointMapBins { uvec2 bins[]; } u_point_map; // gi_point_map.glsl
layout(std430, binding = 15) readonly buffer ProxyBins { uint masks[]; } u_proxy_bins; // gi_light_bins
layout(std430, binding = 16) readonly buffer DirtyBins { uint bins[]; } u_dirty; // LIST
layout(binding = 17) uniform samplerBuffer u_sun_direct; // SUNS: rgba16f views
layout(binding = 18) uniform samplerBuffer u_sun_shadow; // rg8 unorm: G
layout(binding = 19) uniform samplerBuffer u_sun_face_px;
layout(binding = 20) uniform samplerBuffer u_sun_face_nx;
layout(binding = 21) uniform samplerBuffer u_sun_face_pz;
layout(binding = 22) uniform samplerBuffer u_sun_face_nz;
layout(binding = 23) uniform samplerBuffer u_sun_upper_px;
layout(binding = 24) uniform samplerBuffer u_sun_upper_nx;
layout(binding = 25) uniform samplerBuffer u_sun_upper_pz;
layout(binding = 26) uniform samplerBuffer u_sun_upper_nz;

// The proxies this workgroup's bin lists (gi_shadow.glsl's loops).
int g_proxy_base;
int g_proxy_words;
int g_bin, g_bins_total;
int g_sub;  // the texel's strip: its column k of the invocation's BLOCK_W (gi_light_bins)
int g_band; // the invocation row's band of the bin's proxy_per_light bands (gi_light_bins)
#define GI_PROXY_MASK(w) u_proxy_bins.masks[g_proxy_base + (w)]
#define GI_PROXY_WORDS g_proxy_words

#include "lantern/gi_shadow.glsl"
#include "lantern/gi_point_map.glsl"

// light_falloff, with the exponent folded away when it is 1 (pow(x, 1) is x, as in the
// reference's std::pow).
float falloff(float dist, float radius, float softness) {
    return LINEAR_FALLOFF ? 1.0 - saturate(dist / radius) : light_falloff(dist, radius, softness);
}

#include "lantern/gi_texel_light.glsl"

float light_distance(vec2 p, vec2 pos) {
    precise vec2 d = pos - p;
    precise float dist = gi_length(d);
    return dist;
}

vec4 face_weights(vec4 mask, vec2 p, vec2 light_pos) {
    precise vec2 to_light = light_pos - p;
    precise float squared = max(to_light.x * to_light.x + to_light.y * to_light.y, 1e-6);
    precise float inv_len = gi_div(1.0, gi_sqrt(squared));
    return mask * wall_facing(to_light * inv_len, pc.pass.face_exponent, LINEAR_FACES);
}

// The lights this workgroup's bin lists, in ascending order: point lights first. lavapipe
// runs both sides of every branch, so point lights and emissives have loops of their own and
// a texel's targets (its centre, or two faces) share one code path.
int g_bin_base;
int g_bin_words;

#define FOR_EACH_BIN_LIGHT(i, first, end)                                                        \
    for (int w_ = (first) >> 5; w_ < ((end) + 31) >> 5; ++w_)                                    \
        for (uint bits_ = u_bins.masks[g_bin_base + w_] & light_word_mask(w_, first, end); bits_ != 0u; \
             bits_ &= bits_ - 1u)                                                                \
            for (int i = w_ * 32 + findLSB(bits_), once_ = 1; once_ == 1; once_ = 0)

// The bits of mask word w that stand for lights in [first, end).
uint light_word_mask(int w, int first, int end) {
    int lo = clamp(first - w * 32, 0, 32), hi = clamp(end - w * 32, 0, 32);
    uint below_hi = hi >= 32 ? ~0u : (1u << uint(hi)) - 1u;
    uint below_lo = lo >= 32 ? ~0u : (1u << uint(lo)) - 1u;
    return below_hi & ~below_lo;
}

// Point light i at a texel: on the ground its colour and shadow; on a wall each face that
// can face the light (one across x, one across z), shadowed by its own traversal to just
// outside the face. Grid shadows by the seed's DDA, or by the light's map (POINT_MAP): a
// target the map cannot decide adds nothing and sets its bit in `later` (bit s: target
// s); the caller calls again with `deferred` and those bits in `only`, and the DDA decides.
// Without `proxies`, no proxy shades the light here (its list for the texel's sub-bin is
// empty), and the proxy loops are left out.
void point_light(int i, const bool deferred, const bool proxies, uint only, bool wall, ivec2 cell, vec2 p, vec4 mask,
                 float softness, inout TexelLight t, inout uint later) {
    if (proxies && pc.pass.proxy_per_light != 0) // this light's proxies in this texel's sub-bin (gi_light_bins)
        g_proxy_base = (g_bins_total + ((g_bin * pc.counts.x + i) * pc.pass.proxy_per_light + g_band) * int(BLOCK_W) + g_sub) *
                       g_proxy_words;
    GpuPointLight l = u_lights.lights[i];
    vec2 pos = l.position_radius.xy;
    float radius = l.position_radius.z;
    float dist = light_distance(p, pos);
    vec4 weight = face_weights(mask, p, pos);
    int fx = weight.x > 0.0 ? 0 : 1, fz = weight.z > 0.0 ? 2 : 3;
    vec3 contribution = l.color.rgb * falloff(dist, radius, softness);
    int targets = dist > radius ? 0 : (wall ? 2 : 1);
    for (int s = 0; s < targets; ++s) {
        int f = s == 0 ? fx : fz;
        float w = s == 0 ? (fx == 0 ? weight.x : weight.y) : (fz == 2 ? weight.z : weight.w);
        vec2 target = wall ? face_position(f, cell, p) : p;
        float grid;
        bool skip = false;
        if (!POINT_MAP || deferred) {
            grid = shadow_dda(pos, target, radius);
            skip = deferred && ((only >> uint(s)) & 1u) == 0u;
        } else {
            grid = point_map_lookup(l, target);
            skip = grid < 0.0;
            later |= skip ? 1u << uint(s) : 0u;
        }
        vec3 light = skip ? vec3(0.0) : contribution; // adding 0 leaves every sum as it is
        if (UPPER && wall) {
            add_face(t, f, light * w, grid, proxies ? point_proxy_face_shadow(pos, target, pc.pass.wall_height) : vec3(1.0, 1.0, 0.0));
            continue;
        }
        float shadow = skip ? 0.0 : (proxies ? min(grid, point_proxy_shadow(pos, target)) : grid);
        if (wall) {
            add_face_light(t, f, light * (w * shadow)); // w = 0: adds 0, as the reference's skip
        } else {
            t.shadow = max(t.shadow, shadow);
            t.color += light * shadow; // (colour x falloff) x shadow, as the reference
        }
    }
}

// Emissive light i at a texel (no shadows): the ground colour, or each face's.
void emissive_light(int i, bool wall, vec2 p, vec4 mask, float softness, inout TexelLight t) {
    GpuPointLight l = u_lights.lights[i];
    vec2 pos = l.position_radius.xy;
    float radius = l.position_radius.z;
    float dist = light_distance(p, pos);
    if (dist > radius) return;
    vec3 contribution = l.color.rgb * falloff(dist, radius, softness);
    if (!wall) {
        t.color += contribution;
        return;
    }
    vec4 weight = face_weights(mask, p, pos);
    for (int f = 0; f < 4; ++f) {
        t.face[f] += contribution * weight[f];
        if (UPPER) t.upper[f] += contribution * weight[f];
    }
}

void texel_light(bool wall, ivec2 cell, vec2 p, inout TexelLight t) {
    vec4 mask = wall ? wall_face_mask(cell) * face_bits_mask(FACES) : vec4(0.0);
    float softness = pc.pass.light_softness;
    int points = pc.counts.x, lights = pc.counts.x + pc.counts.y;
    // Point lights 32 at a time (a word of the bin's mask): first every target the map (or
    // the DDA) decides, the lights no proxy shades in the texel's sub-bin (gi_light_bins's
    // mask of the lights with a proxy list there) before the others, then, in a loop of their
    // own, the map's close calls by the DDA. The reference adds the lights in ascending order
    // (with the close calls last, reference_passes.cpp, PendingTargets): the sums agree to
    // rounding, not bit for bit.
    int point_words = (points + 31) >> 5;
    int has_base = g_bins_total * g_proxy_words * (1 + points * pc.pass.proxy_per_light * int(BLOCK_W)) +
                   ((g_bin * pc.pass.proxy_per_light + g_band) * int(BLOCK_W) + g_sub) * point_words;
    for (int w = 0; w < point_words; ++w) {
        uint later0 = 0u, later1 = 0u;
        uint lit = u_bins.masks[g_bin_base + w] & light_word_mask(w, 0, points);
        uint shaded = !HAS_PROXIES ? 0u : (pc.pass.proxy_per_light != 0 ? u_proxy_bins.masks[has_base + w] : ~0u);
        for (uint bits = lit & ~shaded; bits != 0u; bits &= bits - 1u) {
            int j = findLSB(bits);
            uint later = 0u;
            point_light(w * 32 + j, false, false, 0u, wall, cell, p, mask, softness, t, later);
            later0 |= (later & 1u) << uint(j);
            later1 |= ((later >> 1u) & 1u) << uint(j);
        }
        if (HAS_PROXIES)
            for (uint bits = lit & shaded; bits != 0u; bits &= bits - 1u) {
                int j = findLSB(bits);
                uint later = 0u;
                point_light(w * 32 + j, false, true, 0u, wall, cell, p, mask, softness, t, later);
                later0 |= (later & 1u) << uint(j);
                later1 |= ((later >> 1u) & 1u) << uint(j);
            }
        if (POINT_MAP)
            for (uint bits = later0 | later1; bits != 0u; bits &= bits - 1u) {
                int j = findLSB(bits);
                uint only = ((later0 >> uint(j)) & 1u) | (((later1 >> uint(j)) & 1u) << 1u), unused = 0u;
                point_light(w * 32 + j, true, HAS_PROXIES, only, wall, cell, p, mask, softness, t, unused);
            }
    }
    FOR_EACH_BIN_LIGHT(i, points, lights) emissive_light(i, wall, p, mask, softness, t);
}

// Adds the suns' light of texel `index` to t (SUNS): colour and faces summed, the upper
// faces' edges merged, each weighted by the light its shadows take. Returns their shadow (G).
float add_suns(inout TexelLight t, uint faces, int index) {
    t.color += texelFetch(u_sun_direct, index).rgb;
    if (!HAS_WALLS) return texelFetch(u_sun_shadow, index).g;
    vec4 low[4] = vec4[4](texelFetch(u_sun_face_px, index), texelFetch(u_sun_face_nx, index),
                          texelFetch(u_sun_face_pz, index), texelFetch(u_sun_face_nz, index));
    for (int f = 0; f < 4; ++f) {
        if (!computes_face(faces, f)) continue;
        if (UPPER) {
            vec4 up = f == 0 ? texelFetch(u_sun_upper_px, index)
                    : f == 1 ? texelFetch(u_sun_upper_nx, index)
                    : f == 2 ? texelFetch(u_sun_upper_pz, index) : texelFetch(u_sun_upper_nz, index);
            float taken = (up.r - low[f].r) + (up.g - low[f].g) + (up.b - low[f].b);
            if (taken > 0.0) {
                t.edge_sum[f] += taken * up.a;
                t.edge_weight[f] += taken;
            }
            t.upper[f] += up.rgb;
        }
        t.face[f] += low[f].rgb;
    }
    return texelFetch(u_sun_shadow, index).g;
}

// The shadow map R and G of the workgroup's texels (rg8, 16 bits each), repacked from the
// lanes' texels into each invocation's 4 x BLOCK_H block.
shared uint s_shadow[gl_WorkGroupSize.x * gl_WorkGroupSize.y * BLOCK_W * BLOCK_H];

void main() {
    uvec2 group = gl_WorkGroupID.xy, groups = gl_NumWorkGroups.xy;
    if (LIST) {
        groups = uvec2(pc.pass.bins_x, pc.pass.bins_y);
        uint bin = u_dirty.bins[pc.pass.list_first + int(gl_WorkGroupID.x)];
        group = uvec2(bin % groups.x, bin / groups.x);
    }
    // Lanes hold neighbouring texels: invocation x of a workgroup row computes texels x,
    // x + size_x, x + 2 size_x, x + 3 size_x of its block rows, so the 8 lanes llvmpipe runs
    // as one vector are 8 adjacent texels (one tile's row at giRes 8, when aligned) rather
    // than 32 across four tiles: the per-light loops (a wall's two targets, the DDA's close
    // calls, the reach) then run only as long as those texels need. The shadow texture's
    // rows of 4 texels are repacked through shared memory.
    const int row_w = int(gl_WorkGroupSize.x * BLOCK_W);
    ivec2 group_o = ivec2(group * gl_WorkGroupSize.xy * uvec2(BLOCK_W, BLOCK_H));
    ivec2 o = group_o + ivec2(int(gl_LocalInvocationID.x), int(gl_LocalInvocationID.y * BLOCK_H));
    g_bin = int(group.y * groups.x + group.x);
    g_bin_words = (pc.counts.x + pc.counts.y + 31) >> 5;
    g_bin_base = g_bin * g_bin_words;
    g_proxy_words = (pc.counts.w + 31) >> 5;
    g_bins_total = int(groups.x * groups.y);
    g_proxy_base = g_bin * g_proxy_words;
    g_band = int(gl_LocalInvocationID.y) * max(pc.pass.proxy_per_light, 1) / int(gl_WorkGroupSize.y);
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        for (int k = 0; k < int(BLOCK_W); ++k) {
            int x = o.x + k * int(gl_WorkGroupSize.x);
            g_sub = k;
            // Texels up to the pitch (the width rounded up to 4) are written, as every pass.
            if (y >= pc.size.y || (x & ~3) >= pc.size.x) continue;
            TexelLight t = no_texel_light();
            bool wall = false;
            if (x < pc.size.x) {
                vec2 p = texel_center(x, y);
                ivec2 cell = ivec2(floor(p));
                wall = HAS_WALLS && is_wall(cell);
                // A wall's ground light is 0; with no face computed a wall texel has no light.
                if (!NO_LIGHTS && (!wall || FACES != 0u)) texel_light(wall, cell, p, t);
            }
            int index = texel_index(x, y);
            float sun_shadow = SUNS ? add_suns(t, FACES, index) : 0.0;
            o_direct.texels[index] = pack_rgba16f(vec4(t.color, 0.0));
            if (HAS_WALLS) { // otherwise the face textures are cleared once by the host
                float has_faces = wall ? 1.0 : 0.0; // alpha flags texels holding face light
                uint faces = FACES;         // a face not computed has no texture
                if (computes_face(faces, 0)) o_face_px.texels[index] = pack_rgba16f(vec4(t.face[0], has_faces));
                if (computes_face(faces, 1)) o_face_nx.texels[index] = pack_rgba16f(vec4(t.face[1], has_faces));
                if (computes_face(faces, 2)) o_face_pz.texels[index] = pack_rgba16f(vec4(t.face[2], has_faces));
                if (computes_face(faces, 3)) o_face_nz.texels[index] = pack_rgba16f(vec4(t.face[3], has_faces));
                if (UPPER) {
                    if (computes_face(faces, 0)) o_upper_px.texels[index] = pack_rgba16f(vec4(t.upper[0], face_edge(t, 0)));
                    if (computes_face(faces, 1)) o_upper_nx.texels[index] = pack_rgba16f(vec4(t.upper[1], face_edge(t, 1)));
                    if (computes_face(faces, 2)) o_upper_pz.texels[index] = pack_rgba16f(vec4(t.upper[2], face_edge(t, 2)));
                    if (computes_face(faces, 3)) o_upper_nz.texels[index] = pack_rgba16f(vec4(t.upper[3], face_edge(t, 3)));
                }
            }
            s_shadow[(int(gl_LocalInvocationID.y * BLOCK_H) + int(r)) * row_w + (x - group_o.x)] =
                unorm8(wall ? 0.0 : t.shadow) | (unorm8(sun_shadow) << 8);
        }
    }
    barrier();
    // Each invocation writes the shadow texels of its own block: 4 x BLOCK_H from x0.
    int x0 = group_o.x + int(gl_LocalInvocationID.x * BLOCK_W);
    if (x0 >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        int at = (int(gl_LocalInvocationID.y * BLOCK_H) + int(r)) * row_w + (x0 - group_o.x);
        o_shadow.texels[texel_index(x0, y) / 4] =
            uvec2(s_shadow[at] | (s_shadow[at + 1] << 16), s_shadow[at + 2] | (s_shadow[at + 3] << 16));
    }
}
