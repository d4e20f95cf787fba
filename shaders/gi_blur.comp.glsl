// One direction of the edge-aware blur: 5 taps, Gaussian sigma 1, only texels of the
// centre's conduction class, renormalised (brightness preserving). The class comes from the
// conduction texture (1 in air, 0 in walls: the tile under the texel centre), one byte per
// tap instead of a wall lookup; each invocation slides a window of five taps along its
// block's lines. Parameters: BlurParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct BlurParams {
    int axis_x, axis_y; // (1, 0) horizontal, (0, 1) vertical (FEATURES bit 0 says which the shader runs)
    int pad0, pad1, pad2, pad3, pad4, pad5;
};
#define GI_PASS_PARAMS BlurParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_conduction;
layout(binding = 1) uniform samplerBuffer u_src;
layout(std430, binding = 2) writeonly buffer Out { uvec2 texels[]; } o_dst;

const float K0 = 0.13533528, K1 = 0.60653066, K2 = 1.0; // exp(-k^2 / 2), k = 2, 1, 0

// A tap: its conduction class (1 air, 0 wall, -1 outside the window, which no centre
// matches) and its value.
struct Tap {
    float cls;
    vec4 value;
};

Tap tap(ivec2 q) {
    bool inside = q.x >= 0 && q.y >= 0 && q.x < pc.size.x && q.y < pc.size.y;
    int index = texel_index(clamp(q.x, 0, pc.size.x - 1), clamp(q.y, 0, pc.size.y - 1));
    Tap t;
    t.cls = inside ? (texelFetch(u_conduction, index).r > 0.5 ? 1.0 : 0.0) : -1.0;
    t.value = texelFetch(u_src, index);
    return t;
}

void take(Tap t, float centre, float k, inout vec3 sum, inout float wsum) {
    if (t.cls == centre) {
        sum += t.value.rgb * k;
        wsum += k;
    }
}

// Blurs `length` texels from `first` along `axis`, sliding a window of five taps: each
// texel is read once per line instead of five times. The taps add in the order -2..2.
void blur_line(ivec2 first, ivec2 axis, int length) {
    Tap t0 = tap(first - 2 * axis), t1 = tap(first - axis), t2 = tap(first), t3 = tap(first + axis);
    for (int n = 0; n < length; ++n) {
        ivec2 q = first + n * axis;
        if (q.y >= pc.size.y) return;
        Tap t4 = tap(q + 2 * axis);
        vec4 value = vec4(0.0); // the pitch's padding texels
        if (q.x < pc.size.x) {
            vec3 sum = vec3(0.0);
            float wsum = 0.0;
            take(t0, t2.cls, K0, sum, wsum);
            take(t1, t2.cls, K1, sum, wsum);
            take(t2, t2.cls, K2, sum, wsum);
            take(t3, t2.cls, K1, sum, wsum);
            take(t4, t2.cls, K0, sum, wsum);
            value = vec4(sum / wsum, t2.value.a);
        }
        o_dst.texels[texel_index(q.x, q.y)] = pack_rgba16f(value);
        t0 = t1;
        t1 = t2;
        t2 = t3;
        t3 = t4;
    }
}

// The pass's axis (FEATURES bit 0: vertical) as a specialisation constant: lavapipe runs both
// sides of a branch, masked, so a branch on axis_x would run both blurs in every invocation.
const bool VERTICAL = (FEATURES & 1u) != 0u;

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    if (!VERTICAL) {
        for (uint r = 0; r < BLOCK_H; ++r) blur_line(o + ivec2(0, r), ivec2(1, 0), 4);
    } else {
        for (int k = 0; k < 4; ++k) blur_line(o + ivec2(k, 0), ivec2(0, 1), int(BLOCK_H));
    }
}
