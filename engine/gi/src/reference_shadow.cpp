// Shadow building blocks of the reference: grid traversals, shadow proxies, falloff and
// wall-face weights. Constants and control flow follow seed 000 exactly.
#include "lantern/gi/reference.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::gi {
namespace {

constexpr float ray_bias = 1e-4f;    // keeps floor() stable on grid lines
constexpr float dir_eps = 1e-6f;     // near-zero direction component
constexpr float corner_eps = 1e-5f;  // "both boundaries at once" tolerance
constexpr float big = 1e30f;

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }

// Distance along the ray to the first x (or z) cell boundary.
float first_boundary(float start, float dir, int step) {
    if (std::abs(dir) < dir_eps) return big;
    const float cell = std::floor(start);
    return step > 0 ? (cell + 1.0f - start) / dir : (start - cell) / -dir;
}

float boundary_step(float dir) { return std::abs(dir) < dir_eps ? big : std::abs(1.0f / dir); }

int sign_of(float v) { return v > 0.0f ? 1 : v < 0.0f ? -1 : 0; }

} // namespace

float shadow_dda(const WallView& walls, glm::vec2 light, glm::vec2 pixel, float radius) {
    const glm::vec2 ray = pixel - light;
    float ray_length = std::sqrt(ray.x * ray.x + ray.y * ray.y);
    if (ray_length < 1e-4f) return 1.0f;
    const glm::vec2 dir = ray / ray_length;
    const glm::vec2 start = light + dir * ray_bias;
    const glm::vec2 end = pixel - dir * ray_bias;
    ray_length = std::max(ray_length - 2.0f * ray_bias, 0.0f);

    glm::ivec2 cell(int(std::floor(start.x)), int(std::floor(start.y)));
    const glm::ivec2 end_cell(int(std::floor(end.x)), int(std::floor(end.y)));
    const glm::ivec2 step(sign_of(dir.x), sign_of(dir.y));
    glm::vec2 t_max(first_boundary(start.x, dir.x, step.x), first_boundary(start.y, dir.y, step.y));
    const glm::vec2 t_delta(boundary_step(dir.x), boundary_step(dir.y));
    const int max_steps = std::max(1, int(std::ceil(radius * 2.0f)) + 2);

    for (int i = 0; i < max_steps; ++i) {
        if (walls.is_wall(cell.x, cell.y)) return 0.0f;
        if (cell == end_cell) return 1.0f;
        float traveled;
        if (t_max.x < t_max.y - corner_eps) {
            traveled = t_max.x;
            t_max.x += t_delta.x;
            cell.x += step.x;
        } else if (t_max.y < t_max.x - corner_eps) {
            traveled = t_max.y;
            t_max.y += t_delta.y;
            cell.y += step.y;
        } else {
            // Through a grid corner: blocked only if both side cells are walls.
            traveled = t_max.x;
            if (walls.is_wall(cell.x + step.x, cell.y) && walls.is_wall(cell.x, cell.y + step.y)) return 0.0f;
            t_max += t_delta;
            cell += step;
        }
        if (traveled > ray_length) return 1.0f;
    }
    return 1.0f;
}

namespace {

bool blocks_directional_cell(const WallView& walls, glm::ivec2 cell, glm::vec2 start, glm::vec3 to_sun,
                             float to_sun_xz_length, float wall_height) {
    if (!walls.is_wall(cell.x, cell.y)) return false;
    const glm::vec2 d = glm::vec2(cell) + 0.5f - start;
    const float distance_to_wall = std::sqrt(d.x * d.x + d.y * d.y);
    if (std::abs(to_sun.y) > 0.001f && to_sun_xz_length > 1e-4f) {
        const float vertical_rate = to_sun.y / to_sun_xz_length;
        return distance_to_wall * vertical_rate < wall_height;
    }
    return true;
}

// True when the traversal can never meet a wall again: outside the grid and stepping away
// from it along an axis it is outside on (so the result does not depend on how far the
// grid extends: tiles outside it are air).
bool leaving_grid(const WallView& walls, glm::ivec2 cell, glm::ivec2 step) {
    const glm::ivec2 lo = walls.origin, hi = walls.origin + glm::ivec2(walls.width, walls.height);
    return (cell.x < lo.x && step.x <= 0) || (cell.x >= hi.x && step.x >= 0) || (cell.y < lo.y && step.y <= 0) ||
           (cell.y >= hi.y && step.y >= 0);
}

} // namespace

