// The heat-transfer taps: 8 neighbour directions at one distance, or three rings (near 1.5
// texels 30 %, mid half distance 30 %, far full distance 40 %) when the distance exceeds
// 2.5 heat texels. Tap t is ring t / 8, direction t % 8. A tap at texel offset `off` from
// texel i lands on floor(i + 0.5 + off) = i + floor(0.5 + off): the integer offsets are
// the same for every texel. Mirrors heat_taps() in engine/gi/src/reference_indirect.cpp.
#ifndef LANTERN_GI_HEAT_TAPS_GLSL
#define LANTERN_GI_HEAT_TAPS_GLSL

const vec2 HEAT_DIRECTIONS[8] = vec2[8](vec2(-1, -1), vec2(0, -1), vec2(1, -1), vec2(-1, 0), vec2(1, 0),
                                        vec2(-1, 1), vec2(0, 1), vec2(1, 1));
const float HEAT_DIRECTION_WEIGHTS[8] = float[8](0.70710678, 1.0, 0.70710678, 1.0, 1.0, 0.70710678, 1.0, 0.70710678);

int heat_tap_count(float distance) { return distance > 2.5 ? 24 : 8; }

float heat_ring_distance(int ring, float distance) {
    if (distance <= 2.5) return distance;
    return ring == 0 ? 1.5 : (ring == 1 ? distance * 0.5 : distance);
}
float heat_ring_share(int ring, float distance) {
    if (distance <= 2.5) return 1.0;
    return ring == 2 ? 0.4 : 0.3;
}
// Integer texel offset of tap t.
ivec2 heat_tap_offset(int t, float distance) {
    return ivec2(floor(HEAT_DIRECTIONS[t % 8] * heat_ring_distance(t / 8, distance) + 0.5));
}
float heat_tap_weight(int t, float distance) {
    return HEAT_DIRECTION_WEIGHTS[t % 8] * heat_ring_share(t / 8, distance);
}
// Whether the tap skips over a texel (and so could jump a wall): the segment check applies.
bool heat_tap_skips(ivec2 k) { return abs(k.x) > 1 || abs(k.y) > 1; }

#endif
