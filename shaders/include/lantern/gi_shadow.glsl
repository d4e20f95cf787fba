// Grid traversals, shadow proxies, falloff and wall-face weights: the GLSL side of
// engine/gi/src/reference_shadow.cpp, operation for operation. `precise` keeps the
// compiler from fusing multiply-adds, so cell decisions match the reference.
//
// Requires before inclusion: gi_common.glsl, `usamplerBuffer u_walls` (R8_UINT, 1 = wall)
// and a `u_proxies` block with `GpuShadowProxy proxies[]` (bound even when HAS_PROXIES is
// false; the specialisation constant lets the driver drop the proxy loops).
#ifndef LANTERN_GI_SHADOW_GLSL
#define LANTERN_GI_SHADOW_GLSL

#include "gi_types.glsl"
#include "gi_exact.glsl"

const float GI_RAY_BIAS = 1e-4;
const float GI_DIR_EPS = 1e-6;
const float GI_CORNER_EPS = 1e-5;
const float GI_BIG = 1e30;
const float GI_FACE_EPS = 1e-3;

#include "gi_walls.glsl"
// True when a traversal can never meet a wall again: outside the grid and stepping away
// from it (results then do not depend on how far the grid extends).
bool leaving_grid(ivec2 cell, ivec2 stp) {
    ivec2 lo = pc.grid.zw, hi = pc.grid.zw + pc.grid.xy;
    return (cell.x < lo.x && stp.x <= 0) || (cell.x >= hi.x && stp.x >= 0) || (cell.y < lo.y && stp.y <= 0) ||
           (cell.y >= hi.y && stp.y >= 0);
}

float saturate(float x) { return clamp(x, 0.0, 1.0); }

float first_boundary(float start, float dir, int stp) {
    if (abs(dir) < GI_DIR_EPS) return GI_BIG;
    precise float cell = floor(start);
    precise float t = stp > 0 ? gi_div(cell + 1.0 - start, dir) : gi_div(start - cell, -dir);
    return t;
}
float boundary_step(float dir) { return abs(dir) < GI_DIR_EPS ? GI_BIG : abs(gi_div(1.0, dir)); }
int sign_of(float v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }

float shadow_dda(vec2 light, vec2 pixel, float radius) {
    precise vec2 ray = pixel - light;
    precise float ray_length = gi_length(ray);
    if (ray_length < 1e-4) return 1.0;
    precise vec2 dir = gi_div(ray, ray_length);
    precise vec2 start = light + dir * GI_RAY_BIAS;
    precise vec2 end_pos = pixel - dir * GI_RAY_BIAS;
    ray_length = max(ray_length - 2.0 * GI_RAY_BIAS, 0.0);

    ivec2 cell = ivec2(floor(start));
    ivec2 end_cell = ivec2(floor(end_pos));
    ivec2 stp = ivec2(sign_of(dir.x), sign_of(dir.y));
    precise vec2 t_max = vec2(first_boundary(start.x, dir.x, stp.x), first_boundary(start.y, dir.y, stp.y));
    vec2 t_delta = vec2(boundary_step(dir.x), boundary_step(dir.y));
    int max_steps = max(1, int(ceil(radius * 2.0)) + 2);

    for (int i = 0; i < max_steps; ++i) {
        if (is_wall(cell)) return 0.0;
        if (cell == end_cell) return 1.0;
        float traveled;
        if (t_max.x < t_max.y - GI_CORNER_EPS) {
            traveled = t_max.x;
            t_max.x += t_delta.x;
            cell.x += stp.x;
        } else if (t_max.y < t_max.x - GI_CORNER_EPS) {
            traveled = t_max.y;
            t_max.y += t_delta.y;
            cell.y += stp.y;
        } else {
            traveled = t_max.x;
            if (is_wall(cell.x + stp.x, cell.y) && is_wall(cell.x, cell.y + stp.y)) return 0.0;
            t_max += t_delta;
            cell += stp;
        }
        if (traveled > ray_length) return 1.0;
    }
    return 1.0;
}

bool blocks_directional_cell(ivec2 cell, vec2 start, vec3 to_sun, float to_sun_xz_length, float wall_height) {
    if (!is_wall(cell)) return false;
    precise vec2 d = vec2(cell) + 0.5 - start;
    precise float distance_to_wall = gi_length(d);
    if (abs(to_sun.y) > 0.001 && to_sun_xz_length > 1e-4) {
        precise float vertical_rate = gi_div(to_sun.y, to_sun_xz_length);
        precise float height = distance_to_wall * vertical_rate;
        return height < wall_height;
    }
    return true;
}

