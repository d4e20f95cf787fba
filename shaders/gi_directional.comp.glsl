// Directional lights (sun, moon): traversal towards the light with the wall-height test,
// into the direct colour and wall faces; writes shadow map G (max visibility). The
// directional row lights the realtime suns into their own textures (nothing read: the
// direct pass adds them); the mixed row the mixed suns, added in place to its own textures
// (FEATURES & 64).
// Each workgroup visits only the proxies whose shadow from the sun can reach it (a mask per
// sun and workgroup, built on the host: record_directional's sun_proxy_bins).
// Parameters: DirectionalParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct DirectionalParams {
    float wall_height;
    float angle_scale; // gi.directional_angle_scale
    float face_exponent; // gi.wall_face_exponent
    int pad_f;            // (the faces computed are FACES, a specialisation constant)
    int pad0, pad1, pad2, pad3;
};
#define GI_PASS_PARAMS DirectionalParams
#include "lantern/gi_common.glsl"

const bool UPPER = (FEATURES & 1u) != 0u;   // unfolded proxy shadows: the upper-face textures
const bool SUN_MAP = (FEATURES & 2u) != 0u; // the suns' grid shadows by their shadow map
// The mixed suns (the mixed row: in place on its textures), else the realtime ones
// (frame_inputs.hpp is_mixed_sun: bounce.y != 0).
const bool MIXED_SUNS = (FEATURES & 64u) != 0u;

// An input texel: what the mixed suns add to; the realtime suns start from zero (their
// inputs are bound to their outputs and never read).
vec4 input_texel(samplerBuffer t, int index) { return MIXED_SUNS ? texelFetch(t, index) : vec4(0.0); }

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[256]; } u_proxies;
layout(std140, binding = 2) uniform SunBlock { GpuDirectionalLight suns[8]; } u_suns;
layout(binding = 3) uniform samplerBuffer u_direct_in; // rgba16f views of the outputs
layout(binding = 4) uniform samplerBuffer u_shadow_in; // rg8 unorm
layout(binding = 5) uniform samplerBuffer u_face_px_in;
layout(binding = 6) uniform samplerBuffer u_face_nx_in;
layout(binding = 7) uniform samplerBuffer u_face_pz_in;
layout(binding = 8) uniform samplerBuffer u_face_nz_in;
layout(std430, binding = 9) writeonly buffer DirectOut { uvec2 texels[]; } o_direct;
layout(std430, binding = 10) writeonly buffer ShadowOut { uvec2 texels[]; } o_shadow;
layout(std430, binding = 11) writeonly buffer FacePX { uvec2 texels[]; } o_face_px;
layout(std430, binding = 12) writeonly buffer FaceNX { uvec2 texels[]; } o_face_nx;
layout(std430, binding = 13) writeonly buffer FacePZ { uvec2 texels[]; } o_face_pz;
layout(std430, binding = 14) writeonly buffer FaceNZ { uvec2 texels[]; } o_face_nz;
layout(binding = 15) uniform samplerBuffer u_sun_headers; // gi_sun_map.glsl
layout(binding = 16) uniform usamplerBuffer u_sun_first;
layout(binding = 17) uniform samplerBuffer u_sun_entries;
layout(binding = 18) uniform samplerBuffer u_upper_px_in; // the point lights' upper faces
layout(binding = 19) uniform samplerBuffer u_upper_nx_in;
layout(binding = 20) uniform samplerBuffer u_upper_pz_in;
layout(binding = 21) uniform samplerBuffer u_upper_nz_in;
layout(std430, binding = 22) writeonly buffer UpperPX { uvec2 texels[]; } o_upper_px;
layout(std430, binding = 23) writeonly buffer UpperNX { uvec2 texels[]; } o_upper_nx;
layout(std430, binding = 24) writeonly buffer UpperPZ { uvec2 texels[]; } o_upper_pz;
layout(std430, binding = 25) writeonly buffer UpperNZ { uvec2 texels[]; } o_upper_nz;
layout(std430, binding = 26) readonly buffer SunProxyBins { uint masks[]; } u_sun_proxy_bins;

// The proxies the current sun's mask lists for this workgroup (gi_shadow.glsl's loops).
int g_bin, g_bins_total, g_proxy_base, g_proxy_words;
#define GI_PROXY_MASK(w) u_sun_proxy_bins.masks[g_proxy_base + (w)]
#define GI_PROXY_WORDS g_proxy_words

#include "lantern/gi_shadow.glsl"
#include "lantern/gi_sun_map.glsl"

#include "lantern/gi_texel_light.glsl"

float sun_angle(GpuDirectionalLight sun) {
    return mix(saturate(-sun.direction_base.y * 2.0), 1.0, pc.pass.angle_scale);
}

// The walls' part of the sun's visibility (0 below the horizon).
float sun_grid_visibility(int i, GpuDirectionalLight sun, vec2 from) {
    vec3 dir = sun.direction_base.xyz;
    if (dir.y >= 0.0) return 0.0; // below the horizon
    float max_distance = sun.direction_base.w * sun.color_multiplier.w;
    return SUN_MAP ? sun_map_visibility(i, sun, from, max_distance, pc.pass.wall_height)
                                : directional_shadow_dda(from, dir, max_distance, pc.pass.wall_height);
}

