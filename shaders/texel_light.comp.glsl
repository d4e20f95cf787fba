#version 450
// Per-texel lighting, the light pass (seed 001's DynamicLight and Apply kernels;
// engine/texel/texel.hpp): one invocation per atlas texel sums the lights in its placement's
// light list (texel::light_lists: those in reach): the seed's term, the wall grid's and the
// other models' shadows, the light's ambient. It then writes the raw sum (mode 0: bake) or
// saturate(sum + baked) (mode 1: realtime). The bake leaves placements that move out, as
// receivers (0) and as occluders; the realtime pass skips baked lights (blur.w 1) on still
// placements, whose baked light holds them (texel::LightPass; their lists leave them out).
#extension GL_GOOGLE_include_directive : require
#include "lantern/texel.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Triangles { TexelTriangle triangles[]; };
layout(std430, set = 0, binding = 1) readonly buffer Placements { TexelPlacement placements[]; };
layout(std430, set = 0, binding = 2) readonly buffer Surfaces { TexelSurface surfaces[]; };
layout(std430, set = 0, binding = 3) readonly buffer Lights { TexelLight lights[]; };
layout(std430, set = 0, binding = 4) readonly buffer Walls { uint wall_words[]; };
layout(std430, set = 0, binding = 5) readonly buffer Baked { vec4 baked[]; };
layout(std430, set = 0, binding = 6) writeonly buffer Result { vec4 result[]; };
// Per placement the lights that can reach it (texel::light_lists): words 2k, 2k + 1 its first
// index and count, the indices after the 2 x placements words. In the lights' order: every
// sum is the one over all lights.
layout(std430, set = 0, binding = 7) readonly buffer LightLists { uint light_lists[]; };

const float RAY_BIAS = 1e-4;
const float DIR_EPS = 1e-6;
const float CORNER_EPS = 1e-5;
const float BIG = 1e30;

bool is_wall(int x, int z) {
    const int c = x - pc.walls.x, r = z - pc.walls.y;
    if (c < 0 || r < 0 || c >= pc.walls.z || r >= pc.walls.w) return false;
    const uint i = uint(c) + uint(r) * uint(pc.walls.z);
    return ((wall_words[i >> 2u] >> ((i & 3u) * 8u)) & 0xffu) != 0u;
}

float first_boundary(float start, float dir, int stp) {
    if (abs(dir) < DIR_EPS) return BIG;
    precise float cell = floor(start);
    precise float num = stp > 0 ? cell + 1.0 - start : start - cell;
    return gi_div(num, stp > 0 ? dir : -dir);
}
float boundary_step(float dir) { return abs(dir) < DIR_EPS ? BIG : abs(gi_div(1.0, dir)); }
int sign_of(float v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }

float height_at(float t, float light_y, float rise, float full_length) {
    precise float along = t + RAY_BIAS;
    precise float h = light_y + rise * gi_div(along, full_length);
    return h;
}

