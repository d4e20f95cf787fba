// Wall indirect: each exposed face of a wall texel takes the indirect light of the texel
// one world unit across that face (clamped to the window); ground texels stay zero.
// The faces computed are FACES (a specialisation constant). FEATURES bit 0: every block lies
// in one wall tile (window.hpp blocks_in_one_tile), whose wall bit and exposed faces are
// looked up once per block instead of once per texel. Bit 1: invocation i computes block
// u_blocks.blocks[i] (x | y << 16, in blocks of 4 x BLOCK_H texels), i < `blocks`, and the
// others keep what they hold (the blocks holding a wall texel, when the others hold the
// zeros of an earlier run over the same window and walls: rows::wall_blocks).
#version 450
#extension GL_GOOGLE_include_directive : require
struct WallIndirectParams {
    int blocks; // BLOCKS: how many blocks are listed
    int unused1, unused2, unused3, unused4, unused5, unused6, unused7;
};
#define GI_PASS_PARAMS WallIndirectParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(binding = 2) uniform samplerBuffer u_indirect;
layout(std430, binding = 3) writeonly buffer FacePX { uvec2 texels[]; } o_face_px;
layout(std430, binding = 4) writeonly buffer FaceNX { uvec2 texels[]; } o_face_nx;
layout(std430, binding = 5) writeonly buffer FacePZ { uvec2 texels[]; } o_face_pz;
layout(std430, binding = 6) writeonly buffer FaceNZ { uvec2 texels[]; } o_face_nz;
layout(std430, binding = 7) readonly buffer Blocks { uint blocks[]; } u_blocks; // BLOCKS

#include "lantern/gi_shadow.glsl"

const vec2 ACROSS[4] = vec2[4](vec2(1, 0), vec2(-1, 0), vec2(0, 1), vec2(0, -1));

vec4 face_value(int f, vec4 mask, vec2 p) {
    if (!(mask[f] > 0.0)) return vec4(0.0, 0.0, 0.0, 1.0);
    vec2 q = p + ACROSS[f];
    float res = float(pc.size.w);
    int sx = clamp(int(floor((q.x - pc.camera_view.x) * res)), 0, pc.size.x - 1);
    int sy = clamp(int(floor((q.y - pc.camera_view.y) * res)), 0, pc.size.y - 1);
    return vec4(texelFetch(u_indirect, texel_index(sx, sy)).rgb, 1.0);
}

const bool BLOCK_TILE = (FEATURES & 1u) != 0u;
const bool BLOCKS = (FEATURES & 2u) != 0u;

void main() {
    ivec2 o = block_origin();
    if (BLOCKS) {
        uint i = listed_block_index();
        if (i >= uint(pc.pass.blocks)) return;
        o = listed_block_origin(u_blocks.blocks[i]);
    }
    if (o.x >= pc.size.x) return;
    ivec2 block_cell = ivec2(floor(texel_center(o.x, o.y)));
    bool block_wall = BLOCK_TILE && is_wall(block_cell);
    vec4 block_mask = block_wall ? wall_face_mask(block_cell) * face_bits_mask(FACES) : vec4(0.0);
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            int index = texel_index(x, y);
            vec4 v[4] = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
            if (x < pc.size.x) {
                vec2 p = texel_center(x, y);
                ivec2 cell = ivec2(floor(p));
                if (BLOCK_TILE ? block_wall : is_wall(cell)) {
                    vec4 mask = BLOCK_TILE ? block_mask : wall_face_mask(cell) * face_bits_mask(FACES);
                    for (int f = 0; f < 4; ++f) v[f] = face_value(f, mask, p);
                }
            }
            uint faces = FACES; // a face not computed has no texture
            if (computes_face(faces, 0)) o_face_px.texels[index] = pack_rgba16f(v[0]);
            if (computes_face(faces, 1)) o_face_nx.texels[index] = pack_rgba16f(v[1]);
            if (computes_face(faces, 2)) o_face_pz.texels[index] = pack_rgba16f(v[2]);
            if (computes_face(faces, 3)) o_face_nz.texels[index] = pack_rgba16f(v[3]);
        }
    }
}
