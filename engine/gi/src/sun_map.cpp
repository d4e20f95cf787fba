// The sun's shadow map (sun_map.hpp). The arithmetic mirrors directional_shadow_dda
// (reference_shadow.cpp) and shaders/include/lantern/gi_sun_map.glsl operation for
// operation: keep the three in step.
#include "lantern/gi/sun_map.hpp"

#include "lantern/gi/reference.hpp"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lantern::gi {
namespace {

constexpr float ray_bias = 1e-4f; // as the DDA's
constexpr float dir_eps = 1e-6f;
constexpr float big = 1e30f;
// A tile is listed in every bin its footprint across the sun overlaps, widened by this much
// so that a start point's bin, however it rounds, lists every tile its ray can meet.
constexpr float bin_margin = 0.01f;

struct SunRay {
    glm::vec3 to_sun{0.0f};
    float xz_length = 0.0f;
    glm::vec2 dir{0.0f};
};

SunRay sun_ray(const GpuDirectionalLight& sun) {
    SunRay r;
    r.to_sun = -glm::vec3(sun.direction_base);
    r.xz_length = std::sqrt(r.to_sun.x * r.to_sun.x + r.to_sun.z * r.to_sun.z);
    if (r.xz_length >= 1e-4f) r.dir = glm::vec2(r.to_sun.x / r.xz_length, r.to_sun.z / r.xz_length);
    return r;
}

// The seed's wall-height test against the tile centre (blocks_directional_cell).
bool blocks(glm::ivec2 cell, glm::vec2 start, const SunRay& r, float wall_height) {
    const glm::vec2 d = glm::vec2(cell) + 0.5f - start;
    const float distance_to_wall = std::sqrt(d.x * d.x + d.y * d.y);
    if (std::abs(r.to_sun.y) > 0.001f && r.xz_length > 1e-4f) {
        const float vertical_rate = r.to_sun.y / r.xz_length;
        return distance_to_wall * vertical_rate < wall_height;
    }
    return true;
}

// The part [t_in, t_out] of the ray start + dir * t inside the tile, for a tile the line
// meets: an axis the ray is parallel to (as the DDA: |dir| < dir_eps, never stepped along)
// bounds nothing.
void span_in_tile(glm::vec2 start, glm::vec2 dir, glm::ivec2 cell, float& t_in, float& t_out) {
    t_in = -big;
    t_out = big;
    for (int a = 0; a < 2; ++a) {
        const float lo = float(cell[a]), hi = lo + 1.0f;
        if (std::abs(dir[a]) < dir_eps) continue;
        const float t1 = (lo - start[a]) / dir[a], t2 = (hi - start[a]) / dir[a];
        t_in = std::max(t_in, std::min(t1, t2));
        t_out = std::min(t_out, std::max(t1, t2));
    }
}

float sun_max_distance(const GpuDirectionalLight& sun) { return sun.direction_base.w * sun.color_multiplier.w; }

float hand_to_dda(const WallView& walls, const GpuDirectionalLight& sun, glm::vec2 pixel, float wall_height, int* count) {
    if (count) ++*count;
    return directional_shadow_dda(walls, pixel, glm::vec3(sun.direction_base), sun_max_distance(sun), wall_height);
}

} // namespace

