// Test shader (engine::gpu tests): the driver's division and square root beside
// gi_exact.glsl's correctly rounded ones, for pairs (a, b): out = (a / b, gi_div, sqrt(|a|),
// gi_sqrt). Where push.multiplier is k > 0, the helpers start instead from the driver's
// result moved (i mod (2k + 1)) - k ULP, as a driver with that much error would give.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "test_common.glsl"
#include "lantern/gi_exact.glsl"

layout(local_size_x = TEST_GROUP_SIZE) in;

layout(push_constant) uniform Push { FillPush push; };
layout(std430, set = 0, binding = 0) readonly buffer Pairs { vec2 pairs[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Results { vec4 results[]; };

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) return;
    const vec2 p = pairs[i];
    precise float q = p.x / p.y;
    precise float s = sqrt(abs(p.x));
    const int k = int(push.multiplier), shift = k > 0 ? int(i % uint(2 * k + 1)) - k : 0;
    const float q_off = uintBitsToFloat(uint(int(floatBitsToUint(q)) + shift));
    const float s_off = uintBitsToFloat(uint(int(floatBitsToUint(s)) + shift));
    const bool div_in = gi_exact_in_range(q) && gi_exact_in_range(p.y);
    const bool sqrt_in = gi_exact_in_range(abs(p.x)) && gi_exact_in_range(s);
    results[i] = vec4(q, k > 0 ? (div_in ? gi_div_from(p.x, p.y, q_off) : q) : gi_div(p.x, p.y), s,
                      k > 0 ? (sqrt_in ? gi_sqrt_from(abs(p.x), s_off) : s) : gi_sqrt(abs(p.x)));
}