float wall_visibility(vec3 light, vec3 point) {
    const float wall_height = pc.params.x;
    precise vec2 ray = vec2(point.x - light.x, point.z - light.z);
    float ray_length = gi_length(ray);
    if (ray_length < 1e-4) return 1.0;
    const float full_length = ray_length;
    const vec2 dir = gi_div(ray, ray_length);
    precise vec2 start = vec2(light.x, light.z) + dir * RAY_BIAS;
    precise vec2 end_pos = vec2(point.x, point.z) - dir * RAY_BIAS;
    precise float shortened = ray_length - 2.0 * RAY_BIAS;
    ray_length = max(shortened, 0.0);
    precise float rise = point.y - light.y;

    ivec2 cell = ivec2(floor(start));
    const ivec2 end_cell = ivec2(floor(end_pos));
    const ivec2 stp = ivec2(sign_of(dir.x), sign_of(dir.y));
    precise vec2 t_max = vec2(first_boundary(start.x, dir.x, stp.x), first_boundary(start.y, dir.y, stp.y));
    const vec2 t_delta = vec2(boundary_step(dir.x), boundary_step(dir.y));
    const int max_steps = max(1, int(ceil(min(full_length, 1e7) * 2.0)) + 2);
    float entered = 0.0;
    for (int i = 0; i < max_steps; ++i) {
        if (is_wall(cell.x, cell.y)) {
            const float left = min(min(t_max.x, t_max.y), ray_length);
            if (min(height_at(entered, light.y, rise, full_length), height_at(left, light.y, rise, full_length)) <
                wall_height)
                return 0.0;
        }
        if (cell == end_cell) return 1.0;
        float traveled;
        if (t_max.x < t_max.y - CORNER_EPS) {
            traveled = t_max.x;
            t_max.x += t_delta.x;
            cell.x += stp.x;
        } else if (t_max.y < t_max.x - CORNER_EPS) {
            traveled = t_max.y;
            t_max.y += t_delta.y;
            cell.y += stp.y;
        } else {
            traveled = t_max.x;
            if (is_wall(cell.x + stp.x, cell.y) && is_wall(cell.x, cell.y + stp.y) &&
                height_at(min(traveled, ray_length), light.y, rise, full_length) < wall_height)
                return 0.0;
            t_max += t_delta;
            cell += stp;
        }
        if (traveled > ray_length) return 1.0;
        entered = traveled;
    }
    return 1.0;
}

bool inside_triangle_3d(vec3 p, uint t) {
    const vec3 a = triangles[t].p1.xyz;
    precise vec3 v0 = triangles[t].p2.xyz - a, v1 = triangles[t].p3.xyz - a, v2 = p - a;
    const float d00 = texel_dot(v0, v0), d01 = texel_dot(v0, v1), d11 = texel_dot(v1, v1);
    const float d20 = texel_dot(v2, v0), d21 = texel_dot(v2, v1);
    precise float denom = d00 * d11 - d01 * d01;
    if (denom == 0.0) return false;
    precise float vn = d11 * d20 - d01 * d21, wn = d00 * d21 - d01 * d20;
    return texel_inside(gi_div(vn, denom), gi_div(wn, denom));
}

// Conservative: false only when the segment cannot touch the sphere (only skips work).
bool segment_meets_sphere(vec3 a, vec3 dir, float len, vec4 sphere) {
    const float t = clamp(dot(sphere.xyz - a, dir), 0.0, len);
    const vec3 d = sphere.xyz - (a + dir * t);
    const float r = sphere.w * 1.001 + 2e-3;
    return dot(d, d) <= r * r;
}

// Placement k moves (its triangles' uv3.w, texel::Placement::moves).
bool placement_moves(uvec4 ranges) { return ranges.y > 0u && triangles[ranges.x].uv3.w > 0.5; }

float occluder_visibility(uint l, vec3 origin, vec3 point, int own) {
    precise vec3 to_point = point - origin;
    const float lr = texel_length(to_point);
    if (!(lr > 0.0)) return 1.0;
    const vec3 dir = texel_div(to_point, lr);
    const bool hard = int(lights[l].color_type.w + 0.5) == 1;
    float nearest = -1.0;
    for (uint k = 0u; k < pc.counts.y; ++k) {
        if (!segment_meets_sphere(origin, dir, lr, placements[k].bounds)) continue;
        const uvec4 ranges = placements[k].ranges;
        if (pc.counts.w == 0u && placement_moves(ranges)) continue; // the bake: still occluders only
        for (uint i = ranges.x; i < ranges.x + ranges.y; ++i) {
            if (int(i) == own) continue;
            const vec3 n = triangles[i].normal.xyz;
            const float facing = texel_dot(dir, n);
            if (!(facing < 0.0)) continue;
            precise vec3 to_plane = triangles[i].p3.xyz - origin;
            const float along = gi_div(texel_dot(to_plane, n), facing);
            precise float limit = lr - TEXEL_INSIDE_EPS;
            if (!(along > 0.0) || along >= limit) continue;
            precise vec3 hit = origin + along * dir;
            if (!inside_triangle_3d(hit, i)) continue;
            if (hard) return 0.0;
            precise vec3 back = hit - point;
            const float nlr = texel_length(back);
            nearest = nearest < 0.0 ? nlr : min(nearest, nlr);
        }
    }
    if (nearest < 0.0) return 1.0;
    const float ratio = gi_div(nearest, lr);
    const float power = lights[l].blur.y;
    precise float blur = (power == 1.0 ? ratio : pow(ratio, power)) * lights[l].blur.x;
    return clamp(blur, 0.0, 1.0);
}

