#version 450
#extension GL_GOOGLE_include_directive : require
#include "value.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Data { uint data[]; };
void main() { data[gl_GlobalInvocationID.x] = VALUE + undeclared_name; }