float directional_shadow_dda(vec2 pixel, vec3 light_dir, float max_distance, float wall_height) {
    vec3 to_sun = -light_dir;
    precise float xz_length = gi_length(to_sun.xz);
    if (xz_length < 1e-4) return 1.0;
    precise vec2 dir = vec2(gi_div(to_sun.x, xz_length), gi_div(to_sun.z, xz_length));
    precise vec2 start = pixel + dir * GI_RAY_BIAS;
    ivec2 cell = ivec2(floor(start));
    ivec2 stp = ivec2(sign_of(dir.x), sign_of(dir.y));
    precise vec2 t_max = vec2(first_boundary(start.x, dir.x, stp.x), first_boundary(start.y, dir.y, stp.y));
    vec2 t_delta = vec2(boundary_step(dir.x), boundary_step(dir.y));
    // A straight line crosses at most 2 cells per unit of length (plus the ends).
    int max_steps = 2 * int(ceil(min(max_distance, 1e6))) + 2;
    for (int i = 0; i < max_steps; ++i) {
        if (blocks_directional_cell(cell, start, to_sun, xz_length, wall_height)) return 0.0;
        if (t_max.x < t_max.y) {
            t_max.x += t_delta.x;
            cell.x += stp.x;
        } else {
            t_max.y += t_delta.y;
            cell.y += stp.y;
        }
        if (min(t_max.x, t_max.y) > max_distance) return 1.0;
        if (leaving_grid(cell, stp)) return 1.0;
    }
    return 1.0;
}

float light_falloff(float dist, float radius, float softness) {
    return pow(1.0 - saturate(dist / radius), softness);
}

vec4 wall_face_mask(ivec2 c) {
    return vec4(is_wall(c.x + 1, c.y) ? 0.0 : 1.0, is_wall(c.x - 1, c.y) ? 0.0 : 1.0,
                is_wall(c.x, c.y + 1) ? 0.0 : 1.0, is_wall(c.x, c.y - 1) ? 0.0 : 1.0);
}
// 1 for the faces whose bit is set in `faces` (computed_faces: gi.wall_lighting and
// gi.wall_faces), 0 for the others; multiplies wall_face_mask.
vec4 face_bits_mask(uint faces) {
    return vec4((faces & 1u) != 0u ? 1.0 : 0.0, (faces & 2u) != 0u ? 1.0 : 0.0,
                (faces & 4u) != 0u ? 1.0 : 0.0, (faces & 8u) != 0u ? 1.0 : 0.0);
}
bool computes_face(uint faces, int face) { return ((faces >> uint(face)) & 1u) != 0u; }
// Each face's weight (+x, -x, +z, -z) for light from unit direction d, raised to `exponent`
// (gi.wall_face_exponent). `linear`: the exponent is 1, so no pow (the reference's
// std::pow(x, 1) is x); pass a specialisation constant. lavapipe evaluates both sides of a
// select, and pow as exp2(log2) on each of the four: with a run-time test alone that cost
// the direct pass 13 % per (texel, light) pair (docs/performance.md).
vec4 wall_facing(vec2 d, float exponent, const bool linear) {
    vec4 w = vec4(saturate(d.x), saturate(-d.x), saturate(d.y), saturate(-d.y));
    return linear || exponent == 1.0 ? w : pow(w, vec4(exponent));
}

// Where a wall face's shadow ray ends (or starts, for the sun): just outside the face.
vec2 face_position(int face, ivec2 cell, vec2 p) {
    if (face == 0) return vec2(float(cell.x) + 1.0 + GI_FACE_EPS, p.y);
    if (face == 1) return vec2(float(cell.x) - GI_FACE_EPS, p.y);
    if (face == 2) return vec2(p.x, float(cell.y) + 1.0 + GI_FACE_EPS);
    return vec2(p.x, float(cell.y) - GI_FACE_EPS);
}

float penumbra_factor(float dist, float edge, float width, float power, int mode) {
    if (!(width > 0.0)) return dist <= edge ? 1.0 : 0.0;
    float lo = mode == 0 ? edge - width : (mode == 1 ? edge : edge - 0.5 * width);
    float t = saturate((lo + width - dist) / width);
    return LINEAR_PENUMBRA ? t : pow(t, power);
}

float proxy_width(GpuShadowProxy p, vec2 perp) {
    if (p.modes.y > 0.5) return p.position_size.z;
    vec2 half_size = p.position_size.zw;
    if (p.modes.z > 0.5) return max(half_size.x, half_size.y);
    return abs(perp.x) * half_size.x + abs(perp.y) * half_size.y;
}

