// Test shader (engine::gpu tests): specialization constants pick the formula and the group
// size. MODE 0: data[i] = i + VALUE; MODE 1: data[i] = i * VALUE. Covers exactly `count`
// invocations when dispatched with count / GROUP_SIZE groups.
#version 450

layout(local_size_x_id = 2) in;
layout(constant_id = 0) const uint MODE = 0u;
layout(constant_id = 1) const uint VALUE = 0u;

layout(std430, set = 0, binding = 0) writeonly buffer Data { uint data[]; };

void main() {
    const uint i = gl_GlobalInvocationID.x;
    data[i] = MODE == 0u ? i + VALUE : i * VALUE;
}