// A texel's targets share one code path, as in the direct pass: the ground texel's centre,
// or a wall texel's x face and z face that can face the sun (weight > 0; at most one of each
// pair). lavapipe runs both sides of every branch, masked, so separate ground and wall paths
// cost every texel both, and a loop over four faces four traversals.
void sun_texel(bool wall, ivec2 cell, vec2 p, inout TexelLight t) {
    vec4 mask = wall ? wall_face_mask(cell) * face_bits_mask(FACES) : vec4(0.0);
    int targets = wall ? 2 : 1;
    for (int i = 0; i < pc.counts.z; ++i) {
        GpuDirectionalLight sun = u_suns.suns[i];
        if ((sun.bounce.y != 0.0) != MIXED_SUNS) continue;
        g_proxy_base = (i * g_bins_total + g_bin) * g_proxy_words;
        vec3 color = sun.color_multiplier.rgb * sun_angle(sun);
        vec2 to_sun = vec2(-sun.direction_base.x, -sun.direction_base.z);
        precise float len = gi_length(to_sun);
        // The sun overhead lights no face (len < 1e-4).
        vec4 weight = len < 1e-4 ? vec4(0.0) : mask * wall_facing(gi_div(to_sun, max(len, 1e-4)), pc.pass.face_exponent);
        int fx = weight.x > 0.0 ? 0 : 1, fz = weight.z > 0.0 ? 2 : 3;
        for (int s = 0; s < targets; ++s) {
            int f = s == 0 ? fx : fz;
            float w = s == 0 ? (fx == 0 ? weight.x : weight.y) : (fz == 2 ? weight.z : weight.w);
            if (wall && !(w > 0.0)) continue;
            vec2 target = wall ? face_position(f, cell, p) : p;
            float grid = sun_grid_visibility(i, sun, target);
            // The proxies' shadow at the target (x), and with unfolded proxy shadows at a
            // face's top (y) and the height its shadow ends (z).
            vec3 proxy = UPPER ? directional_proxy_face_shadow(target, sun.direction_base.xyz, pc.pass.wall_height)
                               : vec3(directional_proxy_shadow(target, sun.direction_base.xyz), 1.0, 0.0);
            if (UPPER && wall) {
                add_face(t, f, color * w, grid, proxy);
                continue;
            }
            float visibility = min(grid, proxy.x);
            if (wall) {
                add_face_light(t, f, color * (w * visibility));
            } else {
                t.shadow = max(t.shadow, visibility);
                t.color += color * visibility;
            }
        }
    }
}

// Adds the suns' upper-face light to the input's and merges the edges, each weighted by the
// light its shadows take (reference_passes.cpp reference_directional).
void merge_upper(inout TexelLight t, uint faces, int index) {
    vec4 low[4] = vec4[4](input_texel(u_face_px_in, index), input_texel(u_face_nx_in, index),
                          input_texel(u_face_pz_in, index), input_texel(u_face_nz_in, index));
    vec4 up[4] = vec4[4](input_texel(u_upper_px_in, index), input_texel(u_upper_nx_in, index),
                         input_texel(u_upper_pz_in, index), input_texel(u_upper_nz_in, index));
    vec4 out_upper[4];
    for (int f = 0; f < 4; ++f) {
        float taken = (up[f].r - low[f].r) + (up[f].g - low[f].g) + (up[f].b - low[f].b);
        if (taken > 0.0) {
            t.edge_sum[f] += taken * up[f].a;
            t.edge_weight[f] += taken;
        }
        out_upper[f] = vec4(up[f].rgb + t.upper[f], face_edge(t, f));
    }
    if (computes_face(faces, 0)) o_upper_px.texels[index] = pack_rgba16f(out_upper[0]);
    if (computes_face(faces, 1)) o_upper_nx.texels[index] = pack_rgba16f(out_upper[1]);
    if (computes_face(faces, 2)) o_upper_pz.texels[index] = pack_rgba16f(out_upper[2]);
    if (computes_face(faces, 3)) o_upper_nz.texels[index] = pack_rgba16f(out_upper[3]);
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    g_bin = int(gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x);
    g_bins_total = int(gl_NumWorkGroups.x * gl_NumWorkGroups.y);
    g_proxy_words = (pc.counts.w + 31) >> 5;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        vec2 shadow[4];
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            int index = texel_index(x, y);
            TexelLight t = no_texel_light();
            bool wall = false;
            if (x < pc.size.x) {
                vec2 p = texel_center(x, y);
                ivec2 cell = ivec2(floor(p));
                wall = HAS_WALLS && is_wall(cell);
                sun_texel(wall, cell, p, t);
            }
            vec4 direct = input_texel(u_direct_in, index);
            o_direct.texels[index] = pack_rgba16f(vec4(direct.rgb + t.color, direct.a));
            if (HAS_WALLS) {
                float has_faces = wall ? 1.0 : 0.0; // alpha flags texels holding face light
                uint faces = FACES;         // a face not computed has no texture
                if (UPPER) merge_upper(t, faces, index);
                if (computes_face(faces, 0))
                    o_face_px.texels[index] = pack_rgba16f(vec4(input_texel(u_face_px_in, index).rgb + t.face[0], has_faces));
                if (computes_face(faces, 1))
                    o_face_nx.texels[index] = pack_rgba16f(vec4(input_texel(u_face_nx_in, index).rgb + t.face[1], has_faces));
                if (computes_face(faces, 2))
                    o_face_pz.texels[index] = pack_rgba16f(vec4(input_texel(u_face_pz_in, index).rgb + t.face[2], has_faces));
                if (computes_face(faces, 3))
                    o_face_nz.texels[index] = pack_rgba16f(vec4(input_texel(u_face_nz_in, index).rgb + t.face[3], has_faces));
            }
            shadow[k] = vec2(input_texel(u_shadow_in, index).r, wall ? 0.0 : t.shadow);
        }
        o_shadow.texels[texel_index(o.x, y) / 4] = uvec2(pack_rg8x2(shadow[0], shadow[1]), pack_rg8x2(shadow[2], shadow[3]));
    }
}