SunMap build_sun_map(const WallView& walls, glm::vec2 lo, glm::vec2 hi, const GpuDirectionalLight& sun,
                     float wall_height) {
    SunMap m;
    const SunRay r = sun_ray(sun);
    // Overhead (no grid shadow in the DDA) and below the horizon (no light at all: the pass
    // never asks) need no map.
    if (r.xz_length < 1e-4f || sun.direction_base.y >= 0.0f) {
        m.lit_everywhere = true;
        return m;
    }
    m.dir = r.dir;
    m.perp = glm::vec2(-r.dir.y, r.dir.x);
    const float max_distance = sun_max_distance(sun);
    // How far along the sun a tile can still shade: it must be left by max_distance and, when
    // the sun has a slope, its centre nearer than wall_height / slope (plus the tile's reach).
    float reach = std::min(max_distance, 1e6f);
    if (std::abs(r.to_sun.y) > 0.001f) reach = std::min(reach, wall_height / (r.to_sun.y / r.xz_length) + 1.0f);
    m.reach = std::max(reach, 0.0f);

    // The start points' extent along (u) and across (v) the sun.
    float u_lo = big, u_hi = -big, v_lo = big, v_hi = -big;
    for (glm::vec2 corner : {lo, hi, glm::vec2(lo.x, hi.y), glm::vec2(hi.x, lo.y)}) {
        const float u = corner.x * m.dir.x + corner.y * m.dir.y, v = corner.x * m.perp.x + corner.y * m.perp.y;
        u_lo = std::min(u_lo, u);
        u_hi = std::max(u_hi, u);
        v_lo = std::min(v_lo, v);
        v_hi = std::max(v_hi, v);
    }
    m.v0 = v_lo - 1.0f;
    m.bins = int(std::ceil((v_hi + 1.0f - m.v0) / sun_map_bin_width)) + 1;
    m.first.assign(std::size_t(m.bins) + 1, 0);

    // Tiles that can shade a start point: within the window swept towards the sun by the
    // reach, inside the grid (outside it is air).
    const glm::vec2 far = m.dir * (m.reach + 2.0f);
    glm::vec2 box_lo = glm::min(lo, lo + far) - 2.0f, box_hi = glm::max(hi, hi + far) + 2.0f;
    const glm::ivec2 grid_lo = walls.origin, grid_hi = walls.origin + glm::ivec2(walls.width, walls.height);
    const glm::ivec2 t_lo = glm::max(glm::ivec2(glm::floor(box_lo)), grid_lo);
    const glm::ivec2 t_hi = glm::min(glm::ivec2(glm::floor(box_hi)) + 1, grid_hi);
    const float half_width = 0.5f * (std::abs(m.dir.x) + std::abs(m.dir.y)) + bin_margin;
    const float u_min = u_lo - 1.0f, u_max = u_hi + m.reach + 2.0f;

    struct Tile {
        float u;
        int first_bin, last_bin;
        glm::ivec2 cell;
    };
    std::vector<Tile> tiles;
    for (int z = t_lo.y; z < t_hi.y; ++z)
        for (int x = t_lo.x; x < t_hi.x; ++x) {
            if (!walls.is_wall(x, z)) continue;
            const glm::vec2 c(float(x) + 0.5f, float(z) + 0.5f);
            const float u = c.x * m.dir.x + c.y * m.dir.y;
            if (u < u_min || u > u_max) continue;
            const float v = c.x * m.perp.x + c.y * m.perp.y;
            const int b0 = std::max(int(std::floor((v - half_width - m.v0) / sun_map_bin_width)), 0);
            const int b1 = std::min(int(std::floor((v + half_width - m.v0) / sun_map_bin_width)), m.bins - 1);
            if (b1 < b0) continue;
            tiles.push_back({u, b0, b1, {x, z}});
            for (int b = b0; b <= b1; ++b) ++m.first[std::size_t(b) + 1];
        }
    for (int b = 0; b < m.bins; ++b) m.first[std::size_t(b) + 1] += m.first[std::size_t(b)];
    m.entries.resize(m.first.back());
    std::vector<std::uint32_t> fill(m.first.begin(), m.first.end() - 1);
    for (const Tile& t : tiles)
        for (int b = t.first_bin; b <= t.last_bin; ++b)
            m.entries[fill[std::size_t(b)]++] = glm::vec4(t.u, float(t.cell.x), float(t.cell.y), 0.0f);
    for (int b = 0; b < m.bins; ++b)
        std::sort(m.entries.begin() + m.first[std::size_t(b)], m.entries.begin() + m.first[std::size_t(b) + 1],
                  [](const glm::vec4& a, const glm::vec4& c) { return a.x < c.x; });
    return m;
}

