// Models, placements and the wall patch of the texel passes (texel.hpp).
#include "lantern/texel/texel.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace lantern::texel {
namespace {

struct Face {
    glm::vec3 normal, right, up; // outward; right and up as seen from outside (up: +v upwards)
    float width, height;         // world extents along right and up
};

glm::vec3 safe_normalize(glm::vec3 v, glm::vec3 fallback) {
    const float len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return len > 1e-20f ? v / len : fallback;
}

// Any unit vector perpendicular to n.
glm::vec3 perpendicular(glm::vec3 n) {
    const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return safe_normalize(glm::cross(n, axis), glm::vec3(0, 0, 1));
}

GpuTriangle world_triangle(const ModelTriangle& t, const glm::mat4& transform, std::uint32_t placement, bool moves) {
    glm::vec3 p[3];
    for (int i = 0; i < 3; ++i) p[i] = glm::vec3(transform * glm::vec4(t.p[i], 1.0f));
    GpuTriangle g;
    g.p1 = glm::vec4(p[0], 0.0f);
    g.p2 = glm::vec4(p[1], 0.0f);
    g.p3 = glm::vec4(p[2], 0.0f);
    g.uv12 = glm::vec4(t.uv[0], t.uv[1]);
    g.uv3 = glm::vec4(t.uv[2], float(placement), moves ? 1.0f : 0.0f);
    const glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const glm::vec3 n = safe_normalize(glm::cross(e1, e2), glm::vec3(0, 1, 0));
    const glm::vec2 d1 = t.uv[1] - t.uv[0], d2 = t.uv[2] - t.uv[0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    glm::vec3 tangent, binormal;
    if (std::abs(det) > 1e-20f) {
        tangent = safe_normalize((e1 * d2.y - e2 * d1.y) / det, perpendicular(n));
        binormal = safe_normalize((e2 * d1.x - e1 * d2.x) / det, glm::cross(n, tangent));
    } else { // no area in UV: no texel can land on it; any frame will do
        tangent = perpendicular(n);
        binormal = glm::cross(n, tangent);
    }
    g.normal = glm::vec4(n, 0.0f);
    g.tangent = glm::vec4(tangent, 0.0f);
    g.binormal = glm::vec4(binormal, 0.0f);
    return g;
}

glm::vec4 placement_bounds(std::span<const GpuTriangle> triangles) {
    if (triangles.empty()) return glm::vec4(0.0f);
    glm::vec3 lo(triangles[0].p1), hi(lo);
    for (const GpuTriangle& t : triangles)
        for (const glm::vec4& p : {t.p1, t.p2, t.p3}) {
            lo = glm::min(lo, glm::vec3(p));
            hi = glm::max(hi, glm::vec3(p));
        }
    const glm::vec3 c = (lo + hi) * 0.5f;
    float r2 = 0.0f;
    for (const GpuTriangle& t : triangles)
        for (const glm::vec4& p : {t.p1, t.p2, t.p3}) {
            const glm::vec3 d = glm::vec3(p) - c;
            r2 = std::max(r2, glm::dot(d, d));
        }
    return glm::vec4(c, std::sqrt(r2) * (1.0f + 1e-5f) + 1e-5f);
}

} // namespace

Model box_model(glm::vec3 min, glm::vec3 max, int texels_per_unit) {
    const glm::vec3 lo = glm::min(min, max), hi = glm::max(min, max);
    const glm::vec3 size = hi - lo;
    const std::array<Face, 5> faces = {{
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}, size.z, size.y},
        {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}, size.z, size.y},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, size.x, size.y},
        {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}, size.x, size.y},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}, size.x, size.z},
    }};
    const int density = std::max(texels_per_unit, 1);
    std::array<glm::ivec2, 5> texels{};
    for (std::size_t f = 0; f < faces.size(); ++f)
        texels[f] = glm::ivec2(std::max(1, int(std::lround(faces[f].width * float(density)))),
                               std::max(1, int(std::lround(faces[f].height * float(density)))));
    // Shelf packing with a one-texel gutter, into the smallest square texture that holds it
    // (any size: nothing here needs powers of two, and they left half the atlas empty).
    std::array<glm::ivec2, 5> origin{};
    int tex = 1;
    for (;; ++tex) {
        int x = 1, y = 1, row = 0;
        bool fits = true;
        for (std::size_t f = 0; f < faces.size() && fits; ++f) {
            if (x + texels[f].x + 1 > tex) {
                x = 1;
                y += row + 1;
                row = 0;
            }
            origin[f] = glm::ivec2(x, y);
            x += texels[f].x + 1;
            row = std::max(row, texels[f].y);
            fits = x <= tex && y + texels[f].y + 1 <= tex;
        }
        if (fits || tex >= 4096) break;
    }
    Model m;
    m.size = tex;
    const glm::vec3 centre = (lo + hi) * 0.5f, half = size * 0.5f;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const Face& face = faces[f];
        const glm::vec3 fc = centre + face.normal * glm::dot(glm::abs(face.normal), half);
        const glm::vec3 r = face.right * (face.width * 0.5f), u = face.up * (face.height * 0.5f);
        const glm::vec3 a = fc - r - u, b = fc + r - u, c = fc + r + u, d = fc - r + u;
        const float s = float(tex);
        const glm::vec2 o(origin[f]), e(texels[f]);
        const glm::vec2 ua = glm::vec2(o.x, o.y + e.y) / s, ub = glm::vec2(o.x + e.x, o.y + e.y) / s,
                        uc = glm::vec2(o.x + e.x, o.y) / s, ud = o / s;
        m.triangles.push_back({{a, b, c}, {ua, ub, uc}});
        m.triangles.push_back({{a, c, d}, {ua, uc, ud}});
        m.faces.emplace_back(origin[f], texels[f]);
    }
    return m;
}

