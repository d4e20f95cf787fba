// Test shader (engine::gpu tests): data[i] = i * multiplier + offset for i < count.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "test_common.glsl"

layout(local_size_x = TEST_GROUP_SIZE) in;

layout(push_constant) uniform Push { FillPush push; };
layout(std430, set = 0, binding = 0) writeonly buffer Data { uint data[]; };

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) return;
    data[i] = i * push.multiplier + push.offset;
}