float proxy_occlusion(GpuShadowProxy p, vec2 pixel, vec2 dir_shadow) {
    vec2 perp = vec2(-dir_shadow.y, dir_shadow.x);
    precise vec2 to_pixel = pixel - p.position_size.xy;
    precise float along = to_pixel.x * dir_shadow.x + to_pixel.y * dir_shadow.y;
    if (along <= 0.0) return 0.0;
    float max_length = p.lengths.x, pen_width = p.lengths.z, pen_length = p.lengths.w;
    if (along > max_length + pen_length) return 0.0;
    precise float perp_dist = abs(to_pixel.x * perp.x + to_pixel.y * perp.y);
    float power = p.modes.x;
    int mode = int(p.modes.w + 0.5);
    float edge = penumbra_factor(perp_dist, proxy_width(p, perp), pen_width, power, mode);
    float len = penumbra_factor(along, max_length, pen_length, power, mode);
    return edge * len * p.fade.x; // a strength of 1 changes nothing, bit for bit
}

// The shadow proxies a light's loops visit: all of them, unless the including shader
// defines GI_PROXY_MASK(w), word w of a mask of the proxies to visit (the direct and
// directional passes: the proxies its workgroup's bin lists for the light; one left out
// occludes nothing there, so the result is the same), and GI_PROXY_WORDS, its length. Then
// they are visited in ascending order, as without a mask:
//     for (ProxyCursor c = proxy_list(); proxy_step(c);) { ... proxy c.i ... }
// With PROXY_REGISTERS (the frame's proxies fit two mask words, gi_common.glsl) the words are read
// once, into the cursor: proxy_next reads a word per proxy visited and loops over the empty
// words, and lavapipe runs every storage-buffer load lane by lane and every loop at least
// once, masked, so each visit paid two loads and an inner loop (docs/performance.md).
#ifdef GI_PROXY_MASK
int proxy_next(int i) {
    int j = i + 1;
    int w = j >> 5;
    if (w >= GI_PROXY_WORDS) return pc.counts.w;
    uint bits = GI_PROXY_MASK(w) & (~0u << uint(j & 31));
    while (bits == 0u) {
        if (++w >= GI_PROXY_WORDS) return pc.counts.w;
        bits = GI_PROXY_MASK(w);
    }
    return w * 32 + findLSB(bits);
}
#else
int proxy_next(int i) { return i + 1; }
#endif

struct ProxyCursor {
    int i;       // the proxy visited (-1 before the first)
    uint lo, hi; // PROXY_REGISTERS: the list's words 0 and 1, less the proxies visited
};
ProxyCursor proxy_list() {
    ProxyCursor c;
    c.i = -1;
#ifdef GI_PROXY_MASK
    c.lo = PROXY_REGISTERS && GI_PROXY_WORDS > 0 ? GI_PROXY_MASK(0) : 0u;
    c.hi = PROXY_REGISTERS && GI_PROXY_WORDS > 1 ? GI_PROXY_MASK(1) : 0u;
#else
    c.lo = c.hi = 0u;
#endif
    return c;
}
// Moves to the next proxy of the list (c.i); false past the last.
bool proxy_step(inout ProxyCursor c) {
#ifdef GI_PROXY_MASK
    if (PROXY_REGISTERS) {
        bool more = (c.lo | c.hi) != 0u;
        c.i = c.lo != 0u ? findLSB(c.lo) : 32 + findLSB(c.hi);
        if (c.lo != 0u) c.lo &= c.lo - 1u;
        else c.hi &= c.hi - 1u;
        return more;
    }
#endif
    c.i = proxy_next(c.i);
    return c.i < pc.counts.w;
}

// The axis of proxy p's shadow from a point light (reference_shadow.cpp point_shadow_axis).
bool point_shadow_axis(GpuShadowProxy p, vec2 light, vec2 dir, out vec2 dir_shadow) {
    precise vec2 to_proxy = p.position_size.xy - light;
    precise float proxy_dist = gi_length(to_proxy);
    dir_shadow = vec2(0.0);
    if (proxy_dist < 1e-4) return false;
    precise vec2 dir_flat = gi_div(to_proxy, proxy_dist);
    float blend = saturate(p.lengths.y);
    precise vec2 blended = dir * (1.0 - blend) + dir_flat * blend; // glm::mix, operation for operation
    precise float blended_len = gi_length(blended);
    dir_shadow = blended_len > 1e-6 ? gi_div(blended, blended_len) : dir_flat;
    precise float ahead = to_proxy.x * dir_shadow.x + to_proxy.y * dir_shadow.y;
    return ahead > 0.0;
}

