// The C++ reference of the texel passes (texel.hpp). shaders/include/lantern/texel.glsl is its
// twin, operation for operation: float only, no fused multiply-adds (the shaders mark every
// step `precise` and divide and take roots through gi_exact.glsl), so that the GPU's inside
// tests, cell steps and occluder hits decide as these do.
#include "lantern/texel/texel.hpp"

#include <algorithm>
#include <cmath>

namespace lantern::texel {
namespace {

constexpr float ray_bias = 1e-4f;   // gi::shadow_dda's: keeps floor() stable on grid lines
constexpr float dir_eps = 1e-6f;
constexpr float corner_eps = 1e-5f; // "both boundaries at once"
constexpr float big = 1e30f;

float first_boundary(float start, float dir, int step) {
    if (std::abs(dir) < dir_eps) return big;
    const float cell = std::floor(start);
    return step > 0 ? (cell + 1.0f - start) / dir : (start - cell) / -dir;
}
float boundary_step(float dir) { return std::abs(dir) < dir_eps ? big : std::abs(1.0f / dir); }
int sign_of(float v) { return v > 0.0f ? 1 : v < 0.0f ? -1 : 0; }

float dot3(glm::vec3 a, glm::vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
float length3(glm::vec3 v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

// The texel's UV and the barycentric (v, w) of it in triangle t's UV corners; false when the
// triangle has no area in UV.
bool uv_barycentric(const GpuTriangle& t, glm::vec2 uv, float& v, float& w) {
    const glm::vec2 p1(t.uv12.x, t.uv12.y), p2(t.uv12.z, t.uv12.w), p3(t.uv3.x, t.uv3.y);
    const float denom = (p2.x - p1.x) * (p3.y - p1.y) - (p3.x - p1.x) * (p2.y - p1.y);
    if (denom == 0.0f) return false;
    v = ((uv.x - p1.x) * (p3.y - p1.y) - (p3.x - p1.x) * (uv.y - p1.y)) / denom;
    w = ((p2.x - p1.x) * (uv.y - p1.y) - (uv.x - p1.x) * (p2.y - p1.y)) / denom;
    return true;
}

bool inside(float v, float w) { return -inside_eps <= v && -inside_eps <= w && v + w <= 1.0f + inside_eps; }

glm::vec2 texel_uv(int x, int y, int size) {
    return glm::vec2((float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size));
}

TexelSurface surface_on(const GpuTriangle& t, std::uint32_t index, float v, float w, glm::vec4 nm) {
    const glm::vec3 p1(t.p1), p2(t.p2), p3(t.p3);
    TexelSurface s;
    const glm::vec3 e1 = p2 - p1, e2 = p3 - p1;
    const glm::vec3 pos = p1 + (v * e1 + w * e2);
    s.position_used = glm::vec4(pos, 1.0f);
    // The seed's normal map: green flipped (binormal runs down the texture, green up it),
    // then [0, 1] -> [-1, 1], the tangent frame weighted by it.
    const glm::vec3 m = glm::vec3(nm.r, 1.0f - nm.g, nm.b) * 2.0f - 1.0f;
    const glm::vec3 mapped = glm::vec3(t.normal) * m.z + glm::vec3(t.binormal) * m.y + glm::vec3(t.tangent) * m.x;
    const float len = length3(mapped);
    s.normal_triangle = glm::vec4(len > 0.0f ? mapped / len : glm::vec3(t.normal), float(index));
    s.geo_normal = glm::vec4(glm::vec3(t.normal), 0.0f);
    return s;
}

// The seed's checkIntersectionInTri (Real-Time Collision Detection 3.4).
bool inside_triangle_3d(glm::vec3 p, const GpuTriangle& t) {
    const glm::vec3 a(t.p1), b(t.p2), c(t.p3);
    const glm::vec3 v0 = b - a, v1 = c - a, v2 = p - a;
    const float d00 = dot3(v0, v0), d01 = dot3(v0, v1), d11 = dot3(v1, v1), d20 = dot3(v2, v0), d21 = dot3(v2, v1);
    const float denom = d00 * d11 - d01 * d01;
    if (denom == 0.0f) return false;
    const float v = (d11 * d20 - d01 * d21) / denom;
    const float w = (d00 * d21 - d01 * d20) / denom;
    return inside(v, w);
}

// Whether the segment from `a` along unit `dir` for `len` passes within the placement's sphere.
bool segment_meets_sphere(glm::vec3 a, glm::vec3 dir, float len, glm::vec4 sphere) {
    const glm::vec3 c(sphere);
    const float t = std::clamp(dot3(c - a, dir), 0.0f, len);
    const glm::vec3 d = c - (a + dir * t);
    const float r = sphere.w * 1.001f + 1e-3f;
    return dot3(d, d) <= r * r;
}

// The texel lies on a placement that moves (its triangle's Placement::moves).
bool on_mover(const TexelScene& scene, const TexelSurface& s) {
    return scene.triangles[std::size_t(int(s.normal_triangle.w + 0.5f))].uv3.w > 0.5f;
}

} // namespace

std::vector<TexelSurface> uv_to_world_brute(const TexelScene& scene) {
    std::vector<TexelSurface> out(scene.texel_count);
    for (const GpuPlacement& p : scene.placements) {
        const int size = int(p.ranges.w);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const std::uint32_t texel = p.ranges.z + std::uint32_t(y * size + x);
                const glm::vec2 uv = texel_uv(x, y, size);
                for (std::uint32_t i = p.ranges.x; i < p.ranges.x + p.ranges.y; ++i) {
                    float v, w;
                    if (!uv_barycentric(scene.triangles[i], uv, v, w) || !inside(v, w)) continue;
                    out[texel] = surface_on(scene.triangles[i], i, v, w, scene.normal_maps[texel]);
                    break;
                }
            }
    }
    return out;
}

void uv_to_world_placement(const TexelScene& scene, std::uint32_t index, std::span<TexelSurface> surfaces) {
    const GpuPlacement& p = scene.placements.at(index);
    const int size = int(p.ranges.w);
    if (size <= 0) return;
    std::fill(surfaces.begin() + p.ranges.z, surfaces.begin() + p.ranges.z + std::size_t(size) * std::size_t(size),
              TexelSurface{});
    // The inside test accepts points up to inside_eps (barycentric) outside the triangle: at
    // most inside_eps x the longest UV edge, which the margin of two texels covers for any
    // texture up to 1000 texels (and a UV edge of at most sqrt(2)).
    const float margin = 2.0f + inside_eps * 1.5f * float(size);
    for (std::uint32_t i = p.ranges.x; i < p.ranges.x + p.ranges.y; ++i) {
        const GpuTriangle& t = scene.triangles[i];
        const float u_lo = std::min({t.uv12.x, t.uv12.z, t.uv3.x}), u_hi = std::max({t.uv12.x, t.uv12.z, t.uv3.x});
        const float v_lo = std::min({t.uv12.y, t.uv12.w, t.uv3.y}), v_hi = std::max({t.uv12.y, t.uv12.w, t.uv3.y});
        if (!(u_hi >= u_lo) || !(v_hi >= v_lo)) continue; // NaN corners: the test never passes
        const auto clamp_texel = [&](float f) { return int(std::clamp(f, 0.0f, float(size - 1))); };
        const int x0 = clamp_texel(std::floor(u_lo * float(size) - 0.5f - margin));
        const int x1 = clamp_texel(std::ceil(u_hi * float(size) - 0.5f + margin));
        const int y0 = clamp_texel(std::floor(v_lo * float(size) - 0.5f - margin));
        const int y1 = clamp_texel(std::ceil(v_hi * float(size) - 0.5f + margin));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const std::uint32_t texel = p.ranges.z + std::uint32_t(y * size + x);
                if (surfaces[texel].position_used.w != 0.0f) continue; // an earlier triangle has it
                float v, w;
                if (!uv_barycentric(t, texel_uv(x, y, size), v, w) || !inside(v, w)) continue;
                surfaces[texel] = surface_on(t, i, v, w, scene.normal_maps[texel]);
            }
    }
}

std::vector<TexelSurface> uv_to_world(const TexelScene& scene) {
    std::vector<TexelSurface> out(scene.texel_count);
    for (std::uint32_t k = 0; k < scene.placements.size(); ++k) uv_to_world_placement(scene, k, out);
    return out;
}

float wall_visibility(const WallPatch& walls, float wall_height, glm::vec3 light, glm::vec3 point) {
    const glm::vec2 ray(point.x - light.x, point.z - light.z);
    float ray_length = std::sqrt(ray.x * ray.x + ray.y * ray.y);
    if (ray_length < 1e-4f) return 1.0f;
    const float full_length = ray_length;
    const glm::vec2 dir = ray / ray_length;
    const glm::vec2 start = glm::vec2(light.x, light.z) + dir * ray_bias;
    const glm::vec2 end = glm::vec2(point.x, point.z) - dir * ray_bias;
    ray_length = std::max(ray_length - 2.0f * ray_bias, 0.0f);
    const float rise = point.y - light.y;
    // The segment's height at distance t along the traversal (from `start`).
    const auto height_at = [&](float t) { return light.y + rise * ((t + ray_bias) / full_length); };

    glm::ivec2 cell(int(std::floor(start.x)), int(std::floor(start.y)));
    const glm::ivec2 end_cell(int(std::floor(end.x)), int(std::floor(end.y)));
    const glm::ivec2 step(sign_of(dir.x), sign_of(dir.y));
    glm::vec2 t_max(first_boundary(start.x, dir.x, step.x), first_boundary(start.y, dir.y, step.y));
    const glm::vec2 t_delta(boundary_step(dir.x), boundary_step(dir.y));
    const int max_steps = std::max(1, int(std::ceil(std::min(full_length, 1e7f) * 2.0f)) + 2);
    float entered = 0.0f;
    for (int i = 0; i < max_steps; ++i) {
        if (walls.is_wall(cell.x, cell.y)) {
            const float left = std::min(std::min(t_max.x, t_max.y), ray_length);
            if (std::min(height_at(entered), height_at(left)) < wall_height) return 0.0f;
        }
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
            // Through a grid corner: blocked only between two wall cells, below their tops.
            traveled = t_max.x;
            if (walls.is_wall(cell.x + step.x, cell.y) && walls.is_wall(cell.x, cell.y + step.y) &&
                height_at(std::min(traveled, ray_length)) < wall_height)
                return 0.0f;
            t_max += t_delta;
            cell += step;
        }
        if (traveled > ray_length) return 1.0f;
        entered = traveled;
    }
    return 1.0f;
}