float directional_shadow_dda(const WallView& walls, glm::vec2 pixel, glm::vec3 light_dir, float max_distance,
                             float wall_height) {
    const glm::vec3 to_sun = -light_dir;
    const float xz_length = std::sqrt(to_sun.x * to_sun.x + to_sun.z * to_sun.z);
    if (xz_length < 1e-4f) return 1.0f; // sun overhead: nothing casts a grid shadow
    const glm::vec2 dir(to_sun.x / xz_length, to_sun.z / xz_length);
    const glm::vec2 start = pixel + dir * ray_bias;
    glm::ivec2 cell(int(std::floor(start.x)), int(std::floor(start.y)));
    const glm::ivec2 step(sign_of(dir.x), sign_of(dir.y));
    glm::vec2 t_max(first_boundary(start.x, dir.x, step.x), first_boundary(start.y, dir.y, step.y));
    const glm::vec2 t_delta(boundary_step(dir.x), boundary_step(dir.y));
    // A straight line crosses at most 2 cells per unit of length (plus the ends).
    const int max_steps = 2 * int(std::ceil(std::min(max_distance, 1e6f))) + 2;

    for (int i = 0; i < max_steps; ++i) {
        if (blocks_directional_cell(walls, cell, start, to_sun, xz_length, wall_height)) return 0.0f;
        if (t_max.x < t_max.y) {
            t_max.x += t_delta.x;
            cell.x += step.x;
        } else {
            t_max.y += t_delta.y;
            cell.y += step.y;
        }
        if (std::min(t_max.x, t_max.y) > max_distance) return 1.0f;
        if (leaving_grid(walls, cell, step)) return 1.0f;
    }
    return 1.0f;
}

float penumbra_factor(float distance, float edge, float width, float power, int mode) {
    if (!(width > 0.0f)) return distance <= edge ? 1.0f : 0.0f;
    // The soft band [lo, lo + width] runs from full occlusion to none.
    const float lo = mode == 0 ? edge - width : mode == 1 ? edge : edge - 0.5f * width;
    const float t = saturate((lo + width - distance) / width);
    return std::pow(t, power);
}

float proxy_width(const GpuShadowProxy& p, glm::vec2 perp) {
    const bool circle = p.modes.y > 0.5f;
    if (circle) return p.position_size.z;
    const glm::vec2 half(p.position_size.z, p.position_size.w);
    if (p.modes.z > 0.5f) return std::max(half.x, half.y); // max axis
    return std::abs(perp.x) * half.x + std::abs(perp.y) * half.y; // projected
}

namespace {

// Occlusion of one proxy for light travelling along `dir_shadow` past it.
float proxy_occlusion(const GpuShadowProxy& p, glm::vec2 pixel, glm::vec2 dir_shadow) {
    const glm::vec2 perp(-dir_shadow.y, dir_shadow.x);
    const glm::vec2 position(p.position_size.x, p.position_size.y);
    const glm::vec2 to_pixel = pixel - position;
    const float along = glm::dot(to_pixel, dir_shadow);
    if (along <= 0.0f) return 0.0f;
    const float max_length = p.lengths.x, pen_width = p.lengths.z, pen_length = p.lengths.w;
    if (along > max_length + pen_length) return 0.0f;
    const float perp_dist = std::abs(glm::dot(to_pixel, perp));
    const float power = p.modes.x;
    const int mode = int(p.modes.w + 0.5f);
    const float edge = penumbra_factor(perp_dist, proxy_width(p, perp), pen_width, power, mode);
    const float len = penumbra_factor(along, max_length, pen_length, power, mode);
    return edge * len * p.fade.x; // a strength of 1 changes nothing, bit for bit
}

} // namespace