void append_triangles(Model& a, const Model& b, const glm::mat4& transform, glm::vec2 origin, glm::vec2 extent) {
    for (const ModelTriangle& t : b.triangles) {
        ModelTriangle out;
        for (int i = 0; i < 3; ++i) {
            out.p[i] = glm::vec3(transform * glm::vec4(t.p[i], 1.0f));
            out.uv[i] = origin + t.uv[i] * extent;
        }
        a.triangles.push_back(out);
    }
}

TexelLight make_light(glm::vec3 position, glm::vec3 color, float intensity, float range, ShadowType shadow,
                      float blur_multiplier, float blur_power, glm::vec3 ambient) {
    TexelLight l;
    l.position_range = glm::vec4(position, std::max(range, 1e-3f));
    l.color_type = glm::vec4(color * intensity, float(int(shadow)));
    l.blur = glm::vec4(blur_multiplier, blur_power, 0.0f, 0.0f);
    l.ambient = glm::vec4(ambient, 0.0f);
    return l;
}

TexelLight make_sun(glm::vec3 direction, glm::vec3 color, float intensity, ShadowType shadow, float reach,
                    glm::vec3 ambient) {
    const float len = std::sqrt(direction.x * direction.x + direction.y * direction.y + direction.z * direction.z);
    TexelLight l;
    l.position_range = glm::vec4(len > 0.0f ? direction / len : glm::vec3(0, -1, 0), std::max(reach, 1e-3f));
    l.color_type = glm::vec4(color * intensity, float(int(shadow)));
    l.blur = glm::vec4(1.0f, 1.0f, 1.0f, 0.0f);
    l.ambient = glm::vec4(ambient, 0.0f);
    return l;
}

bool is_directional(const TexelLight& light) { return light.blur.z > 0.5f; }

bool WallPatch::is_wall(int x, int z) const {
    const int c = x - origin.x, r = z - origin.y;
    if (c < 0 || r < 0 || c >= width || r >= height) return false;
    const std::size_t i = std::size_t(c) + std::size_t(r) * std::size_t(width);
    return ((words[i >> 2] >> ((i & 3u) * 8u)) & 0xffu) != 0;
}

TexelScene build_scene(std::span<const Placement> placements, const gi::WallView& walls, float wall_height,
                       float reach) {
    TexelScene scene;
    scene.wall_height = wall_height;
    glm::vec3 lo(0.0f), hi(0.0f);
    for (std::uint32_t k = 0; k < placements.size(); ++k) {
        const Model& m = *placements[k].model;
        GpuPlacement p;
        p.ranges = glm::uvec4(std::uint32_t(scene.triangles.size()), std::uint32_t(m.triangles.size()),
                              scene.texel_count, std::uint32_t(std::max(m.size, 0)));
        for (const ModelTriangle& t : m.triangles)
            scene.triangles.push_back(world_triangle(t, placements[k].transform, k, placements[k].moves));
        p.bounds = placement_bounds(std::span(scene.triangles).subspan(p.ranges.x, p.ranges.y));
        const std::size_t texels = std::size_t(p.ranges.w) * p.ranges.w;
        for (std::size_t i = 0; i < texels; ++i)
            scene.normal_maps.push_back(m.normal_map.size() == texels ? m.normal_map[i] : glm::vec4(0.5f, 0.5f, 1.0f, 0.0f));
        scene.texel_count += std::uint32_t(texels);
        const glm::vec3 c(p.bounds), r(p.bounds.w);
        lo = k == 0 ? c - r : glm::min(lo, c - r);
        hi = k == 0 ? c + r : glm::max(hi, c + r);
        scene.placements.push_back(p);
    }
    if (placements.empty() || walls.width <= 0 || walls.height <= 0) return scene;
    const float grow = std::max(reach, 0.0f) + 1.0f;
    glm::ivec2 a(int(std::floor(lo.x - grow)), int(std::floor(lo.z - grow)));
    glm::ivec2 b(int(std::ceil(hi.x + grow)) + 1, int(std::ceil(hi.z + grow)) + 1);
    a = glm::max(a, walls.origin);
    b = glm::min(b, walls.origin + glm::ivec2(walls.width, walls.height));
    if (b.x <= a.x || b.y <= a.y) return scene;
    WallPatch& patch = scene.walls;
    patch.origin = a;
    patch.width = b.x - a.x;
    patch.height = b.y - a.y;
    const std::size_t cells = std::size_t(patch.width) * std::size_t(patch.height);
    patch.words.assign((cells + 3) / 4, 0u);
    for (int z = a.y; z < b.y; ++z)
        for (int x = a.x; x < b.x; ++x)
            if (walls.is_wall(x, z)) {
                const std::size_t i = std::size_t(x - a.x) + std::size_t(z - a.y) * std::size_t(patch.width);
                patch.words[i >> 2] |= 1u << ((i & 3u) * 8u);
            }
    return scene;
}

void move_placement(TexelScene& scene, std::uint32_t index, const Model& model, const glm::mat4& transform) {
    GpuPlacement& p = scene.placements.at(index);
    const bool moves = placement_moves(scene, p);
    for (std::uint32_t i = 0; i < p.ranges.y && i < model.triangles.size(); ++i)
        scene.triangles[p.ranges.x + i] = world_triangle(model.triangles[i], transform, index, moves);
    p.bounds = placement_bounds(std::span(scene.triangles).subspan(p.ranges.x, p.ranges.y));
}

bool placement_moves(const TexelScene& scene, const GpuPlacement& p) {
    return p.ranges.y > 0 && scene.triangles[p.ranges.x].uv3.w > 0.5f;
}

} // namespace lantern::texel
