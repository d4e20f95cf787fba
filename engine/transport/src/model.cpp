// The physical model's source terms, built from Lantern's own shadow building blocks so
// that the direct terms match the GI passes exactly (gi/reference.hpp).
#include "lantern/transport/model.hpp"

#include "lantern/gi/reference.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::transport {
namespace {

constexpr float face_eps = 1e-3f; // Lantern's face rays end this far in front of the face

float max_channel(glm::vec3 c) {
    return std::max(c.r, std::max(c.g, c.b));
}

float sun_angle(const gi::FrameInputs& in, const gi::GpuDirectionalLight& sun) {
    return glm::mix(std::clamp(-sun.direction_base.y * 2.0f, 0.0f, 1.0f), 1.0f,
                    in.settings.directional_angle_scale);
}

// Lantern's directional visibility from a point: grid traversal with the wall-height test,
// then the directional proxies; 0 for a sun below the horizon.
float sun_visibility(const gi::FrameInputs& in, const gi::GpuDirectionalLight& sun,
                     glm::vec2 from) {
    const glm::vec3 dir(sun.direction_base);
    if (dir.y >= 0.0f) return 0.0f;
    const float max_distance = sun.direction_base.w * sun.color_multiplier.w;
    const float grid =
        gi::directional_shadow_dda(in.walls, from, dir, max_distance, in.wall_height);
    return std::min(grid, gi::directional_proxy_shadow(in.proxies, from, dir));
}

// Cosine between a face normal and the horizontal direction towards a sun; 0 when the sun
// is below the horizon, overhead, or behind the face.
float sun_face_cosine(const gi::GpuDirectionalLight& sun, glm::vec2 normal) {
    const glm::vec3 dir(sun.direction_base);
    if (dir.y >= 0.0f) return 0.0f;
    const glm::vec2 to_sun(-dir.x, -dir.z);
    const float len = std::sqrt(to_sun.x * to_sun.x + to_sun.y * to_sun.y);
    if (len < 1e-4f) return 0.0f;
    return std::max(0.0f, glm::dot(normal, to_sun / len));
}

const gi::GpuPointLight& local_light(const gi::FrameInputs& in, SourceRef s) {
    return s.kind == SourceKind::point ? in.point_lights[s.index] : in.emissive_lights[s.index];
}

} // namespace

glm::vec2 face_normal(int face) {
    switch (face) {
    case gi::face_pos_x:
        return {1.0f, 0.0f};
    case gi::face_neg_x:
        return {-1.0f, 0.0f};
    case gi::face_pos_z:
        return {0.0f, 1.0f};
    default:
        return {0.0f, -1.0f};
    }
}

glm::vec2 face_point(FaceRef f, float s) {
    const glm::vec2 t(f.tile);
    switch (f.face) {
    case gi::face_pos_x:
        return {t.x + 1.0f, t.y + s};
    case gi::face_neg_x:
        return {t.x, t.y + s};
    case gi::face_pos_z:
        return {t.x + s, t.y + 1.0f};
    default:
        return {t.x + s, t.y};
    }
}

bool face_exposed(const gi::WallView& walls, FaceRef f) {
    const glm::ivec2 n(face_normal(f.face));
    return walls.is_wall(f.tile.x, f.tile.y) && !walls.is_wall(f.tile.x + n.x, f.tile.y + n.y);
}

glm::vec3 direct_fluence(const gi::FrameInputs& in, glm::vec2 p) {
    const float softness = in.settings.light_softness;
    glm::vec3 out(0.0f);
    for (const gi::GpuPointLight& l : in.point_lights) {
        const glm::vec2 pos(l.position_radius.x, l.position_radius.y);
        const float radius = l.position_radius.z;
        const float dist = glm::distance(p, pos);
        if (dist > radius) continue;
        const float shadow = std::min(gi::shadow_dda(in.walls, pos, p, radius),
                                      gi::point_proxy_shadow(in.proxies, pos, p));
        out += glm::vec3(l.color) * gi::light_falloff(dist, radius, softness) * shadow;
    }
    for (const gi::GpuPointLight& l : in.emissive_lights) {
        const glm::vec2 pos(l.position_radius.x, l.position_radius.y);
        const float radius = l.position_radius.z;
        const float dist = glm::distance(p, pos);
        if (dist > radius) continue;
        out += glm::vec3(l.color) * gi::light_falloff(dist, radius, softness);
    }
    for (const gi::GpuDirectionalLight& sun : in.directional_lights)
        out += glm::vec3(sun.color_multiplier) * sun_angle(in, sun) * sun_visibility(in, sun, p);
    return out;
}

