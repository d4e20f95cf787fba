// Directional lights (sun, moon): traversal towards the light with the wall-height test,
// into the direct colour and wall faces; writes shadow map G (max visibility). The
// directional row lights the realtime suns into their own textures (the direct pass adds
// them); the mixed row the mixed suns into theirs (FEATURES & 64; the baked pass adds them).
// Nothing is read: every output starts from zero.
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
// The mixed suns (the mixed row), else the realtime ones (frame_inputs.hpp is_mixed_sun:
// bounce.y != 0).
const bool MIXED_SUNS = (FEATURES & 64u) != 0u;
const bool LINEAR_FACES = (FEATURES & 256u) != 0u; // gi.wall_face_exponent 1: no pow (wall_facing)

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[256]; } u_proxies;
layout(std140, binding = 2) uniform SunBlock { GpuDirectionalLight suns[8]; } u_suns;
layout(std430, binding = 3) writeonly buffer DirectOut { uvec2 texels[]; } o_direct;
layout(std430, binding = 4) writeonly buffer ShadowOut { uvec2 texels[]; } o_shadow;
layout(std430, binding = 5) writeonly buffer FacePX { uvec2 texels[]; } o_face_px;
layout(std430, binding = 6) writeonly buffer FaceNX { uvec2 texels[]; } o_face_nx;
layout(std430, binding = 7) writeonly buffer FacePZ { uvec2 texels[]; } o_face_pz;
layout(std430, binding = 8) writeonly buffer FaceNZ { uvec2 texels[]; } o_face_nz;
layout(binding = 9) uniform samplerBuffer u_sun_headers; // gi_sun_map.glsl
layout(binding = 10) uniform usamplerBuffer u_sun_first;
layout(binding = 11) uniform samplerBuffer u_sun_entries;
layout(std430, binding = 12) writeonly buffer UpperPX { uvec2 texels[]; } o_upper_px;
layout(std430, binding = 13) writeonly buffer UpperNX { uvec2 texels[]; } o_upper_nx;
layout(std430, binding = 14) writeonly buffer UpperPZ { uvec2 texels[]; } o_upper_pz;
layout(std430, binding = 15) writeonly buffer UpperNZ { uvec2 texels[]; } o_upper_nz;
layout(std430, binding = 16) readonly buffer SunProxyBins { uint masks[]; } u_sun_proxy_bins;

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
        vec4 weight = len < 1e-4 ? vec4(0.0) : mask * wall_facing(gi_div(to_sun, max(len, 1e-4)), pc.pass.face_exponent, LINEAR_FACES);
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

// The suns' upper-face light and the height where their proxies' shadows end
// (reference_passes.cpp reference_directional, onto zero textures).
void write_upper(inout TexelLight t, uint faces, int index) {
    if (computes_face(faces, 0)) o_upper_px.texels[index] = pack_rgba16f(vec4(t.upper[0], face_edge(t, 0)));
    if (computes_face(faces, 1)) o_upper_nx.texels[index] = pack_rgba16f(vec4(t.upper[1], face_edge(t, 1)));
    if (computes_face(faces, 2)) o_upper_pz.texels[index] = pack_rgba16f(vec4(t.upper[2], face_edge(t, 2)));
    if (computes_face(faces, 3)) o_upper_nz.texels[index] = pack_rgba16f(vec4(t.upper[3], face_edge(t, 3)));
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
            o_direct.texels[index] = pack_rgba16f(vec4(t.color, 0.0));
            if (HAS_WALLS) {
                float has_faces = wall ? 1.0 : 0.0; // alpha flags texels holding face light
                uint faces = FACES;         // a face not computed has no texture
                if (UPPER) write_upper(t, faces, index);
                if (computes_face(faces, 0)) o_face_px.texels[index] = pack_rgba16f(vec4(t.face[0], has_faces));
                if (computes_face(faces, 1)) o_face_nx.texels[index] = pack_rgba16f(vec4(t.face[1], has_faces));
                if (computes_face(faces, 2)) o_face_pz.texels[index] = pack_rgba16f(vec4(t.face[2], has_faces));
                if (computes_face(faces, 3)) o_face_nz.texels[index] = pack_rgba16f(vec4(t.face[3], has_faces));
            }
            shadow[k] = vec2(0.0, wall ? 0.0 : t.shadow);
        }
        o_shadow.texels[texel_index(o.x, y) / 4] = uvec2(pack_rg8x2(shadow[0], shadow[1]), pack_rg8x2(shadow[2], shadow[3]));
    }
}
