// The reference passes: one function per texel, run over every texel of the window.
#include "lantern/gi/reference.hpp"
#include "lantern/gi/point_map.hpp"
#include "lantern/gi/sun_map.hpp"

#include "lantern/jobs/job_system.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace lantern::gi {
namespace {

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }

template <typename F>
void for_each_row(const GiWindow& w, const RefOptions& options, F&& row) {
    if (options.jobs) {
        options.jobs->parallel_for("gi.reference", 0, std::uint32_t(w.height), 8,
                                   [&](std::uint32_t b, std::uint32_t e, std::uint32_t) {
                                       for (std::uint32_t y = b; y < e; ++y) row(int(y));
                                   });
    } else {
        for (int y = 0; y < w.height; ++y) row(y);
    }
}

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

glm::ivec2 tile_of(glm::vec2 p) { return {int(std::floor(p.x)), int(std::floor(p.y))}; }

// Where a wall face's shadow ray ends (or starts, for the sun): just outside the face, at
// the texel's position along it.
glm::vec2 face_position(int face, glm::ivec2 cell, glm::vec2 p) {
    constexpr float face_eps = 1e-3f;
    switch (face) {
    case face_pos_x: return {float(cell.x) + 1.0f + face_eps, p.y};
    case face_neg_x: return {float(cell.x) - face_eps, p.y};
    case face_pos_z: return {p.x, float(cell.y) + 1.0f + face_eps};
    default: return {p.x, float(cell.y) - face_eps};
    }
}

std::span<const GpuShadowProxy> proxies_of(const FrameInputs& in) { return in.proxies; }

struct TexelLight {
    glm::vec3 color{0.0f};
    float shadow = 0.0f;
    glm::vec3 face[4] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    // Unfolded proxy shadows (unfolds_proxy_shadows): the light at each face's top, and the
    // shadow edge's height summed weighted by the light the shadow takes (edge_weight).
    glm::vec3 upper[4] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    float edge_sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float edge_weight[4] = {0.0f, 0.0f, 0.0f, 0.0f};

    // Light `light` reaching face f, with grid visibility `grid` and the proxies' `s`.
    void add_face(int f, glm::vec3 light, float grid, const FaceProxyShadow& s) {
        face[f] += light * std::min(grid, s.low);
        upper[f] += light * std::min(grid, s.high);
        const float taken = (light.r + light.g + light.b) * (std::min(grid, s.high) - std::min(grid, s.low));
        edge_sum[f] += taken * s.edge;
        edge_weight[f] += taken;
    }
    float edge(int f) const { return edge_weight[f] > 0.0f ? edge_sum[f] / edge_weight[f] : 0.0f; }
};

// Point light i's grid visibility of `target`: by the seed's DDA, or (gi.shadow_method =
// shadow_map, `maps` set) by its map, which returns -1 for a close call unless `deferred`:
// then the DDA decides it later (see for_each_point_light).
float point_visibility(const FrameInputs& in, const PointMaps* maps, std::size_t i, glm::vec2 pos, glm::vec2 target,
                       float radius, bool deferred) {
    return maps && !deferred ? point_map_lookup(*maps, i, pos, target, radius) : shadow_dda(in.walls, pos, target, radius);
}

// Calls visit(i, deferred) for every point light in the direct pass's order of addition:
// 32 lights at a time (a word of the GPU's bin masks); visit returns the bits of the
// targets its map could not decide (added nothing), which are visited again, with
// `deferred` and those bits, after the 32. Without maps every call returns 0: light order.
template <typename Visit>
void for_each_point_light(const FrameInputs& in, Visit&& visit) {
    std::uint32_t later[32];
    for (std::size_t group = 0; group < in.point_lights.size(); group += 32) {
        const std::size_t end = std::min(in.point_lights.size(), group + 32);
        std::uint32_t any = 0u;
        for (std::size_t i = group; i < end; ++i) any |= later[i - group] = visit(i, 0u);
        if (any != 0u)
            for (std::size_t i = group; i < end; ++i)
                if (later[i - group] != 0u) visit(i, later[i - group]);
    }
}

