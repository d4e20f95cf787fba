// The radiosity method's distance field (seed 003's jump flood), on the radiosity grid, in
// three modes (FEATURES): 0 seed (wall texels hold their own coordinate, 16 bits per axis:
// the seed's two-byte encoding), 1 one pass (the 3x3 neighbourhood at pc.pass.offset; the
// first nearest wins), 2 finish (distance and direction to the nearest wall texel, and the
// fixed-point steps the raymarch takes). Mirrors engine/gi/src/radiosity.cpp.
// camera_view.xy = grid origin; size = grid (w, h, pitch, -); parameters: JumpFloodParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct JumpFloodParams {
    float texels_per_unit; // grid texels per world unit
    int offset;            // mode 1: this pass's offset
    int pad0, pad1, pad2, pad3, pad4, pad5;
};
#define GI_PASS_PARAMS JumpFloodParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(binding = 2) uniform usamplerBuffer u_jfa;                    // modes 1, 2
layout(std430, binding = 3) writeonly buffer Out { uint words[]; } o_jfa; // modes 0, 1: jfa; 2: distance steps
layout(std430, binding = 4) writeonly buffer Field { uvec2 texels[]; } o_field; // mode 2

#include "lantern/gi_shadow.glsl"

const uint NONE = 0xFFFFFFFFu;
const uint MODE = FEATURES;

uint pack_coord(int x, int y) { return uint(x) | (uint(y) << 16); }
ivec2 unpack_coord(uint v) { return ivec2(int(v & 0xFFFFu), int(v >> 16)); }

// floor(256 sqrt(d2)) clamped to 65535, in exact integer arithmetic (radiosity.cpp).
uint distance_steps_of(uint d2) {
    if (d2 > 65535u) return 65535u;
    uint v = d2 * 65536u;
    uint s = uint(sqrt(float(v)));
    if (s * s > v) --s;
    if (s < 65535u && (s + 1u) * (s + 1u) <= v) ++s;
    return min(s, 65535u);
}

uint seed(int x, int y) {
    vec2 c = grid_texel_center(x, y, pc.pass.texels_per_unit);
    return is_wall(ivec2(floor(c))) ? pack_coord(x, y) : NONE;
}

uint flood(int x, int y) {
    int k = pc.pass.offset;
    uint best = NONE;
    int best_d2 = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int sx = x + dx * k, sy = y + dy * k;
            if (sx < 0 || sy < 0 || sx >= pc.size.x || sy >= pc.size.y) continue;
            uint v = texelFetch(u_jfa, texel_index(sx, sy)).r;
            if (v == NONE) continue;
            ivec2 c = unpack_coord(v);
            int d2 = (c.x - x) * (c.x - x) + (c.y - y) * (c.y - y);
            if (best == NONE || d2 < best_d2) {
                best = v;
                best_d2 = d2;
            }
        }
    return best;
}

void finish(int x, int y) {
    uint v = texelFetch(u_jfa, texel_index(x, y)).r;
    vec4 field = vec4(65504.0, 0.0, 0.0, 0.0);
    uint steps = 65535u;
    if (v != NONE) {
        ivec2 c = unpack_coord(v);
        int dx = c.x - x, dy = c.y - y;
        uint d2 = uint(dx * dx + dy * dy);
        float len = sqrt(float(d2));
        field = d2 == 0u ? vec4(0.0) : vec4(len, float(dx) / len, float(dy) / len, 0.0);
        steps = distance_steps_of(d2);
    }
    o_field.texels[texel_index(x, y)] = pack_rgba16f(field);
    o_jfa.words[texel_index(x, y)] = steps;
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            if (x >= pc.size.x) break;
            if (MODE == 0u) o_jfa.words[texel_index(x, y)] = seed(x, y);
            else if (MODE == 1u) o_jfa.words[texel_index(x, y)] = flood(x, y);
            else finish(x, y);
        }
    }
}
