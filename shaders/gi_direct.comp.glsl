// Direct light from point lights (DDA-shadowed, proxy-shadowed) and emissives (no
// shadows, no cap): ground colour (rgba16f), shadow map R (rg8), and per-face wall light
// (4 x rgba16f) on wall texels. Each workgroup visits only the lights gi_light_bins listed
// for its footprint. Parameters: DirectParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct DirectParams {
    float light_softness; // falloff exponent (gi.light_softness)
    float face_exponent;  // gi.wall_face_exponent
    int pad_f;            // (the faces computed are FACES, a specialisation constant)
    float wall_height;    // unfolded proxy shadows: the face's height
    int pad0, pad1, pad2, pad3;
};
#define GI_PASS_PARAMS DirectParams
#include "lantern/gi_common.glsl"

const bool UPPER = (FEATURES & 1u) != 0u; // unfolded proxy shadows: write the upper-face textures

layout(constant_id = 4) const int MAX_LIGHTS = 2048; // point lights + emissives (64 KiB UBO)

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[256]; } u_proxies;
layout(std140, binding = 2) uniform LightBlock { GpuPointLight lights[MAX_LIGHTS]; } u_lights;
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

#include "lantern/gi_shadow.glsl"

#include "lantern/gi_texel_light.glsl"

float light_distance(vec2 p, vec2 pos) {
    precise vec2 d = pos - p;
    precise float dist = sqrt(d.x * d.x + d.y * d.y);
    return dist;
}

vec4 face_weights(vec4 mask, vec2 p, vec2 light_pos) {
    precise vec2 to_light = light_pos - p;
    precise float inv_len = 1.0 / sqrt(max(to_light.x * to_light.x + to_light.y * to_light.y, 1e-6));
    return mask * wall_facing(to_light * inv_len, pc.pass.face_exponent);
}

// The lights this workgroup's bin lists, in ascending order: point lights first.
int g_bin_base;
int g_bin_words;

#define FOR_EACH_BIN_LIGHT(i)                                                                   \
    for (int w_ = 0; w_ < g_bin_words; ++w_)                                                    \
        for (uint bits_ = u_bins.masks[g_bin_base + w_]; bits_ != 0u; bits_ &= bits_ - 1u)      \
            for (int i = w_ * 32 + findLSB(bits_), once_ = 1; once_ == 1; once_ = 0)

void point_wall_light(int i, ivec2 cell, vec2 p, vec4 mask, float softness, inout TexelLight t) {
        GpuPointLight l = u_lights.lights[i];
        vec2 pos = l.position_radius.xy;
        float radius = l.position_radius.z;
        float dist = light_distance(p, pos);
        if (dist > radius) return;
        vec4 weight = face_weights(mask, p, pos);
        if (weight == vec4(0.0)) return;
        vec3 contribution = l.color.rgb * light_falloff(dist, radius, softness);
        for (int f = 0; f < 4; ++f) {
            if (!(weight[f] > 0.0)) continue;
            vec2 target = face_position(f, cell, p);
            if (UPPER) {
                add_face(t, f, contribution * weight[f], shadow_dda(pos, target, radius),
                         point_proxy_face_shadow(pos, target, pc.pass.wall_height));
                continue;
            }
            float shadow = min(shadow_dda(pos, target, radius), point_proxy_shadow(pos, target));
            t.face[f] += contribution * (weight[f] * shadow);
        }
}

void emissive_wall_light(int i, vec2 p, vec4 mask, float softness, inout TexelLight t) {
        GpuPointLight l = u_lights.lights[i];
        vec2 pos = l.position_radius.xy;
        float radius = l.position_radius.z;
        float dist = light_distance(p, pos);
        if (dist > radius) return;
        vec3 contribution = l.color.rgb * light_falloff(dist, radius, softness);
        vec4 weight = face_weights(mask, p, pos);
        for (int f = 0; f < 4; ++f) {
            t.face[f] += contribution * weight[f];
            t.upper[f] += contribution * weight[f];
        }
}

void wall_texel(ivec2 cell, vec2 p, inout TexelLight t) {
    vec4 mask = wall_face_mask(cell) * face_bits_mask(FACES);
    float softness = pc.pass.light_softness;
    FOR_EACH_BIN_LIGHT(i) {
        if (i < pc.counts.x) point_wall_light(i, cell, p, mask, softness, t);
        else emissive_wall_light(i, p, mask, softness, t);
    }
}

void ground_texel(vec2 p, inout TexelLight t) {
    float softness = pc.pass.light_softness;
    FOR_EACH_BIN_LIGHT(i) {
        GpuPointLight l = u_lights.lights[i];
        vec2 pos = l.position_radius.xy;
        float radius = l.position_radius.z;
        float dist = light_distance(p, pos);
        if (dist > radius) continue;
        if (i < pc.counts.x) {
            float shadow = min(shadow_dda(pos, p, radius), point_proxy_shadow(pos, p));
            t.shadow = max(t.shadow, shadow);
            t.color += l.color.rgb * light_falloff(dist, radius, softness) * shadow;
        } else {
            t.color += l.color.rgb * light_falloff(dist, radius, softness);
        }
    }
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    g_bin_words = (pc.counts.x + pc.counts.y + 31) >> 5;
    g_bin_base = int(gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * g_bin_words;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        vec2 shadow[4];
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            TexelLight t = no_texel_light();
            bool wall = false;
            if (x < pc.size.x) {
                vec2 p = texel_center(x, y);
                ivec2 cell = ivec2(floor(p));
                wall = HAS_WALLS && is_wall(cell);
                if (!wall) ground_texel(p, t);
                else if (FACES != 0u) wall_texel(cell, p, t); // a wall's ground light is 0
            }
            int index = texel_index(x, y);
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
            shadow[k] = vec2(wall ? 0.0 : t.shadow, 0.0);
        }
        o_shadow.texels[texel_index(o.x, y) / 4] = uvec2(pack_rg8x2(shadow[0], shadow[1]), pack_rg8x2(shadow[2], shadow[3]));
    }
}