void wall_texel(const FrameInputs& in, const PointMaps* maps, glm::ivec2 cell, glm::vec2 p, TexelLight& out) {
    const glm::vec4 mask = wall_face_mask(in.walls, cell) * face_bits_mask(computed_faces(in.settings));
    const bool unfold = unfolds_proxy_shadows(in);
    const float softness = in.settings.light_softness;
    auto face_weights = [&](glm::vec2 light_pos) {
        glm::vec2 to_light = light_pos - p;
        const float inv_len = 1.0f / std::sqrt(std::max(glm::dot(to_light, to_light), 1e-6f));
        return mask * wall_facing(to_light * inv_len, in.settings.wall_face_exponent);
    };
    // Point light i at this texel; `only`: bit f set for the faces deferred to the DDA (0: all).
    for_each_point_light(in, [&](std::size_t i, std::uint32_t only) -> std::uint32_t {
        const GpuPointLight& l = in.point_lights[i];
        const glm::vec2 pos(l.position_radius.x, l.position_radius.y);
        const float radius = l.position_radius.z;
        const float dist = glm::distance(p, pos);
        if (dist > radius) return 0u;
        const glm::vec4 weight = face_weights(pos);
        if (weight == glm::vec4(0.0f)) return 0u;
        const glm::vec3 contribution = glm::vec3(l.color) * light_falloff(dist, radius, softness);
        std::uint32_t later = 0u;
        for (int f = 0; f < 4; ++f) {
            if (!(weight[f] > 0.0f) || (only != 0u && !((only >> f) & 1u))) continue;
            const glm::vec2 target = face_position(f, cell, p);
            const float grid = point_visibility(in, maps, i, pos, target, radius, only != 0u);
            if (grid < 0.0f) {
                later |= 1u << f;
                continue;
            }
            if (unfold) {
                out.add_face(f, contribution * weight[f], grid, point_proxy_face_shadow(proxies_of(in), pos, target, in.wall_height));
                continue;
            }
            const float shadow = std::min(grid, point_proxy_shadow(proxies_of(in), pos, target));
            out.face[f] += contribution * (weight[f] * shadow);
        }
        return later;
    });
    for (const GpuPointLight& l : in.emissive_lights) {
        const glm::vec2 pos(l.position_radius.x, l.position_radius.y);
        const float radius = l.position_radius.z;
        const float dist = glm::distance(p, pos);
        if (dist > radius) continue;
        const glm::vec3 contribution = glm::vec3(l.color) * light_falloff(dist, radius, softness);
        const glm::vec4 weight = face_weights(pos);
        for (int f = 0; f < 4; ++f) {
            out.face[f] += contribution * weight[f];
            if (unfold) out.upper[f] += contribution * weight[f];
        }
    }
}

void ground_texel(const FrameInputs& in, const PointMaps* maps, glm::vec2 p, TexelLight& out) {
    const float softness = in.settings.light_softness;
    for_each_point_light(in, [&](std::size_t i, std::uint32_t only) -> std::uint32_t {
        const GpuPointLight& l = in.point_lights[i];
        const glm::vec2 pos(l.position_radius.x, l.position_radius.y);
        const float radius = l.position_radius.z;
        const float dist = glm::distance(p, pos);
        if (dist > radius) return 0u;
        const float grid = point_visibility(in, maps, i, pos, p, radius, only != 0u);
        if (grid < 0.0f) return 1u;
        const float shadow = std::min(grid, point_proxy_shadow(proxies_of(in), pos, p));
        out.shadow = std::max(out.shadow, shadow);
        out.color += glm::vec3(l.color) * light_falloff(dist, radius, softness) * shadow;
        return 0u;
    });
    for (const GpuPointLight& l : in.emissive_lights) {
        const glm::vec2 pos(l.position_radius.x, l.position_radius.y);
        const float radius = l.position_radius.z;
        const float dist = glm::distance(p, pos);
        if (dist > radius) continue;
        out.color += glm::vec3(l.color) * light_falloff(dist, radius, softness);
    }
}

