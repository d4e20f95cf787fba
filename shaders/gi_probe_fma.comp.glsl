// Probe (GI renderer start-up, GPUs only): does this driver fuse fma? For each entry
// (a, b, c, _) writes fma(a, b, c) to w. The renderer compares with the host's fused fma
// and chooses how gi_exact.glsl computes residuals (renderer.cpp driver_fuses_fma).
#version 450

layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Entries { vec4 entries[]; };

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= uint(entries.length())) return;
    const vec4 e = entries[i];
    precise float f = fma(e.x, e.y, e.z);
    entries[i].w = f;
}
