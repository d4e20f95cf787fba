// The gather method (lantern/gi/gather.hpp; mirrors engine/gi/src/gather.cpp step for step:
// integer tile crossings, the same rays, the same sums in the same order). Three modes
// (FEATURES & 3):
//   0 face bounce: every exposed face texel of the window gathers E_indirect from B =
//     albedo x (direct + previous) + emission of the faces its rays hit (their tiles' materials); writes the face texture
//     (face f of texel (x, y) at (x, f x height + y)); FEATURES & 4: a previous bounce exists
//   1 fill: wall_indirect_* from the face texture, across each wall tile
//   2 ground: fluence on the gather grid from B = albedo x (direct + indirect) + emission
// Modes 0 and 2 run over a list of the texels that have work (u_list: exposed face texels
// with their face, or the gather grid's texels in air), laid out LIST_WIDTH entries a row so
// that no invocation idles on a texel without work (lavapipe runs masked code for every lane);
// their outputs were cleared before. size: the list's rows (modes 0, 2) or the window (1);
// parameters: GatherParams (engine/gi/src/rows/gather.cpp).
#version 450
#extension GL_GOOGLE_include_directive : require
struct GatherParams {
    int origin_x, origin_z; // the window's origin tile (absolute)
    int offset;             // window texels from that tile's corner: x | y << 8 | resolution << 16
    int tiles;              // tiles the window touches: x | y << 16
    int rays;               // rays per texel (face rays in mode 0)
    int noise;              // window texel 0's blue-noise coordinate x | y << 8 | grid scale << 16
    int window;             // window texels: width | height << 16
    int pad;
};
#define GI_PASS_PARAMS GatherParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(binding = 2) uniform samplerBuffer u_direct_px;
layout(binding = 3) uniform samplerBuffer u_direct_nx;
layout(binding = 4) uniform samplerBuffer u_direct_pz;
layout(binding = 5) uniform samplerBuffer u_direct_nz;
layout(binding = 6) uniform samplerBuffer u_faces;       // E_indirect per face texel (previous bounce)
layout(binding = 7) uniform isamplerBuffer u_directions; // 4096 x (cos, sin) x 4096
layout(binding = 8) uniform usamplerBuffer u_noise;      // 64 x 64 blue-noise ranks
layout(std430, binding = 9) writeonly buffer Out0 { uvec2 texels[]; } o_out0; // faces / ground / wall_indirect_px
layout(std430, binding = 10) writeonly buffer Out1 { uvec2 texels[]; } o_out1; // wall_indirect_nx
layout(std430, binding = 11) writeonly buffer Out2 { uvec2 texels[]; } o_out2; // wall_indirect_pz
layout(std430, binding = 12) writeonly buffer Out3 { uvec2 texels[]; } o_out3; // wall_indirect_nz
layout(binding = 13) uniform usamplerBuffer u_list; // modes 0, 2: x | y << 16, face (or 0); rows padded with ~0
layout(binding = 14) uniform samplerBuffer u_materials; // per wall cell value: albedo, emission (frame_inputs.hpp material_table)

#include "lantern/gi_shadow.glsl"

const int LIST_WIDTH = 256; // entries per row of the list (rows/gather.cpp gather_list_width)
const float PI = 3.14159265;
const uint MODE = FEATURES & 3u;
const bool HAS_PREVIOUS = (FEATURES & 4u) != 0u;
const int NORMAL_INDEX[4] = int[4](0, 2048, 1024, 3072);
const ivec2 NORMAL[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));

#include "lantern/gi_gather_trace.glsl"

int blue_noise_at(int x, int y) {
    int nx = (x + (pc.pass.noise & 255)) & 63, ny = (y + ((pc.pass.noise >> 8) & 255)) & 63;
    return int(texelFetch(u_noise, ny * 64 + nx).r);
}

int texel_center_fixed(int i_with_offset, int span, int r) { return ((2 * i_with_offset + span) * UNIT) / (2 * r); }

vec3 direct_at(int face, ivec2 t) {
    int i = window_index(t.x, t.y);
    if (face == 0) return computes_face(FACES, 0) ? texelFetch(u_direct_px, i).rgb : vec3(0.0);
    if (face == 1) return computes_face(FACES, 1) ? texelFetch(u_direct_nx, i).rgb : vec3(0.0);
    if (face == 2) return computes_face(FACES, 2) ? texelFetch(u_direct_pz, i).rgb : vec3(0.0);
    return computes_face(FACES, 3) ? texelFetch(u_direct_nz, i).rgb : vec3(0.0);
}
// B = albedo x (direct + indirect) + emission, by the material of t's tile.
vec3 radiosity_at(int face, ivec2 t, bool with_faces) {
    vec3 e = direct_at(face, t);
    if (with_faces) e += texelFetch(u_faces, window_index(t.x, face * window_size().y + t.y)).rgb;
    ivec2 tile = origin_tile() + (offset() + t) / resolution();
    int cell = int(wall_cell(tile.x, tile.y));
    precise vec3 b = texelFetch(u_materials, 2 * cell).rgb * e + texelFetch(u_materials, 2 * cell + 1).rgb;
    return b;
}