float sun_angle(const GpuDirectionalLight& sun, float angle_scale) {
    return glm::mix(saturate(-sun.direction_base.y * 2.0f), 1.0f, angle_scale);
}

// The walls' part of the sun's visibility. `map`: the sun's shadow map when
// gi.sun_shadow_method is shadow_map, else null (the DDA).
float sun_grid_visibility(const FrameInputs& in, const GpuDirectionalLight& sun, const SunMap* map, glm::vec2 from) {
    const glm::vec3 dir(sun.direction_base);
    if (dir.y >= 0.0f) return 0.0f; // below the horizon
    const float max_distance = sun.direction_base.w * sun.color_multiplier.w;
    return map ? sun_map_visibility(*map, in.walls, sun, from, in.wall_height)
               : directional_shadow_dda(in.walls, from, dir, max_distance, in.wall_height);
}

float sun_visibility(const FrameInputs& in, const GpuDirectionalLight& sun, const SunMap* map, glm::vec2 from) {
    const float grid = sun_grid_visibility(in, sun, map, from); // 0 below the horizon
    return std::min(grid, directional_proxy_shadow(proxies_of(in), from, glm::vec3(sun.direction_base)));
}

void directional_texel(const FrameInputs& in, const std::vector<SunMap>& maps, bool wall, glm::ivec2 cell,
                       glm::vec2 p, TexelLight& out) {
    const glm::vec4 mask =
        wall ? wall_face_mask(in.walls, cell) * face_bits_mask(computed_faces(in.settings)) : glm::vec4(0.0f);
    for (std::size_t i = 0; i < in.directional_lights.size(); ++i) {
        const GpuDirectionalLight& sun = in.directional_lights[i];
        const SunMap* map = maps.empty() ? nullptr : &maps[i];
        const glm::vec3 color = glm::vec3(sun.color_multiplier) * sun_angle(sun, in.settings.directional_angle_scale);
        if (!wall) {
            const float visibility = sun_visibility(in, sun, map, p);
            out.shadow = std::max(out.shadow, visibility);
            out.color += color * visibility;
            continue;
        }
        const glm::vec2 to_sun(-sun.direction_base.x, -sun.direction_base.z);
        const float len = std::sqrt(to_sun.x * to_sun.x + to_sun.y * to_sun.y);
        if (len < 1e-4f) continue; // overhead sun: no face faces it
        const glm::vec4 weight = mask * wall_facing(to_sun / len, in.settings.wall_face_exponent);
        for (int f = 0; f < 4; ++f) {
            if (!(weight[f] > 0.0f)) continue;
            const glm::vec2 target = face_position(f, cell, p);
            if (unfolds_proxy_shadows(in)) {
                out.add_face(f, color * weight[f], sun_grid_visibility(in, sun, map, target),
                             directional_proxy_face_shadow(proxies_of(in), target, glm::vec3(sun.direction_base), in.wall_height));
                continue;
            }
            out.face[f] += color * (weight[f] * sun_visibility(in, sun, map, target));
        }
    }
}

void store_rgb(Texture& t, int x, int y, glm::vec3 rgb, float a) {
    const float v[4] = {rgb.r, rgb.g, rgb.b, a};
    t.store(x, y, v);
}

} // namespace

Texture reference_conduction(const FrameInputs& in, const RefOptions& options) {
    const GiWindow& w = in.window;
    Texture t("conduction", TexFormat::r8, w.width, w.height);
    for_each_row(w, options, [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            const glm::ivec2 tile = tile_of(w.texel_center(x, y));
            const float v = in.walls.is_wall(tile.x, tile.y) ? 0.0f : 1.0f;
            t.store(x, y, &v);
        }
    });
    return t;
}