float sun_visibility(uint l, vec3 point, int own) {
    const vec3 dir = lights[l].position_range.xyz;
    const float reach = lights[l].position_range.w;
    float clear = reach;
    if (dir.y < 0.0) {
        precise float above = pc.params.x - point.y;
        clear = min(reach, max(gi_div(above, -dir.y), 0.0));
    }
    if (clear > 0.0) {
        precise vec3 from = point - dir * clear;
        if (wall_visibility(from, point) == 0.0) return 0.0;
    }
    precise vec3 origin = point - dir * reach;
    return occluder_visibility(l, origin, point, own);
}

void main() {
    const uint texel = gl_GlobalInvocationID.x;
    if (texel >= pc.counts.x) return;
    const TexelSurface s = surfaces[texel];
    if (s.position_used.w == 0.0) {
        result[texel] = vec4(0.0);
        return;
    }
    const vec3 p = s.position_used.xyz, n = s.normal_triangle.xyz, g = s.geo_normal.xyz;
    const int own = int(s.normal_triangle.w + 0.5);
    const bool bake = pc.counts.w == 0u;
    const bool moves = triangles[own].uv3.w > 0.5;
    if (bake && moves) { // all of its light is realtime
        result[texel] = vec4(0.0);
        return;
    }
    precise vec3 sum = vec3(0.0);
    // The placement's lights: those in reach, without baked ones on still placements in the
    // realtime pass (in baked[]: texel::light_lists).
    const uint placement = uint(triangles[own].uv3.z + 0.5);
    const uint first = 2u * pc.counts.y + light_lists[2u * placement], count = light_lists[2u * placement + 1u];
    for (uint j = 0u; j < count; ++j) {
        const uint l = light_lists[first + j];
        const bool shadowed = int(lights[l].color_type.w + 0.5) != 0;
        if (lights[l].blur.z > 0.5) { // a sun
            const vec3 sun_dir = lights[l].position_range.xyz;
            sum += lights[l].ambient.rgb;
            const float c = texel_dot(sun_dir, n);
            if (!(c < 0.0) || !(texel_dot(sun_dir, g) < 0.0)) continue;
            const float shade = shadowed ? sun_visibility(l, p, own) : 1.0;
            precise float value = abs(c);
            precise float weight = shade * value * value;
            sum += lights[l].color_type.rgb * weight;
            continue;
        }
        precise vec3 from_light = p - lights[l].position_range.xyz;
        const float d = texel_length(from_light);
        const float range = lights[l].position_range.w;
        if (!(d < range) || !(d > 0.0)) continue;
        precise float falloff = 1.0 - gi_div(d, range);
        sum += lights[l].ambient.rgb * falloff;
        const vec3 dir = texel_div(from_light, d);
        const float c = texel_dot(dir, n);
        if (!(c < 0.0) || !(texel_dot(dir, g) < 0.0)) continue;
        float shade = 1.0;
        if (shadowed) {
            shade = wall_visibility(lights[l].position_range.xyz, p);
            if (shade > 0.0) shade = occluder_visibility(l, lights[l].position_range.xyz, p, own);
        }
        precise float value = falloff * abs(c);
        precise float weight = shade * value * value;
        sum += lights[l].color_type.rgb * weight;
    }
    vec4 total = vec4(sum, 1.0);
    if (pc.counts.w == 1u) total = clamp(total + baked[texel], vec4(0.0), vec4(1.0));
    result[texel] = total;
}