bool face_texel(int x, int y, int face) {
    int r = resolution();
    ivec2 g = offset() + ivec2(x, y);
    ivec2 tile = origin_tile() + g / r;
    if (!is_wall(tile)) return false;
    bool edge = face == 0 ? g.x % r == r - 1 : face == 1 ? g.x % r == 0 : face == 2 ? g.y % r == r - 1 : g.y % r == 0;
    return edge && !is_wall(tile + NORMAL[face]);
}

// Mode 0: E_indirect of face `face` at window texel (x, y), an exposed face texel.
vec3 face_bounce(int x, int y, int face) {
    int r = resolution();
    ivec2 g = offset() + ivec2(x, y);
    ivec2 cell = g / r, p;
    if (face < 2) {
        p = ivec2((cell.x + (face == 0 ? 1 : 0)) * UNIT, texel_center_fixed(g.y, 1, r));
        cell.x += NORMAL[face].x;
    } else {
        p = ivec2(texel_center_fixed(g.x, 1, r), (cell.y + (face == 2 ? 1 : 0)) * UNIT);
        cell.y += NORMAL[face].y;
    }
    int rays = pc.pass.rays;
    int base = NORMAL_INDEX[face] - 1024, noise = blue_noise_at(x, y) / 2;
    vec3 sum = vec3(0.0);
    for (int k = 0; k < rays; ++k) {
        ivec2 d = texelFetch(u_directions, (base + (k * 2048 + noise) / rays) & 4095).xy;
        int cosine = d.x * NORMAL[face].x + d.y * NORMAL[face].y;
        if (cosine <= 0) continue;
        ivec2 texel;
        int hit = trace(p, cell, d, texel);
        if (hit < 0) continue;
        sum += radiosity_at(hit, texel, HAS_PREVIOUS) * float(cosine);
    }
    return sum * (PI / (2.0 * 4096.0 * float(rays)));
}

// Mode 1: face `face` of window texel (x, y) from its tile's edge texel.
vec3 fill(int x, int y, int face) {
    int r = resolution();
    ivec2 g = offset() + ivec2(x, y);
    ivec2 e = ivec2(x, y);
    if (face == 0) e.x = x + (r - 1 - g.x % r);
    if (face == 1) e.x = x - g.x % r;
    if (face == 2) e.y = y + (r - 1 - g.y % r);
    if (face == 3) e.y = y - g.y % r;
    ivec2 size = window_size();
    if (e.x < 0 || e.y < 0 || e.x >= size.x || e.y >= size.y || !face_texel(e.x, e.y, face)) return vec3(0.0);
    return texelFetch(u_faces, window_index(e.x, face * size.y + e.y)).rgb;
}

// Mode 2: fluence at gather-grid texel (i, j), whose centre is in air.
vec3 ground(int i, int j) {
    int r = resolution(), scale = pc.pass.noise >> 16;
    ivec2 off = offset();
    ivec2 p = ivec2(texel_center_fixed(off.x + i * scale, scale, r), texel_center_fixed(off.y + j * scale, scale, r));
    ivec2 cell = p / UNIT;
    vec3 sum = vec3(0.0);
    int rays = pc.pass.rays;
    int noise = blue_noise_at(i * scale, j * scale);
    for (int k = 0; k < rays; ++k) {
        ivec2 d = texelFetch(u_directions, ((k * 4096 + noise) / rays) & 4095).xy;
        ivec2 texel;
        int hit = trace(p, cell, d, texel);
        if (hit >= 0) sum += radiosity_at(hit, texel, true);
    }
    return sum * (PI / float(rays));
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint rr = 0; rr < BLOCK_H; ++rr) {
        int y = o.y + int(rr);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            int index = texel_index(x, y);
            if (MODE != 1u) { // a list entry
                uvec2 e = texelFetch(u_list, y * LIST_WIDTH + x).xy;
                if (e.x == 0xFFFFFFFFu) return; // the padding after the last entry
                int tx = int(e.x & 0xFFFFu), ty = int(e.x >> 16);
                if (MODE == 0u) {
                    int f = int(e.y);
                    vec3 v = face_bounce(tx, ty, f);
                    o_out0.texels[window_index(tx, f * window_size().y + ty)] = pack_rgba16f(vec4(v, 1.0));
                } else {
                    int scale = pc.pass.noise >> 16;
                    int grid_w = (window_size().x + scale - 1) / scale;
                    o_out0.texels[ty * ((grid_w + 3) & ~3) + tx] = pack_rgba16f(vec4(ground(tx, ty), 1.0));
                }
            } else {
                vec3 v[4] = vec3[4](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
                if (x < pc.size.x)
                    for (int f = 0; f < 4; ++f)
                        if (computes_face(FACES, f)) v[f] = fill(x, y, f);
                if (computes_face(FACES, 0)) o_out0.texels[index] = pack_rgba16f(vec4(v[0], 1.0));
                if (computes_face(FACES, 1)) o_out1.texels[index] = pack_rgba16f(vec4(v[1], 1.0));
                if (computes_face(FACES, 2)) o_out2.texels[index] = pack_rgba16f(vec4(v[2], 1.0));
                if (computes_face(FACES, 3)) o_out3.texels[index] = pack_rgba16f(vec4(v[3], 1.0));
            }
        }
    }
}
