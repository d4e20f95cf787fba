// The sun's shadow map (gi.sun_shadow_method = shadow_map): GLSL twin of
// engine/gi/src/sun_map.cpp sun_map_visibility (keep them in step; sun_map.hpp explains the
// map). Requires gi_shadow.glsl and three bindings declared by the includer:
//   u_sun_headers (samplerBuffer, RGBA32F): per sun (v0, 1 / bin width, bins, first base)
//                 and (reach, 1 = lit everywhere, 0, 0);
//   u_sun_first   (usamplerBuffer, R32UI): per sun bins + 1 entry indices (absolute);
//   u_sun_entries (samplerBuffer, RGBA32F): (u of the tile centre, tile x, tile z, 0).
#ifndef LANTERN_GI_SUN_MAP_GLSL
#define LANTERN_GI_SUN_MAP_GLSL

const float GI_SUN_MAP_AMBIGUITY = 1e-3; // sun_map_ambiguity: closer calls go to the DDA

// The part [t_in, t_out] of the ray start + dir * t inside the tile (sun_map.cpp span_in_tile).
void sun_span_in_tile(vec2 start, vec2 dir, ivec2 cell, out float t_in, out float t_out) {
    t_in = -GI_BIG;
    t_out = GI_BIG;
    for (int a = 0; a < 2; ++a) {
        float lo = float(cell[a]), hi = lo + 1.0;
        if (abs(dir[a]) < GI_DIR_EPS) continue; // inside the slab: the caller knows the line meets the tile
        precise float t1 = gi_div(lo - start[a], dir[a]);
        precise float t2 = gi_div(hi - start[a], dir[a]);
        t_in = max(t_in, min(t1, t2));
        t_out = min(t_out, max(t1, t2));
    }
}

float sun_map_visibility(int sun_index, GpuDirectionalLight sun, vec2 pixel, float max_distance, float wall_height) {
    vec4 h0 = texelFetch(u_sun_headers, 2 * sun_index), h1 = texelFetch(u_sun_headers, 2 * sun_index + 1);
    if (h1.y > 0.5) return 1.0;
    vec3 to_sun = -sun.direction_base.xyz;
    precise float xz_length = gi_length(to_sun.xz);
    precise vec2 dir = vec2(gi_div(to_sun.x, xz_length), gi_div(to_sun.z, xz_length));
    vec2 perp = vec2(-dir.y, dir.x);
    precise vec2 start = pixel + dir * GI_RAY_BIAS;
    precise float u = start.x * dir.x + start.y * dir.y;
    precise float v = start.x * perp.x + start.y * perp.y;
    int bin = clamp(int(floor((v - h0.x) * h0.y)), 0, int(h0.z) - 1);
    int first = int(h0.w) + bin;
    uint lo = texelFetch(u_sun_first, first).r, hi = texelFetch(u_sun_first, first + 1).r;
    // Tiles behind the start (u more than 1 below) are never on the path: binary search.
    uint a = lo, b = hi;
    while (a < b) {
        uint mid = (a + b) >> 1;
        if (texelFetch(u_sun_entries, int(mid)).x < u - 1.0) a = mid + 1u;
        else b = mid;
    }
    ivec2 start_cell = ivec2(floor(start));
    precise float half_width = 0.5 * (abs(dir.x) + abs(dir.y));
    float reach = h1.x;
    for (uint i = a; i < hi; ++i) {
        vec4 e = texelFetch(u_sun_entries, int(i));
        if (e.x > u + reach + 1.0) break;
        ivec2 cell = ivec2(e.yz);
        if (cell != start_cell) {
            precise vec2 to_centre = vec2(float(cell.x) + 0.5 - start.x, float(cell.y) + 0.5 - start.y);
            precise float across = abs(to_centre.x * perp.x + to_centre.y * perp.y);
            if (abs(across - half_width) < GI_SUN_MAP_AMBIGUITY) // the line grazes the tile's corner
                return directional_shadow_dda(pixel, sun.direction_base.xyz, max_distance, wall_height);
            if (across > half_width) continue; // the line misses the tile
            float t_in, t_out;
            sun_span_in_tile(start, dir, cell, t_in, t_out);
            if (abs(t_out) < GI_SUN_MAP_AMBIGUITY || abs(t_out - max_distance) < GI_SUN_MAP_AMBIGUITY)
                return directional_shadow_dda(pixel, sun.direction_base.xyz, max_distance, wall_height);
            if (t_out < 0.0 || t_out > max_distance) continue; // behind, or beyond the shadow distance
        }
        if (blocks_directional_cell(cell, start, to_sun, xz_length, wall_height)) return 0.0;
    }
    return 1.0;
}

#endif