float occluder_visibility(const TexelScene& scene, const TexelLight& light, glm::vec3 origin, glm::vec3 point,
                          int own, bool still_only) {
    const glm::vec3 to_point = point - origin;
    const float lr = length3(to_point);
    if (!(lr > 0.0f)) return 1.0f;
    const glm::vec3 dir = to_point / lr;
    const bool hard = int(light.color_type.w + 0.5f) == int(ShadowType::hard);
    float nearest = -1.0f; // NLR: the nearest hit's distance to the texel
    for (const GpuPlacement& p : scene.placements) {
        if (!segment_meets_sphere(origin, dir, lr, p.bounds)) continue;
        if (still_only && placement_moves(scene, p)) continue;
        for (std::uint32_t i = p.ranges.x; i < p.ranges.x + p.ranges.y; ++i) {
            if (int(i) == own) continue;
            const GpuTriangle& t = scene.triangles[i];
            const glm::vec3 n(t.normal);
            const float facing = dot3(dir, n);
            if (!(facing < 0.0f)) continue; // faces away from the light, or edge-on
            const float along = dot3(glm::vec3(t.p3) - origin, n) / facing;
            if (!(along > 0.0f) || along >= lr - inside_eps) continue; // behind the light, or at/beyond the texel
            const glm::vec3 hit = origin + along * dir;
            if (!inside_triangle_3d(hit, t)) continue;
            if (hard) return 0.0f;
            const float nlr = length3(hit - point);
            nearest = nearest < 0.0f ? nlr : std::min(nearest, nlr);
        }
    }
    if (nearest < 0.0f) return 1.0f;
    const float ratio = nearest / lr;
    const float power = light.blur.y;
    const float blur = (power == 1.0f ? ratio : std::pow(ratio, power)) * light.blur.x;
    return std::clamp(blur, 0.0f, 1.0f);
}

