// Live light probes (lantern/gi/probes.hpp; mirrors engine/gi/src/probes.cpp step for step:
// the gather's integer rays, the same floats summed in the same order). Probe (i, j) stands
// at the centre of tile first + 2 (i, j) from the window's origin tile; its rays bring back
// the radiance B / 2 of the first wall face they enter, B = albedo x (wall_direct +
// wall_indirect) + emission of the face's tile, projected on circular harmonics of order 2.
// Writes five RGBA16F texels a probe (a0, a1, b1, a2, b2; a0's alpha: 1 in open ground).
// size: the probe grid, z the texture's pitch; parameters: ProbeParams (engine/gi/src/rows/probes.cpp).
#version 450
#extension GL_GOOGLE_include_directive : require
struct ProbeParams {
    int origin_x, origin_z; // the window's origin tile (absolute)
    int offset;             // window texels from that tile's corner: x | y << 8 | resolution << 16
    int tiles;              // tiles the window touches: x | y << 16
    int window;             // window texels: width | height << 16
    int first;              // the first probe's tile from the origin tile: x | z << 16
    int rays;               // rays per probe (gi.probe_rays)
    float dtheta;           // 2 pi / rays (the host's float: GPUs may divide inexactly)
};
#define GI_PASS_PARAMS ProbeParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(binding = 1) uniform samplerBuffer u_direct_px;
layout(binding = 2) uniform samplerBuffer u_direct_nx;
layout(binding = 3) uniform samplerBuffer u_direct_pz;
layout(binding = 4) uniform samplerBuffer u_direct_nz;
layout(binding = 5) uniform samplerBuffer u_indirect_px;
layout(binding = 6) uniform samplerBuffer u_indirect_nx;
layout(binding = 7) uniform samplerBuffer u_indirect_pz;
layout(binding = 8) uniform samplerBuffer u_indirect_nz;
layout(binding = 9) uniform isamplerBuffer u_directions; // 4096 x (cos, sin) x 4096
layout(binding = 10) uniform samplerBuffer u_materials;  // per wall cell value: albedo, emission
layout(std430, binding = 11) writeonly buffer Out { uvec2 texels[]; } o_probes;

#include "lantern/gi_walls.glsl"

#include "lantern/gi_gather_trace.glsl"

const bool HAS_INDIRECT = (FEATURES & 1u) != 0u; // the wall_indirect_* textures exist

bool computed(int face) { return ((FACES >> uint(face)) & 1u) != 0u; } // computed_faces

// The light arriving at face `face` of window texel t: its direct and indirect parts.
vec3 face_light(int face, ivec2 t) {
    int i = window_index(t.x, t.y);
    vec3 e = vec3(0.0);
    if (face == 0 && computed(0)) e = texelFetch(u_direct_px, i).rgb;
    if (face == 1 && computed(1)) e = texelFetch(u_direct_nx, i).rgb;
    if (face == 2 && computed(2)) e = texelFetch(u_direct_pz, i).rgb;
    if (face == 3 && computed(3)) e = texelFetch(u_direct_nz, i).rgb;
    if (HAS_INDIRECT) {
        if (face == 0 && computed(0)) e += texelFetch(u_indirect_px, i).rgb;
        if (face == 1 && computed(1)) e += texelFetch(u_indirect_nx, i).rgb;
        if (face == 2 && computed(2)) e += texelFetch(u_indirect_pz, i).rgb;
        if (face == 3 && computed(3)) e += texelFetch(u_indirect_nz, i).rgb;
    }
    return e;
}

void capture(int i, int j, int pitch) {
    ivec2 cell = ivec2(pc.pass.first & 0xFFFF, pc.pass.first >> 16) + 2 * ivec2(i, j);
    int base = j * pitch + 5 * i;
    precise vec3 sum[5] = vec3[5](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
    bool open = !is_wall(origin_tile() + cell);
    if (open) {
        ivec2 p = cell * UNIT + UNIT / 2;
        int rays = pc.pass.rays;
        float dtheta = pc.pass.dtheta;
        for (int k = 0; k < rays; ++k) {
            ivec2 d = texelFetch(u_directions, (k * 4096) / rays).xy;
            ivec2 texel;
            int face = trace(p, cell, d, texel);
            if (face < 0) continue;
            ivec2 tile = origin_tile() + (offset() + texel) / resolution();
            int value = int(wall_cell(tile.x, tile.y));
            precise vec3 b = texelFetch(u_materials, 2 * value).rgb * face_light(face, texel) +
                             texelFetch(u_materials, 2 * value + 1).rgb;
            precise vec3 ld = (b * 0.5) * dtheta;
            precise float c = float(d.x) / 4096.0, s = float(d.y) / 4096.0;
            precise float c2 = c * c - s * s, s2 = 2.0 * c * s;
            sum[0] += ld;
            sum[1] += ld * c;
            sum[2] += ld * s;
            sum[3] += ld * c2;
            sum[4] += ld * s2;
        }
    }
    o_probes.texels[base] = pack_rgba16f(vec4(sum[0], open ? 1.0 : 0.0));
    for (int k = 1; k < 5; ++k) o_probes.texels[base + k] = pack_rgba16f(vec4(sum[k], 0.0));
}

// One probe an invocation (BLOCK_H 1, workgroups of 8 x 4 probes: rows/probes.cpp): a
// window's few hundred probes spread over every core, which blocks of 4 x 4 would not.
void main() {
    int i = int(gl_GlobalInvocationID.x), j = int(gl_GlobalInvocationID.y);
    if (i < pc.size.x && j < pc.size.y) capture(i, j, pc.size.z);
}