glm::vec3 source_face_irradiance(const gi::FrameInputs& in, SourceRef source, FaceRef face,
                                 glm::vec2 p) {
    const glm::vec2 n = face_normal(face.face);
    const glm::vec2 target = p + n * face_eps;
    if (source.kind == SourceKind::directional) {
        const gi::GpuDirectionalLight& sun = in.directional_lights[source.index];
        const float cosine = sun_face_cosine(sun, n);
        if (cosine <= 0.0f) return glm::vec3(0.0f);
        return glm::vec3(sun.color_multiplier) *
               (sun_angle(in, sun) * cosine * sun_visibility(in, sun, target));
    }
    const gi::GpuPointLight& l = local_light(in, source);
    const glm::vec2 pos(l.position_radius.x, l.position_radius.y);
    const float radius = l.position_radius.z;
    const float dist = glm::distance(p, pos);
    if (dist > radius || dist < 1e-6f) return glm::vec3(0.0f);
    const float cosine = glm::dot(n, (pos - p) / dist);
    if (cosine <= 0.0f) return glm::vec3(0.0f);
    float visibility = 1.0f;
    if (source.kind == SourceKind::point)
        visibility = std::min(gi::shadow_dda(in.walls, pos, target, radius),
                              gi::point_proxy_shadow(in.proxies, pos, target));
    return glm::vec3(l.color) *
           (gi::light_falloff(dist, radius, in.settings.light_softness) * cosine * visibility);
}

glm::vec3 direct_face_irradiance(const gi::FrameInputs& in, FaceRef face, glm::vec2 p) {
    glm::vec3 out(0.0f);
    for (std::uint32_t i = 0; i < in.point_lights.size(); ++i)
        out += source_face_irradiance(in, {SourceKind::point, i}, face, p);
    for (std::uint32_t i = 0; i < in.emissive_lights.size(); ++i)
        out += source_face_irradiance(in, {SourceKind::emissive, i}, face, p);
    for (std::uint32_t i = 0; i < in.directional_lights.size(); ++i)
        out += source_face_irradiance(in, {SourceKind::directional, i}, face, p);
    return out;
}

float source_face_bound(const gi::FrameInputs& in, SourceRef source, FaceRef face, float s0,
                        float s1) {
    const glm::vec2 n = face_normal(face.face);
    if (source.kind == SourceKind::directional) {
        const gi::GpuDirectionalLight& sun = in.directional_lights[source.index];
        return max_channel(glm::vec3(sun.color_multiplier)) * sun_angle(in, sun) *
               sun_face_cosine(sun, n);
    }
    const gi::GpuPointLight& l = local_light(in, source);
    const glm::vec2 pos(l.position_radius.x, l.position_radius.y);
    const float radius = l.position_radius.z;
    const glm::vec2 a = face_point(face, s0), b = face_point(face, s1);
    const float height = glm::dot(pos - a, n); // distance in front of the face's line
    if (height <= 0.0f) return 0.0f;
    const glm::vec2 along = b - a;
    const float t = std::clamp(glm::dot(pos - a, along) / glm::dot(along, along), 0.0f, 1.0f);
    const float dist = glm::distance(pos, a + along * t);
    if (dist >= radius) return 0.0f;
    return max_channel(glm::vec3(l.color)) *
           gi::light_falloff(dist, radius, in.settings.light_softness) * (height / dist);
}

} // namespace lantern::transport
