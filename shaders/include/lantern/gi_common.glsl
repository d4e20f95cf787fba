// Shared by every GI compute pass: push constants, the texel grid, and the storage
// layout. Mirrored in C++ by engine/gi/src/vulkan/pass_params.hpp (GiPassParams).
//
// Layout: every GI texture is a buffer of pitch x height texels, row-major, row 0 at the
// window's min z; pitch is the width rounded up to 4. Each invocation computes a block of
// 4 x BLOCK_H texels, so a block row of r8 texels is one uint, of rg8 texels one uvec2, and
// rgba16f texels are one uvec2 each (packHalf2x16, round to nearest even). Reads go through
// uniform texel buffers (r8/rg8 UNORM, rgba16f SFLOAT views of the same buffers).
#ifndef LANTERN_GI_COMMON_GLSL
#define LANTERN_GI_COMMON_GLSL

#include "gi_types.glsl"
#include "gi_exact.glsl"

layout(constant_id = 0) const uint BLOCK_H = 4;        // texel rows per invocation
layout(local_size_x_id = 1, local_size_y_id = 2) in;  // workgroup size (blocks)
layout(constant_id = 3) const bool HAS_PROXIES = true; // false: proxy loops compiled out
layout(constant_id = 5) const bool HAS_WALLS = true;   // false: no wall tile in the window
layout(constant_id = 8) const uint FEATURES = 0u;      // the pass's own switches (PipelineSpec::features)
layout(constant_id = 9) const uint FACES = 15u;        // computed_faces: bit f = wall face f is computed
// Every shadow proxy's penumbra power is 1 (the default): penumbra_factor skips its pow, which
// lavapipe evaluates as exp2(log2) per (texel, light, proxy): a fifth of the direct pass on
// the seed table's scene. pow(t, 1) is t, as the reference's std::pow.
layout(constant_id = 11) const bool LINEAR_PENUMBRA = false;
// The frame's shadow proxies fit two words of a proxy mask (at most 64), and its point
// lights are at most 256 (pass_params.hpp proxy_register_lights): gi_shadow.glsl's proxy
// loops keep their list's words in registers.
layout(constant_id = 12) const bool PROXY_REGISTERS = false;

const uint BLOCK_W = 4;

// A pass's own parameters: a struct of 32 bytes (eight 4-byte scalars) the shader names
// with `#define GI_PASS_PARAMS MyParams` before including this file, read as pc.pass.NAME.
// Its C++ mirror (engine/gi/src/rows/*.cpp) is checked against the shader's reflected
// layout, field by field, when the pipeline is created.
#ifndef GI_PASS_PARAMS
struct GiNoParams {
    int unused0, unused1, unused2, unused3, unused4, unused5, unused6, unused7;
};
#define GI_PASS_PARAMS GiNoParams
#endif

layout(push_constant) uniform GiPassParams {
    vec4 camera_view;    // min_x, min_z, width, height (world units)
    ivec4 size;          // texture width, height, pitch (texels), resolution (texels per unit)
    ivec4 grid;          // wall grid width, height, origin x, origin z (see gi_shadow.glsl)
    ivec4 counts;        // point lights, emissives, directional lights, proxies
    GI_PASS_PARAMS pass; // the pass's own parameters (32 bytes)
    ivec4 grid_phase;    // toroidal phase of the wall grid (x, z)
} pc;

// The block this invocation owns: x0 is a multiple of 4.
ivec2 block_origin() { return ivec2(gl_GlobalInvocationID.x * BLOCK_W, gl_GlobalInvocationID.y * BLOCK_H); }
// Dispatches over a host-built list of blocks (rows::wall_blocks: x | y << 16, in blocks), one
// dimension of workgroups: this invocation's entry, and an entry's block origin in texels.
uint listed_block_index() { return gl_WorkGroupID.x * (gl_WorkGroupSize.x * gl_WorkGroupSize.y) + gl_LocalInvocationIndex; }
ivec2 listed_block_origin(uint b) { return ivec2(int(b & 0xFFFFu) * int(BLOCK_W), int(b >> 16) * int(BLOCK_H)); }

int texel_index(int x, int y) { return y * pc.size.z + x; }

// Centre in world units of texel (x, y) of a grid of `tpu` texels per world unit laid from
// the window's min corner (the window's textures, the heat and radiosity grids):
// min + (i + 0.5) / tpu, exactly as the C++ reference.
vec2 grid_texel_center(int x, int y, float tpu) {
    precise vec2 c = vec2(pc.camera_view.x + gi_div(float(x) + 0.5, tpu), pc.camera_view.y + gi_div(float(y) + 0.5, tpu));
    return c;
}
// The same for the window's textures (tpu = the resolution).
vec2 texel_center(int x, int y) { return grid_texel_center(x, y, float(pc.size.w)); }

vec4 finite_half_range(vec4 v) {
    v = clamp(v, vec4(-65504.0), vec4(65504.0)); // beyond the half range: stay finite
    return mix(v, vec4(0.0), isnan(v));          // NaN never propagates
}
uvec2 pack_rgba16f(vec4 v) {
    v = finite_half_range(v);
    return uvec2(packHalf2x16(v.xy), packHalf2x16(v.zw));
}
vec4 unpack_rgba16f(uvec2 u) { return vec4(unpackHalf2x16(u.x), unpackHalf2x16(u.y)); }
// floor(v * 255 + 0.5) after clamping, as the reference (GLSL round() leaves ties open).
uint unorm8(float v) { return uint(floor(clamp(v, 0.0, 1.0) * 255.0 + 0.5)); }
uint pack_r8x4(vec4 v) { return unorm8(v.x) | (unorm8(v.y) << 8) | (unorm8(v.z) << 16) | (unorm8(v.w) << 24); }
uint pack_rg8x2(vec2 a, vec2 b) { return unorm8(a.x) | (unorm8(a.y) << 8) | (unorm8(b.x) << 16) | (unorm8(b.y) << 24); }

#endif