float sun_visibility(const TexelScene& scene, const TexelLight& sun, glm::vec3 point, int own, bool still_only) {
    const glm::vec3 dir(sun.position_range);
    const float reach = sun.position_range.w;
    // Walls: towards the sun until the ray clears their tops (or the reach ends).
    float clear = reach;
    if (dir.y < 0.0f) clear = std::min(reach, std::max((scene.wall_height - point.y) / -dir.y, 0.0f));
    if (clear > 0.0f && wall_visibility(scene.walls, scene.wall_height, point - dir * clear, point) == 0.0f)
        return 0.0f;
    return occluder_visibility(scene, sun, point - dir * reach, point, own, still_only);
}

glm::vec3 texel_light(const TexelScene& scene, std::span<const TexelLight> lights, const TexelSurface& s,
                      LightPass pass) {
    glm::vec3 sum(0.0f);
    if (s.position_used.w == 0.0f) return sum;
    const glm::vec3 p(s.position_used), n(s.normal_triangle), g(s.geo_normal);
    const int own = int(s.normal_triangle.w + 0.5f);
    const bool bake = pass == LightPass::bake;
    const bool moves = on_mover(scene, s);
    if (bake && moves) return sum; // all of its light is realtime
    for (const TexelLight& light : lights) {
        if (!bake && !moves && is_baked(light)) continue; // in baked()
        const bool shadowed = int(light.color_type.w + 0.5f) != int(ShadowType::none);
        if (is_directional(light)) {
            const glm::vec3 dir(light.position_range);
            sum += glm::vec3(light.ambient);
            const float c = dot3(dir, n);
            if (!(c < 0.0f) || !(dot3(dir, g) < 0.0f)) continue;
            const float shade = shadowed ? sun_visibility(scene, light, p, own, bake) : 1.0f;
            const float value = std::abs(c);
            sum += glm::vec3(light.color_type) * (shade * value * value);
            continue;
        }
        const glm::vec3 from_light = p - glm::vec3(light.position_range);
        const float d = length3(from_light);
        const float range = light.position_range.w;
        if (!(d < range) || !(d > 0.0f)) continue;
        const float falloff = 1.0f - d / range;
        sum += glm::vec3(light.ambient) * falloff;
        const glm::vec3 dir = from_light / d;
        const float c = dot3(dir, n);
        // Lit when both the bent normal and the triangle itself face the light (a normal map
        // does not let light through the back of its own triangle).
        if (!(c < 0.0f) || !(dot3(dir, g) < 0.0f)) continue;
        float shade = 1.0f;
        if (shadowed) {
            shade = wall_visibility(scene.walls, scene.wall_height, glm::vec3(light.position_range), p);
            if (shade > 0.0f) shade = occluder_visibility(scene, light, glm::vec3(light.position_range), p, own, bake);
        }
        const float value = falloff * std::abs(c);
        sum += glm::vec3(light.color_type) * (shade * value * value);
    }
    return sum;
}

std::vector<glm::vec4> reference_light(const TexelScene& scene, std::span<const TexelSurface> surfaces,
                                       std::span<const TexelLight> lights, std::span<const glm::vec4> baked) {
    std::vector<glm::vec4> out(surfaces.size(), glm::vec4(0.0f));
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        if (surfaces[i].position_used.w == 0.0f) continue;
        if (baked.empty()) {                           // the bake
            if (on_mover(scene, surfaces[i])) continue; // a moving placement's: 0
            out[i] = glm::vec4(texel_light(scene, lights, surfaces[i], LightPass::bake), 1.0f);
            continue;
        }
        const glm::vec4 sum(texel_light(scene, lights, surfaces[i], LightPass::realtime), 1.0f);
        out[i] = glm::clamp(sum + baked[i], glm::vec4(0.0f), glm::vec4(1.0f));
    }
    return out;
}

} // namespace lantern::texel
