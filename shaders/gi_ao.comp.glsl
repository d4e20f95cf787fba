// Ambient occlusion (r8): the distance-weighted share of wall tiles within the AO radius.
// The weights come from the host (AoKernel: per position inside a tile, per neighbour tile);
// an invocation loads the wall pattern around its tile once and sums the weights of the
// walls in it. Parameters: AoParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct AoParams {
    float radius, power; // the kernel's shape (the weights come from the host)
    float strength;      // how dark full occlusion is
    float dither;        // 1: ordered dithering before the 8-bit store
    int range;           // ceil(radius): neighbour tiles each way
    int offset;          // the dispatch's first texel, x | y << 16 (a scrolled window's new strips; x a multiple of 4)
    int pad1, pad2;
};
#define GI_PASS_PARAMS AoParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(binding = 2) uniform samplerBuffer u_kernel; // weights, then totals (R32_SFLOAT)
layout(std430, binding = 3) writeonly buffer Out { uint texels[]; } o_ao;

#include "lantern/gi_shadow.glsl"

const float BAYER4[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);
const int MAX_WORDS = 10; // (2 * 8 + 1)^2 = 289 neighbour bits for radius 8

uint g_walls[MAX_WORDS];
ivec2 g_tile = ivec2(0x7FFFFFFF);

void load_walls(ivec2 tile, int range) {
    if (tile == g_tile) return;
    g_tile = tile;
    int span = 2 * range + 1;
    for (int w = 0; w < (span * span + 31) >> 5; ++w) g_walls[w] = 0u;
    for (int dy = -range; dy <= range; ++dy)
        for (int dx = -range; dx <= range; ++dx)
            if (is_wall(tile.x + dx, tile.y + dy)) {
                int bit = (dy + range) * span + dx + range;
                g_walls[bit >> 5] |= 1u << uint(bit & 31);
            }
}

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

float ao_texel(int x, int y) {
    int res = pc.size.w, range = pc.pass.range;
    int taps = (2 * range + 1) * (2 * range + 1);
    // The tile and the position in it from the global texel index (window_texel_origin):
    // the origin is a whole texel, a whole tile only when gi.window_snap is "tile".
    ivec2 g = ivec2(int(round(pc.camera_view.x * float(res))), int(round(pc.camera_view.y * float(res)))) + ivec2(x, y);
    ivec2 tile = ivec2(floor_div(g.x, res), floor_div(g.y, res));
    load_walls(tile, range);
    int sub = (g.y - tile.y * res) * res + (g.x - tile.x * res);
    float occluded = 0.0;
    int words = (taps + 31) >> 5;
    for (int w = 0; w < words; ++w) {
        uint bits = g_walls[w];
        while (bits != 0u) { // ascending neighbour order, as the reference sums
            int bit = findLSB(bits);
            bits &= bits - 1u;
            occluded += texelFetch(u_kernel, sub * taps + w * 32 + bit).r;
        }
    }
    float total = texelFetch(u_kernel, res * res * taps + sub).r;
    float occlusion = total > 0.0 ? occluded / total : 0.0;
    float value = 1.0 - saturate(pc.pass.strength) * occlusion;
    if (pc.pass.dither > 0.5) value += ((BAYER4[(y & 3) * 4 + (x & 3)] + 0.5) / 16.0 - 0.5) / 255.0;
    return value;
}

void main() {
    ivec2 o = block_origin() + ivec2(pc.pass.offset & 0xFFFF, pc.pass.offset >> 16);
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        vec4 v = vec4(0.0);
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            if (x < pc.size.x) v[k] = ao_texel(x, y);
        }
        o_ao.texels[texel_index(o.x, y) / 4] = pack_r8x4(v);
    }
}
