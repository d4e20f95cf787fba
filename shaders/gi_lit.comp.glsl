// The lit image of the GI window seen from above (rgba8, sRGB): ground, wall tops, and a
// band of wall faces along each exposed edge, shaded by the shading library.
// Parameters: LitParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct LitParams {
    float wall_height;
    uint present;      // bit t: GI texture t is bound (else absent, read as nothing)
    int tone_map;      // scene::ToneMap
    float white_point;
    float angle_scale; // gi.directional_angle_scale
    int pad_f;            // (the faces computed are FACES, a specialisation constant)
    float wall_lighting, ao_walls; // gi_shading.options x, y

};
#define GI_PASS_PARAMS LitParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(std140, binding = 2) uniform SunBlock { GpuDirectionalLight suns[8]; } u_suns;
layout(binding = 3) uniform samplerBuffer u_direct;
layout(binding = 4) uniform samplerBuffer u_indirect;
layout(binding = 5) uniform samplerBuffer u_ao;
layout(binding = 6) uniform samplerBuffer u_shadow;
layout(binding = 7) uniform samplerBuffer u_wall_direct_px;
layout(binding = 8) uniform samplerBuffer u_wall_direct_nx;
layout(binding = 9) uniform samplerBuffer u_wall_direct_pz;
layout(binding = 10) uniform samplerBuffer u_wall_direct_nz;
layout(binding = 11) uniform samplerBuffer u_wall_indirect_px;
layout(binding = 12) uniform samplerBuffer u_wall_indirect_nx;
layout(binding = 13) uniform samplerBuffer u_wall_indirect_pz;
layout(binding = 14) uniform samplerBuffer u_wall_indirect_nz;
layout(std430, binding = 15) writeonly buffer Out { uint texels[]; } o_lit;
layout(binding = 16) uniform samplerBuffer u_wall_upper_px;
layout(binding = 17) uniform samplerBuffer u_wall_upper_nx;
layout(binding = 18) uniform samplerBuffer u_wall_upper_pz;
layout(binding = 19) uniform samplerBuffer u_wall_upper_nz;

#include "lantern/gi_shadow.glsl"
#include "lantern/shading.glsl"
#include "lantern/gi_texture_fetch.glsl"

bool gi_has(int t) { return ((pc.pass.present >> uint(t)) & 1u) != 0u; }
vec4 gi_fetch(int t, ivec2 texel) { return gi_texture_fetch(t, texel_index(texel.x, texel.y)); }
bool gi_wall_tile(ivec2 tile) { return is_wall(tile); }
int gi_sun_count() { return pc.counts.z; }
GpuDirectionalLight gi_sun(int i) { return u_suns.suns[i]; }

// The surface the top-down image shows at a texel (engine/gi/src/shading.cpp lit_surface_at).
void lit_surface_at(int x, int y, out vec3 pos, out vec3 normal) {
    vec2 p = texel_center(x, y);
    ivec2 cell = ivec2(floor(p));
    pos = vec3(p.x, 0.0, p.y);
    normal = vec3(0.0, 1.0, 0.0);
    if (!is_wall(cell)) return;
    float wall_height = pc.pass.wall_height;
    pos.y = wall_height;
    int res = pc.size.w;
    int lx = int(floor((p.x - float(cell.x)) * float(res))), lz = int(floor((p.y - float(cell.y)) * float(res)));
    int band = max(1, res / 4);
    vec4 mask = wall_face_mask(cell) * face_bits_mask(FACES);
    int distance[4] = int[4](res - 1 - lx, lx, res - 1 - lz, lz);
    const vec3 normals[4] = vec3[4](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 0, 1), vec3(0, 0, -1));
    int best = -1;
    for (int face = 0; face < 4; ++face)
        if (mask[face] > 0.0 && distance[face] < band && (best < 0 || distance[face] < distance[best])) best = face;
    if (best >= 0) {
        normal = normals[best];
        pos.y = wall_height * 0.5;
    }
}

uint srgb8(float v) { return uint(floor(linear_to_srgb(v) * 255.0 + 0.5)); }

void main() {
    gi_shading.window = vec4(pc.camera_view.xy, float(pc.size.x), float(pc.size.y));
    gi_shading.config = vec4(float(pc.size.w), float(pc.pass.tone_map), pc.pass.white_point, pc.pass.angle_scale);
    gi_shading.options = vec4(pc.pass.wall_lighting, pc.pass.ao_walls, 0.0, 0.0);
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            uint packed = 0u;
            if (x < pc.size.x) {
                vec3 pos, n;
                lit_surface_at(x, y, pos, n);
                vec3 c = shade(pos, n);
                packed = srgb8(c.r) | (srgb8(c.g) << 8) | (srgb8(c.b) << 16) | (255u << 24);
            }
            o_lit.texels[texel_index(x, y)] = packed;
        }
    }
}
