// Test shader (engine::gpu tests), the GI backend's texel layout: reads an RGBA16F uniform
// texel buffer, scales it, writes each texel as two packHalf2x16 words to a uvec2 SSBO.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "test_common.glsl"

layout(local_size_x = TEST_GROUP_SIZE) in;

layout(push_constant) uniform Push { HalfPush push; };
layout(set = 0, binding = 0) uniform textureBuffer source;
layout(std430, set = 0, binding = 1) writeonly buffer Packed { uvec2 packed_texels[]; };

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) return;
    const vec4 v = texelFetch(source, int(i)) * push.scale;
    packed_texels[i] = uvec2(packHalf2x16(v.xy), packHalf2x16(v.zw));
}