AoKernel ao_kernel(int resolution, const scene::AoSettings& ao) {
    AoKernel k;
    k.resolution = resolution;
    const float radius = std::max(ao.radius, 0.01f);
    const float power = std::max(ao.power, 0.01f);
    k.range = int(std::ceil(radius));
    const int n = k.taps();
    k.weights.assign(std::size_t(resolution) * std::size_t(resolution) * std::size_t(n), 0.0f);
    k.totals.assign(std::size_t(resolution) * std::size_t(resolution), 0.0f);
    for (int sy = 0; sy < resolution; ++sy)
        for (int sx = 0; sx < resolution; ++sx) {
            const glm::vec2 p((float(sx) + 0.5f) / float(resolution), (float(sy) + 0.5f) / float(resolution));
            float total = 0.0f;
            for (int dy = -k.range; dy <= k.range; ++dy)
                for (int dx = -k.range; dx <= k.range; ++dx) {
                    const glm::vec2 center(float(dx) + 0.5f, float(dy) + 0.5f);
                    const float dist = glm::distance(p, center);
                    if (dist > radius) continue;
                    const float weight = std::pow(1.0f - saturate(dist / radius), power);
                    k.weights[std::size_t((sy * resolution + sx) * n + (dy + k.range) * (2 * k.range + 1) + dx + k.range)] =
                        weight;
                    total += weight;
                }
            k.totals[std::size_t(sy * resolution + sx)] = total;
        }
    return k;
}

Texture reference_ao(const FrameInputs& in, const RefOptions& options) {
    const GiWindow& w = in.window;
    const scene::AoSettings& ao = in.settings.ao;
    Texture t("ao", TexFormat::r8, w.width, w.height);
    const AoKernel k = ao_kernel(w.resolution, ao);
    const int res = w.resolution, span = 2 * k.range + 1;
    const glm::ivec2 origin = window_texel_origin(w);
    for_each_row(w, options, [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            // The tile and the position in it from the global texel index (exact integers).
            const glm::ivec2 g = origin + glm::ivec2(x, y);
            const glm::ivec2 base(floor_div(g.x, res), floor_div(g.y, res));
            const int sub = (g.y - base.y * res) * res + (g.x - base.x * res);
            float occluded = 0.0f;
            for (int dy = -k.range; dy <= k.range; ++dy)
                for (int dx = -k.range; dx <= k.range; ++dx)
                    if (in.walls.is_wall(base.x + dx, base.y + dy))
                        occluded += k.weights[std::size_t(sub * k.taps() + (dy + k.range) * span + dx + k.range)];
            const float total = k.totals[std::size_t(sub)];
            const float occlusion = total > 0.0f ? occluded / total : 0.0f;
            float value = 1.0f - saturate(ao.strength) * occlusion;
            if (ao.dither) value += (bayer4(x, y) - 0.5f) / 255.0f;
            t.store(x, y, &value);
        }
    });
    return t;
}

