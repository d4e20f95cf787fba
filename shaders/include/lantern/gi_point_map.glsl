// Point lights' shadow maps (gi.shadow_method = shadow_map): GLSL twin of
// engine/gi/src/point_map.cpp's lookup (point_map.hpp explains the map and its packing).
// Exact against shadow_dda by construction: every answer holds with the light's margin to
// spare, and close calls go to shadow_dda itself.
//
// lavapipe runs both sides of every branch and gathers every loaded component per lane, so
// the lookup is straight-line code around one 64-bit load, and the DDA for its close calls
// is not behind an `if` here (it would run, masked, for every lookup): the caller collects
// them and runs the DDA in a loop that only their lanes extend.
//
// Requires before inclusion: gi_shadow.glsl and a storage buffer u_point_map.bins (uvec2
// per bin). A light's header rides in its spare fields: position_radius.w = first bin (-1:
// no map), color.w = margin.
#ifndef LANTERN_GI_POINT_MAP_GLSL
#define LANTERN_GI_POINT_MAP_GLSL

const uint GI_NO_RUN = 0xffffffu;

// In [0, 4], monotone in atan2(d.y, d.x) (point_map.cpp pseudo_angle).
float pseudo_angle(vec2 d) {
    precise float t = gi_div(d.x, abs(d.x) + abs(d.y));
    precise float a = d.y >= 0.0 ? 1.0 - t : 3.0 + t;
    return a;
}

// A light's bins (point_map.cpp point_map_bins).
int point_map_bins(float radius) {
    precise float quarter = ceil(0.5 * radius * float(pc.size.w));
    return 4 * int(clamp(quarter, 4.0, 1024.0));
}

// Segment 0 -> d against the box [lo, hi]: true when they meet. Branch-free.
bool segment_meets(vec2 d, vec2 lo, vec2 hi) {
    vec2 inv = 1.0 / d;
    vec2 ta = lo * inv, tb = hi * inv;
    bvec2 flat_ = equal(d, vec2(0.0));
    bvec2 inside = bvec2(lo.x <= 0.0 && hi.x >= 0.0, lo.y <= 0.0 && hi.y >= 0.0);
    vec2 t0 = mix(min(ta, tb), mix(vec2(GI_BIG), vec2(-GI_BIG), inside), flat_);
    vec2 t1 = mix(max(ta, tb), mix(vec2(-GI_BIG), vec2(GI_BIG), inside), flat_);
    return max(0.0, max(t0.x, t0.y)) <= min(1.0, min(t1.x, t1.y));
}

// Run `code` against the segment from the light at pos along d: 1 misses it (widened by
// the margin), 0 crosses it (narrowed), -1 unsure or no run.
int run_test(uint code, vec2 pos, vec2 d, float margin) {
    vec2 lo = floor(pos) + vec2(float(int(code & 0xffu) - 128), float(int((code >> 8) & 0xffu) - 128)) - pos;
    vec2 hi = lo + vec2(float((code >> 16) & 0xffu), 1.0);
    bool misses = !segment_meets(d, lo - margin, hi + margin);
    bool crosses = segment_meets(d, lo + margin, hi - margin);
    return code == GI_NO_RUN ? -1 : (misses ? 1 : (crosses ? 0 : -1));
}

// Light l's grid visibility of target from its map: 0 blocked, 1 lit (shadow_dda's
// meaning), -1 when the map cannot tell (close calls, no map): then shadow_dda decides. The
// direct pass defers those to a loop of their own (point_map.cpp point_map_lookup).
float point_map_lookup(GpuPointLight l, vec2 target) {
    vec2 pos = l.position_radius.xy;
    float radius = l.position_radius.z, base = l.position_radius.w, margin = l.color.w;
    precise vec2 d = target - pos;
    precise float dist = gi_length(d);
    int bins = point_map_bins(radius);
    int b = int(pseudo_angle(d) * (float(bins) * 0.25));
    b = max(b >= bins ? b - bins : b, 0);
    uvec2 e = u_point_map.bins[max(int(base), 0) + b];
    float reach = radius + 3.0;
    float step = reach / 65535.0;
    int r1 = run_test(e.y & 0xffffffu, pos, d, margin);
    float v = dist < float(e.x & 0xffffu) * step                            ? 1.0
              : dist > float(e.x >> 16) * step                              ? 0.0
              : r1 == 0                                                     ? 0.0
              : (r1 > 0 && dist < float(e.y >> 24) * (reach / 255.0))        ? 1.0
                                                                            : -1.0;
    if (base < 0.0 || dist < 2e-4) v = -1.0;
    return v;
}

#endif
