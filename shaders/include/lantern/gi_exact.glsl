// Correctly rounded division and square root, so the GI passes' cell decisions match the
// C++ reference on every Vulkan driver. Vulkan lets OpFDiv err by 2.5 ULP and sqrt by as
// much as inversesqrt (NVIDIA's do), and a ray that passes a tile corner, a sun along an
// exact diagonal or a window a third of a tile off the grid turns on one ULP. Vulkan does
// round additions, subtractions and multiplications correctly, but need not fuse fma
// (lavapipe does not), so the residuals here use Dekker's exact product, built from those
// alone (`precise` keeps every step apart).
//
// EXACT_ROUNDING (specialisation constant 10, spec_exact_rounding in pass_params.hpp):
//   0  the driver's own division and root, where they are IEEE 754 already: CPU drivers
//      (lavapipe) compile them to the processor's instructions; the helpers cost nothing;
//   1  residuals by Dekker's product (any driver);
//   2  residuals by one fma, where the renderer's start-up probe found fma fused (GPUs).
// compute_test.cpp (ExactDivisionAndSquareRootAreCorrectlyRounded) checks every mode.
#ifndef LANTERN_GI_EXACT_GLSL
#define LANTERN_GI_EXACT_GLSL

layout(constant_id = 10) const uint EXACT_ROUNDING = 1u;

// The float next to x (finite, non-zero) away from zero when `away`, else toward it.
float gi_exact_step(float x, bool away) {
    return uintBitsToFloat(floatBitsToUint(x) + (away ? 1u : 0xffffffffu));
}

// a - q * b exactly, for q within a few ULP of a / b (Dekker's product q * b = p + e, then
// a - p, exact by Sterbenz's lemma, less e; the residual itself is representable).
float gi_residual(float a, float q, float b) {
    if (EXACT_ROUNDING == 2u) {
        precise float fused = fma(-q, b, a); // one rounding of a representable value: exact
        return fused;
    }
    precise float cq = 4097.0 * q;
    precise float qh = cq - (cq - q);
    precise float ql = q - qh;
    precise float cb = 4097.0 * b;
    precise float bh = cb - (cb - b);
    precise float bl = b - bh;
    precise float p = q * b;
    precise float e = ((qh * bh - p) + qh * bl + ql * bh) + ql * bl;
    precise float r = (a - p) - e;
    return r;
}

// Outside this range the helpers return the driver's result (no overflow in the splits).
bool gi_exact_in_range(float v) { return abs(v) >= 1.17549435e-38 && abs(v) <= 1e30; }

// a / b rounded to nearest from q, an estimate within a few ULP (the driver's a / b).
float gi_div_from(float a, float b, float q) {
    precise float r = gi_residual(a, q, b);
    precise float q1 = q + r / b; // Markstein's correction: now within an ULP
    precise float r1 = gi_residual(a, q1, b);
    if (r1 == 0.0) return q1;
    // The exact quotient lies between q1 and its neighbour toward it; the nearer has the
    // smaller residual (quotients of floats are never midpoints: no tie rule needed).
    bool up = (r1 > 0.0) == (b > 0.0);
    precise float n = gi_exact_step(q1, up == (q1 > 0.0));
    precise float rn = gi_residual(a, n, b);
    return abs(rn) < abs(r1) ? n : q1;
}
// a / b rounded to nearest, as IEEE 754 division.
float gi_div(float a, float b) {
    precise float q = a / b;
    if (EXACT_ROUNDING == 0u || !gi_exact_in_range(q) || !gi_exact_in_range(b)) return q;
    return gi_div_from(a, b, q);
}
vec2 gi_div(vec2 a, float b) { return vec2(gi_div(a.x, b), gi_div(a.y, b)); }

// sqrt(x) rounded to nearest from s, an estimate within a few ULP (the driver's sqrt).
float gi_sqrt_from(float x, float s) {
    precise float r = gi_residual(x, s, s);
    precise float s1 = s + r / (2.0 * s); // Newton's step: now within an ULP
    precise float r1 = gi_residual(x, s1, s1); // x - s1^2: a multiple of ulp(s1)^2
    if (r1 > 0.0) {
        // Up when sqrt(x) > s1 + u / 2, i.e. r1 > s1 u + u^2 / 4, i.e. (r1 being a multiple
        // of u^2) r1 > s1 u; u, the gap above s1, is a power of two, so s1 u is exact.
        precise float up = gi_exact_step(s1, true);
        precise float u = up - s1;
        precise float threshold = s1 * u;
        return r1 > threshold ? up : s1;
    }
    if (r1 < 0.0) {
        // Down when sqrt(x) < s1 - d / 2, i.e. -r1 > s1 d - d^2 / 4, i.e. -r1 >= s1 d.
        precise float down = gi_exact_step(s1, false);
        precise float d = s1 - down;
        precise float threshold = s1 * d;
        return -r1 >= threshold ? down : s1;
    }
    return s1;
}

// sqrt(x) rounded to nearest, as IEEE 754 square root.
float gi_sqrt(float x) {
    precise float s = sqrt(x);
    if (EXACT_ROUNDING == 0u || !(x > 0.0) || !gi_exact_in_range(x) || !gi_exact_in_range(s)) return s;
    return gi_sqrt_from(x, s);
}

// |v| as the reference computes it: sqrt(x * x + y * y), the sum rounded twice (never
// fused) and the root correctly rounded. Pass sums to gi_sqrt through a `precise` local
// like this one: `precise` does not reach through a function's arguments.
float gi_length(vec2 v) {
    precise float squared = v.x * v.x + v.y * v.y;
    return gi_sqrt(squared);
}

#endif
