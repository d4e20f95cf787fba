#version 450
// Per-texel lighting, UV to world (seed 001's UvToWorld kernel; engine/texel/texel.hpp): one
// invocation per atlas texel of the span asked for (pc.span: all, or placements that moved) finds its placement, then the first of the placement's
// triangles that holds the texel's centre in UV space, and writes the texel's world
// position, normal-mapped normal and geometric normal (or an unused texel).
#extension GL_GOOGLE_include_directive : require
#include "lantern/texel.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Triangles { TexelTriangle triangles[]; };
layout(std430, set = 0, binding = 1) readonly buffer Placements { TexelPlacement placements[]; };
layout(std430, set = 0, binding = 2) readonly buffer NormalMaps { vec4 normal_maps[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Surfaces { TexelSurface surfaces[]; };

void main() {
    if (gl_GlobalInvocationID.x >= pc.span.y) return;
    const uint texel = pc.span.x + gl_GlobalInvocationID.x; // the texels of the placements asked for
    if (texel >= pc.counts.x) return;
    // The placement: the last whose first texel is <= texel (first texels ascend).
    uint lo = 0u, hi = pc.counts.y;
    while (hi - lo > 1u) {
        const uint mid = (lo + hi) / 2u;
        if (placements[mid].ranges.z <= texel) lo = mid;
        else hi = mid;
    }
    const uvec4 ranges = placements[lo].ranges;
    const int size = int(ranges.w);
    const int local = int(texel - ranges.z);
    const int y = local / size, x = local - y * size;
    precise float ux = float(x) + 0.5, uy = float(y) + 0.5;
    const vec2 uv = vec2(gi_div(ux, float(size)), gi_div(uy, float(size)));

    TexelSurface s;
    s.position_used = vec4(0.0);
    s.normal_triangle = vec4(0.0);
    s.geo_normal = vec4(0.0);
    for (uint i = ranges.x; i < ranges.x + ranges.y; ++i) {
        const vec2 p1 = triangles[i].uv12.xy, p2 = triangles[i].uv12.zw, p3 = triangles[i].uv3.xy;
        precise float denom = (p2.x - p1.x) * (p3.y - p1.y) - (p3.x - p1.x) * (p2.y - p1.y);
        if (denom == 0.0) continue;
        precise float vn = (uv.x - p1.x) * (p3.y - p1.y) - (p3.x - p1.x) * (uv.y - p1.y);
        precise float wn = (p2.x - p1.x) * (uv.y - p1.y) - (uv.x - p1.x) * (p2.y - p1.y);
        const float v = gi_div(vn, denom), w = gi_div(wn, denom);
        if (!texel_inside(v, w)) continue;

        const vec3 w1 = triangles[i].p1.xyz, w2 = triangles[i].p2.xyz, w3 = triangles[i].p3.xyz;
        precise vec3 e1 = w2 - w1, e2 = w3 - w1;
        precise vec3 pos = w1 + (v * e1 + w * e2);
        s.position_used = vec4(pos, 1.0);
        // The seed's normal map: green flipped, [0, 1] -> [-1, 1], weights of the tangent frame.
        const vec4 nm = normal_maps[texel];
        precise vec3 m = vec3(nm.r, 1.0 - nm.g, nm.b) * 2.0 - 1.0;
        const vec3 n = triangles[i].normal.xyz;
        precise vec3 mapped = n * m.z + triangles[i].binormal.xyz * m.y + triangles[i].tangent.xyz * m.x;
        const float len = texel_length(mapped);
        s.normal_triangle = vec4(len > 0.0 ? texel_div(mapped, len) : n, float(i));
        s.geo_normal = vec4(n, 0.0);
        break;
    }
    surfaces[texel] = s;
}