namespace {

// Beyond this distance from its position proxy p occludes nothing: its shadow is at most
// max_length + penumbra_length long and its width plus penumbra_width wide (the GPU's
// gi_light_bins lists per workgroup only the proxies within it; gi_types.glsl's twin).
bool out_of_reach(const GpuShadowProxy& p, glm::vec2 point) {
    const float along = std::max(p.lengths.x + p.lengths.w, 0.0f);
    const float across = std::abs(p.position_size.z) + std::abs(p.position_size.w) + std::max(p.lengths.z, 0.0f);
    const float reach = std::sqrt(along * along + across * across) * 1.0001f + 1e-3f;
    const glm::vec2 d = point - glm::vec2(p.position_size.x, p.position_size.y);
    return d.x * d.x + d.y * d.y > reach * reach;
}

// The axis of proxy p's shadow from a point light at `light` for a ray along `dir`; false
// when the proxy casts none (it is at the light, or behind it).
bool point_shadow_axis(const GpuShadowProxy& p, glm::vec2 light, glm::vec2 dir, glm::vec2& dir_shadow) {
    const glm::vec2 to_proxy = glm::vec2(p.position_size.x, p.position_size.y) - light;
    const float proxy_dist = std::sqrt(to_proxy.x * to_proxy.x + to_proxy.y * to_proxy.y);
    if (proxy_dist < 1e-4f) return false;
    const glm::vec2 dir_flat = to_proxy / proxy_dist;
    // End-cap blend: rotate the shadow axis from the pixel ray towards the proxy axis.
    const glm::vec2 blended = glm::mix(dir, dir_flat, saturate(p.lengths.y));
    const float blended_len = std::sqrt(blended.x * blended.x + blended.y * blended.y);
    dir_shadow = blended_len > 1e-6f ? blended / blended_len : dir_flat;
    return glm::dot(to_proxy, dir_shadow) > 0.0f;
}

} // namespace

float point_proxy_shadow(std::span<const GpuShadowProxy> proxies, glm::vec2 light, glm::vec2 pixel) {
    if (proxies.empty()) return 1.0f;
    const glm::vec2 ray = pixel - light;
    const float ray_len = std::sqrt(ray.x * ray.x + ray.y * ray.y);
    if (ray_len < 1e-4f) return 1.0f;
    const glm::vec2 dir = ray / ray_len;
    float shadow = 1.0f;
    for (const GpuShadowProxy& p : proxies) {
        glm::vec2 dir_shadow;
        if (out_of_reach(p, pixel) || !point_shadow_axis(p, light, dir, dir_shadow)) continue;
        shadow = std::min(shadow, 1.0f - proxy_occlusion(p, pixel, dir_shadow));
        if (shadow <= 0.001f) break;
    }
    return shadow;
}

namespace {

// Where the proxy's length penumbra is half way (penumbra_factor's band [lo, lo + width]).
float length_edge(const GpuShadowProxy& p) {
    const float edge = p.lengths.x, width = p.lengths.w;
    if (!(width > 0.0f)) return edge;
    const int mode = int(p.modes.w + 0.5f);
    const float lo = mode == 0 ? edge - width : mode == 1 ? edge : edge - 0.5f * width;
    return lo + 0.5f * width;
}

// The height up the face where proxy p's shadow (axis dir_shadow) ends, for a face point
// `target` unfolded along `travel`.
float unfolded_reach(const GpuShadowProxy& p, glm::vec2 target, glm::vec2 travel, glm::vec2 dir_shadow) {
    const glm::vec2 to_target = target - glm::vec2(p.position_size.x, p.position_size.y);
    const float along = to_target.x * dir_shadow.x + to_target.y * dir_shadow.y;
    const float rate = std::max(travel.x * dir_shadow.x + travel.y * dir_shadow.y, 1e-3f);
    return (length_edge(p) - along) / rate;
}

} // namespace

FaceProxyShadow point_proxy_face_shadow(std::span<const GpuShadowProxy> proxies, glm::vec2 light, glm::vec2 target,
                                        float height) {
    FaceProxyShadow s;
    if (proxies.empty()) return s;
    const glm::vec2 ray = target - light;
    const float ray_len = std::sqrt(ray.x * ray.x + ray.y * ray.y);
    if (ray_len < 1e-4f) return s;
    const glm::vec2 dir = ray / ray_len;
    s.low = point_proxy_shadow(proxies, light, target);
    s.high = point_proxy_shadow(proxies, light, target + dir * height);
    if (!(s.high > s.low)) return s;
    float reach = 0.0f;
    for (const GpuShadowProxy& p : proxies) { // the proxies shading the foot, as point_proxy_shadow
        glm::vec2 dir_shadow;
        if (!out_of_reach(p, target) && point_shadow_axis(p, light, dir, dir_shadow) && proxy_occlusion(p, target, dir_shadow) > 0.0f)
            reach = std::max(reach, unfolded_reach(p, target, dir, dir_shadow));
    }
    s.edge = std::clamp(reach, 0.0f, height);
    return s;
}