float point_proxy_shadow(vec2 light, vec2 pixel) {
    if (!HAS_PROXIES) return 1.0;
    precise vec2 ray = pixel - light;
    precise float ray_len = gi_length(ray);
    if (ray_len < 1e-4) return 1.0;
    precise vec2 dir = gi_div(ray, ray_len);
    float shadow = 1.0;
    for (ProxyCursor c = proxy_list(); proxy_step(c);) {
        GpuShadowProxy p = u_proxies.proxies[c.i];
        vec2 dir_shadow;
        if (!point_shadow_axis(p, light, dir, dir_shadow)) continue;
        shadow = min(shadow, 1.0 - proxy_occlusion(p, pixel, dir_shadow));
        if (shadow <= 0.001) break;
    }
    return shadow;
}

float directional_proxy_shadow(vec2 pixel, vec3 light_dir) {
    if (!HAS_PROXIES) return 1.0;
    precise float xz_length = gi_length(light_dir.xz);
    if (xz_length < 1e-4) return 1.0;
    precise vec2 travel = vec2(gi_div(light_dir.x, xz_length), gi_div(light_dir.z, xz_length));
    float shadow = 1.0;
    for (ProxyCursor c = proxy_list(); proxy_step(c);) {
        shadow = min(shadow, 1.0 - proxy_occlusion(u_proxies.proxies[c.i], pixel, travel));
        if (shadow <= 0.001) break;
    }
    return shadow;
}

// gi.proxy_wall_shadows = unfold (reference_shadow.cpp point_proxy_face_shadow): the
// proxies' visibility of a face point at the face's foot (x) and top (y, the ground
// `height` beyond it along the light's travel), and the height where their shadows end (z).
float proxy_length_edge(GpuShadowProxy p) {
    float edge = p.lengths.x, width = p.lengths.w;
    if (!(width > 0.0)) return edge;
    int mode = int(p.modes.w + 0.5);
    float lo = mode == 0 ? edge - width : (mode == 1 ? edge : edge - 0.5 * width);
    return lo + 0.5 * width;
}

float unfolded_reach(GpuShadowProxy p, vec2 target, vec2 travel, vec2 dir_shadow) {
    precise vec2 to_target = target - p.position_size.xy;
    precise float along = to_target.x * dir_shadow.x + to_target.y * dir_shadow.y;
    precise float rate = max(travel.x * dir_shadow.x + travel.y * dir_shadow.y, 1e-3);
    return gi_div(proxy_length_edge(p) - along, rate);
}

vec3 point_proxy_face_shadow(vec2 light, vec2 target, float height) {
    vec3 s = vec3(1.0, 1.0, 0.0);
    if (!HAS_PROXIES) return s;
    precise vec2 ray = target - light;
    precise float ray_len = gi_length(ray);
    if (ray_len < 1e-4) return s;
    precise vec2 dir = gi_div(ray, ray_len);
    s.x = point_proxy_shadow(light, target);
    s.y = point_proxy_shadow(light, target + dir * height);
    if (!(s.y > s.x)) return s;
    float reach = 0.0;
    for (ProxyCursor c = proxy_list(); proxy_step(c);) {
        GpuShadowProxy p = u_proxies.proxies[c.i];
        vec2 dir_shadow;
        if (point_shadow_axis(p, light, dir, dir_shadow) && proxy_occlusion(p, target, dir_shadow) > 0.0)
            reach = max(reach, unfolded_reach(p, target, dir, dir_shadow));
    }
    s.z = clamp(reach, 0.0, height);
    return s;
}

vec3 directional_proxy_face_shadow(vec2 target, vec3 light_dir, float height) {
    vec3 s = vec3(1.0, 1.0, 0.0);
    precise float xz_length = gi_length(light_dir.xz);
    if (!HAS_PROXIES || xz_length < 1e-4) return s;
    precise vec2 travel = vec2(gi_div(light_dir.x, xz_length), gi_div(light_dir.z, xz_length));
    s.x = directional_proxy_shadow(target, light_dir);
    s.y = directional_proxy_shadow(target + travel * height, light_dir);
    if (!(s.y > s.x)) return s;
    float reach = 0.0;
    for (ProxyCursor c = proxy_list(); proxy_step(c);) {
        GpuShadowProxy p = u_proxies.proxies[c.i];
        if (proxy_occlusion(p, target, travel) > 0.0) reach = max(reach, unfolded_reach(p, target, travel, travel));
    }
    s.z = clamp(reach, 0.0, height);
    return s;
}

#endif