std::vector<SunMap> build_sun_maps(const FrameInputs& in, SunKinds kinds) {
    const GiWindow& w = in.window;
    // Start points: texel centres and points 1e-3 outside wall faces, all within 0.01.
    const glm::vec2 lo(w.view.min_x - 0.01f, w.view.min_z - 0.01f);
    const glm::vec2 hi(w.view.min_x + w.view.width + 0.01f, w.view.min_z + w.view.height + 0.01f);
    std::vector<SunMap> maps;
    for (const GpuDirectionalLight& sun : in.directional_lights) {
        if (kinds != SunKinds::all && is_mixed_sun(sun) != (kinds == SunKinds::mixed)) {
            SunMap stand_in;
            stand_in.lit_everywhere = true;
            stand_in.first.assign(1, 0);
            maps.push_back(std::move(stand_in));
            continue;
        }
        maps.push_back(build_sun_map(in.walls, lo, hi, sun, in.wall_height));
    }
    return maps;
}

float sun_map_visibility(const SunMap& m, const WallView& walls, const GpuDirectionalLight& sun, glm::vec2 pixel,
                         float wall_height, int* handed_to_dda) {
    if (m.lit_everywhere) return 1.0f;
    const SunRay r = sun_ray(sun);
    const glm::vec2 start = pixel + r.dir * ray_bias;
    const float u = start.x * m.dir.x + start.y * m.dir.y, v = start.x * m.perp.x + start.y * m.perp.y;
    const int bin = std::clamp(int(std::floor((v - m.v0) / sun_map_bin_width)), 0, m.bins - 1);
    const glm::ivec2 start_cell(int(std::floor(start.x)), int(std::floor(start.y)));
    const float max_distance = sun_max_distance(sun);
    const float half_width = 0.5f * (std::abs(m.dir.x) + std::abs(m.dir.y));
    // Tiles behind the start (u more than 1 below) are never on the path.
    auto it = std::lower_bound(m.entries.begin() + m.first[std::size_t(bin)],
                               m.entries.begin() + m.first[std::size_t(bin) + 1], u - 1.0f,
                               [](const glm::vec4& e, float key) { return e.x < key; });
    const auto end = m.entries.begin() + m.first[std::size_t(bin) + 1];
    for (; it != end && it->x <= u + m.reach + 1.0f; ++it) {
        const glm::ivec2 cell(int(it->y), int(it->z));
        if (cell != start_cell) {
            // Across the sun, from the start's line to the tile centre (small numbers: exact enough).
            const glm::vec2 to_centre(float(cell.x) + 0.5f - start.x, float(cell.y) + 0.5f - start.y);
            const float across = std::abs(to_centre.x * m.perp.x + to_centre.y * m.perp.y);
            if (std::abs(across - half_width) < sun_map_ambiguity) // the line grazes the tile's corner
                return hand_to_dda(walls, sun, pixel, wall_height, handed_to_dda);
            if (across > half_width) continue; // the line misses the tile
            float t_in, t_out;
            span_in_tile(start, r.dir, cell, t_in, t_out);
            if (std::abs(t_out) < sun_map_ambiguity || std::abs(t_out - max_distance) < sun_map_ambiguity)
                return hand_to_dda(walls, sun, pixel, wall_height, handed_to_dda);
            if (t_out < 0.0f || t_out > max_distance) continue; // behind the start, or beyond the shadow distance
        }
        if (blocks(cell, start, r, wall_height)) return 0.0f;
    }
    return 1.0f;
}

PackedSunMaps pack_sun_maps(const std::vector<SunMap>& maps) {
    PackedSunMaps p;
    for (const SunMap& m : maps) {
        const auto base = std::uint32_t(p.first.size()), entry_base = std::uint32_t(p.entries.size());
        p.headers.push_back(glm::vec4(m.v0, 1.0f / sun_map_bin_width, float(m.bins), float(base)));
        p.headers.push_back(glm::vec4(m.reach, m.lit_everywhere ? 1.0f : 0.0f, 0.0f, 0.0f));
        for (std::uint32_t f : m.first) p.first.push_back(entry_base + f);
        p.entries.insert(p.entries.end(), m.entries.begin(), m.entries.end());
    }
    if (p.headers.empty()) p.headers.emplace_back(0.0f);
    if (p.first.empty()) p.first.push_back(0);
    if (p.entries.empty()) p.entries.emplace_back(0.0f);
    return p;
}

} // namespace lantern::gi