FaceProxyShadow directional_proxy_face_shadow(std::span<const GpuShadowProxy> proxies, glm::vec2 target,
                                              glm::vec3 light_dir, float height) {
    FaceProxyShadow s;
    const float xz_length = std::sqrt(light_dir.x * light_dir.x + light_dir.z * light_dir.z);
    if (proxies.empty() || xz_length < 1e-4f) return s;
    const glm::vec2 travel(light_dir.x / xz_length, light_dir.z / xz_length);
    s.low = directional_proxy_shadow(proxies, target, light_dir);
    s.high = directional_proxy_shadow(proxies, target + travel * height, light_dir);
    if (!(s.high > s.low)) return s;
    float reach = 0.0f;
    for (const GpuShadowProxy& p : proxies)
        if (proxy_occlusion(p, target, travel) > 0.0f) reach = std::max(reach, unfolded_reach(p, target, travel, travel));
    s.edge = std::clamp(reach, 0.0f, height);
    return s;
}

bool unfolds_proxy_shadows(const FrameInputs& in) {
    return in.settings.proxy_wall_shadows == scene::ProxyWallShadows::unfold && !in.proxies.empty() &&
           computed_faces(in.settings) != 0 && in.wall_height > 0.0f;
}

float directional_proxy_shadow(std::span<const GpuShadowProxy> proxies, glm::vec2 pixel, glm::vec3 light_dir) {
    const float xz_length = std::sqrt(light_dir.x * light_dir.x + light_dir.z * light_dir.z);
    if (proxies.empty() || xz_length < 1e-4f) return 1.0f;
    const glm::vec2 travel(light_dir.x / xz_length, light_dir.z / xz_length);
    float shadow = 1.0f;
    for (const GpuShadowProxy& p : proxies) {
        shadow = std::min(shadow, 1.0f - proxy_occlusion(p, pixel, travel));
        if (shadow <= 0.001f) break;
    }
    return shadow;
}

float light_falloff(float distance, float radius, float softness) {
    return std::pow(1.0f - saturate(distance / radius), softness);
}

glm::vec4 wall_face_mask(const WallView& walls, glm::ivec2 c) {
    return glm::vec4(walls.is_wall(c.x + 1, c.y) ? 0.0f : 1.0f, walls.is_wall(c.x - 1, c.y) ? 0.0f : 1.0f,
                     walls.is_wall(c.x, c.y + 1) ? 0.0f : 1.0f, walls.is_wall(c.x, c.y - 1) ? 0.0f : 1.0f);
}

std::uint32_t computed_faces(const scene::GiSettings& gi) {
    if (!gi.wall_lighting) return 0;
    return (gi.wall_faces.px ? 1u : 0u) | (gi.wall_faces.nx ? 2u : 0u) | (gi.wall_faces.pz ? 4u : 0u) |
           (gi.wall_faces.nz ? 8u : 0u);
}

glm::vec4 face_bits_mask(std::uint32_t faces) {
    return glm::vec4(computes_face(faces, 0) ? 1.0f : 0.0f, computes_face(faces, 1) ? 1.0f : 0.0f,
                     computes_face(faces, 2) ? 1.0f : 0.0f, computes_face(faces, 3) ? 1.0f : 0.0f);
}

glm::vec4 wall_facing(glm::vec2 d, float exponent) {
    const glm::vec4 w(saturate(d.x), saturate(-d.x), saturate(d.y), saturate(-d.y));
    if (exponent == 1.0f) return w; // today's images, bit for bit
    return glm::vec4(std::pow(w.x, exponent), std::pow(w.y, exponent), std::pow(w.z, exponent),
                     std::pow(w.w, exponent));
}

float bayer4(int x, int y) {
    static constexpr int m[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
    return (float(m[y & 3][x & 3]) + 0.5f) / 16.0f;
}

} // namespace lantern::gi
