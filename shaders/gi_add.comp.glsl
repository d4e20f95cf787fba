// Up to nine textures added to nine others, texel by texel: rgb added with the target's
// alpha kept, or (a pair's write bit) the source copied over the target. The baked pass's
// adds (docs/baked.md, "At run time"): the baked light into the indirect textures, the
// mixed lights' direct light into the direct ones. FEATURES bit k: pair k is used; bit
// 16 + k: pair k copies; bit 15: pairs 0..4 add `scale` x their scaled texture to their
// source first (the bake's pulsing part, by this frame's pulse); bit 14: workgroup i adds
// the texels of workgroup u_groups.groups[i] of the full dispatch's grid (row-major,
// `groups_x` wide), the others being left as they are (the workgroups the mixed lights
// reach: elsewhere their textures hold zeros); bit 13: invocation i adds the texels of block
// u_groups.groups[i] (x | y << 16, in blocks of 4 x BLOCK_H texels), i < `blocks`, the
// others none (the blocks holding a wall texel, for the pairs of wall faces: elsewhere their
// sources are zeros). C++ reference: engine/gi/src/rows/baked.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require

struct AddParams {
    float scale;  // the scaled textures' factor (FrameInputs::baked_pulse)
    int groups_x; // LIST: the full dispatch's workgroups across
    int blocks;   // BLOCKS: how many blocks are listed
    int unused2, unused3, unused4, unused5, unused6;
};
#define GI_PASS_PARAMS AddParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_source0;
layout(binding = 1) uniform samplerBuffer u_source1;
layout(binding = 2) uniform samplerBuffer u_source2;
layout(binding = 3) uniform samplerBuffer u_source3;
layout(binding = 4) uniform samplerBuffer u_source4;
layout(binding = 5) uniform samplerBuffer u_source5;
layout(binding = 6) uniform samplerBuffer u_source6;
layout(binding = 7) uniform samplerBuffer u_source7;
layout(binding = 8) uniform samplerBuffer u_source8;
layout(std430, binding = 9) buffer Target0 { uvec2 texels[]; } io_target0;
layout(std430, binding = 10) buffer Target1 { uvec2 texels[]; } io_target1;
layout(std430, binding = 11) buffer Target2 { uvec2 texels[]; } io_target2;
layout(std430, binding = 12) buffer Target3 { uvec2 texels[]; } io_target3;
layout(std430, binding = 13) buffer Target4 { uvec2 texels[]; } io_target4;
layout(std430, binding = 14) buffer Target5 { uvec2 texels[]; } io_target5;
layout(std430, binding = 15) buffer Target6 { uvec2 texels[]; } io_target6;
layout(std430, binding = 16) buffer Target7 { uvec2 texels[]; } io_target7;
layout(std430, binding = 17) buffer Target8 { uvec2 texels[]; } io_target8;
layout(binding = 18) uniform samplerBuffer u_scaled0;
layout(binding = 19) uniform samplerBuffer u_scaled1;
layout(binding = 20) uniform samplerBuffer u_scaled2;
layout(binding = 21) uniform samplerBuffer u_scaled3;
layout(binding = 22) uniform samplerBuffer u_scaled4;
layout(std430, binding = 23) readonly buffer Groups { uint groups[]; } u_groups; // LIST, BLOCKS

bool used(int k) { return ((FEATURES >> uint(k)) & 1u) != 0u; }
bool copies(int k) { return ((FEATURES >> uint(16 + k)) & 1u) != 0u; }
const bool SCALED = (FEATURES & (1u << 15)) != 0u;
const bool LIST = (FEATURES & (1u << 14)) != 0u;
const bool BLOCKS = (FEATURES & (1u << 13)) != 0u;

// Source k, with its scaled texture's part when the pairs have one.
vec4 source(int k, samplerBuffer src, samplerBuffer scaled, int i) {
    vec4 v = texelFetch(src, i);
    if (SCALED) v.rgb += pc.pass.scale * texelFetch(scaled, i).rgb;
    return v;
}

uvec2 combine(int k, uvec2 old, vec4 add) {
    if (copies(k)) return pack_rgba16f(add);
    vec4 o = unpack_rgba16f(old);
    return pack_rgba16f(vec4(o.rgb + add.rgb, o.a));
}

void main() {
    ivec2 o = block_origin();
    if (LIST) {
        uint g = u_groups.groups[gl_WorkGroupID.x];
        uvec2 group = uvec2(g % uint(pc.pass.groups_x), g / uint(pc.pass.groups_x));
        o = ivec2((group * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy) * uvec2(BLOCK_W, BLOCK_H));
    }
    if (BLOCKS) {
        uint i = listed_block_index();
        if (i >= uint(pc.pass.blocks)) return;
        o = listed_block_origin(u_groups.groups[i]);
    }
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            if (x >= pc.size.x) continue;
            int i = texel_index(x, y);
            if (used(0)) io_target0.texels[i] = combine(0, io_target0.texels[i], source(0, u_source0, u_scaled0, i));
            if (used(1)) io_target1.texels[i] = combine(1, io_target1.texels[i], source(1, u_source1, u_scaled1, i));
            if (used(2)) io_target2.texels[i] = combine(2, io_target2.texels[i], source(2, u_source2, u_scaled2, i));
            if (used(3)) io_target3.texels[i] = combine(3, io_target3.texels[i], source(3, u_source3, u_scaled3, i));
            if (used(4)) io_target4.texels[i] = combine(4, io_target4.texels[i], source(4, u_source4, u_scaled4, i));
            if (used(5)) io_target5.texels[i] = combine(5, io_target5.texels[i], texelFetch(u_source5, i));
            if (used(6)) io_target6.texels[i] = combine(6, io_target6.texels[i], texelFetch(u_source6, i));
            if (used(7)) io_target7.texels[i] = combine(7, io_target7.texels[i], texelFetch(u_source7, i));
            if (used(8)) io_target8.texels[i] = combine(8, io_target8.texels[i], texelFetch(u_source8, i));
        }
    }
}