DirectTextures reference_direct(const FrameInputs& in, const RefOptions& options, const DirectTextures* suns) {
    const GiWindow& w = in.window;
    DirectTextures out{Texture("direct", TexFormat::rgba16f, w.width, w.height),
                       Texture("shadow", TexFormat::rg8, w.width, w.height),
                       {},
                       {}};
    const std::uint32_t faces = computed_faces(in.settings);
    const bool unfold = unfolds_proxy_shadows(in);
    for (int f = 0; f < 4; ++f)
        if (computes_face(faces, f)) {
            out.wall_direct[f] = Texture(std::string("wall_direct_") + face_suffix[f], TexFormat::rgba16f, w.width, w.height);
            if (unfold) out.wall_upper[f] = Texture(std::string("wall_upper_") + face_suffix[f], TexFormat::rgba16f, w.width, w.height);
        }
    // No point or emissive lights and no suns: every output is zero (as the GPU clears them,
    // face flags too).
    if (in.point_lights.empty() && in.emissive_lights.empty() && !suns) return out;
    std::optional<PointMaps> maps;
    if (in.settings.shadow_method == scene::ShadowMethod::shadow_map && !in.point_lights.empty()) maps = build_point_maps(in);
    const PointMaps* map = maps ? &*maps : nullptr;
    for_each_row(w, options, [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            const glm::ivec2 cell = tile_of(p);
            const bool wall = in.walls.is_wall(cell.x, cell.y);
            TexelLight light;
            if (!wall)
                ground_texel(in, map, p, light);
            else if (faces != 0) // a wall texel's ground light is zero; its faces hold its light
                wall_texel(in, map, cell, p, light);
            const auto sun = [&](const Texture& t) {
                const float* v = t.at(x, y);
                return glm::vec4(v[0], v[1], v[2], v[3]);
            };
            float sun_shadow = 0.0f;
            if (suns) {
                light.color += glm::vec3(sun(suns->direct));
                sun_shadow = suns->shadow.at(x, y)[1];
            }
            store_rgb(out.direct, x, y, light.color, 0.0f);
            const float shadow[2] = {wall ? 0.0f : light.shadow, sun_shadow};
            out.shadow.store(x, y, shadow);
            // Face alpha flags texels that hold face light (wall texels).
            for (int f = 0; f < 4; ++f) {
                if (!computes_face(faces, f)) continue;
                if (suns && unfold) { // the suns' edge, weighted by the light their shadows take
                    const glm::vec4 low = sun(suns->wall_direct[f]), up = sun(suns->wall_upper[f]);
                    const float taken = (up.r - low.r) + (up.g - low.g) + (up.b - low.b);
                    if (taken > 0.0f) {
                        light.edge_sum[f] += taken * up.a;
                        light.edge_weight[f] += taken;
                    }
                    light.upper[f] += glm::vec3(up);
                }
                if (suns) light.face[f] += glm::vec3(sun(suns->wall_direct[f]));
                store_rgb(out.wall_direct[f], x, y, light.face[f], wall ? 1.0f : 0.0f);
                if (unfold) store_rgb(out.wall_upper[f], x, y, light.upper[f], light.edge(f));
            }
        }
    });
    return out;
}

void reference_directional(const FrameInputs& in, DirectTextures& t, const RefOptions& options) {
    const GiWindow& w = in.window;
    const std::uint32_t faces = computed_faces(in.settings);
    const bool unfold = unfolds_proxy_shadows(in);
    const std::vector<SunMap> maps =
        in.settings.sun_shadow_method == scene::SunShadowMethod::shadow_map ? build_sun_maps(in) : std::vector<SunMap>{};
    for_each_row(w, options, [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            const glm::ivec2 cell = tile_of(p);
            const bool wall = in.walls.is_wall(cell.x, cell.y);
            TexelLight sun;
            directional_texel(in, maps, wall, cell, p, sun);
            const float* d = t.direct.at(x, y);
            store_rgb(t.direct, x, y, glm::vec3(d[0], d[1], d[2]) + sun.color, d[3]);
            const float shadow[2] = {t.shadow.at(x, y)[0], wall ? 0.0f : sun.shadow};
            t.shadow.store(x, y, shadow);
            for (int f = 0; f < 4; ++f) {
                if (!computes_face(faces, f)) continue;
                if (unfold) {
                    // Merge the edges, each weighted by the light its shadows take.
                    const float* low = t.wall_direct[f].at(x, y);
                    const float* up = t.wall_upper[f].at(x, y);
                    const float taken = (up[0] - low[0]) + (up[1] - low[1]) + (up[2] - low[2]);
                    if (taken > 0.0f) {
                        sun.edge_sum[f] += taken * up[3];
                        sun.edge_weight[f] += taken;
                    }
                    store_rgb(t.wall_upper[f], x, y, glm::vec3(up[0], up[1], up[2]) + sun.upper[f], sun.edge(f));
                }
                const float* face = t.wall_direct[f].at(x, y);
                store_rgb(t.wall_direct[f], x, y, glm::vec3(face[0], face[1], face[2]) + sun.face[f], wall ? 1.0f : 0.0f);
            }
        }
    });
}

} // namespace lantern::gi
