// Point lights' angular shadow maps (point_map.hpp). The lookup mirrors
// shaders/include/lantern/gi_point_map.glsl operation for operation: keep the two in step.
#include "lantern/gi/point_map.hpp"

#include "lantern/gi/reference.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lantern::gi {
namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
// Bins per light: about this many per texel of the light's rim (a wedge is then about a
// texel wide at the edge of its reach), four per quadrant at the least.
constexpr float bins_per_rim_texel = 0.5f;
constexpr int max_bins = 4096;
// Pseudo-angle slack when choosing which bins a run can touch (the distances are then
// computed per bin, with the geometric margin).
constexpr float angle_slack = 1e-4f;
// Distance slack folded into the stored distances (float error of a texel's distance).
constexpr float distance_slack = 2e-4f;

struct Box {
    glm::vec2 lo, hi; // relative to the light
};

struct Run {
    int x0, z, len; // tiles: [x0, x0 + len) x [z, z + 1] for a horizontal run
    bool vertical;  // then [x0, x0 + 1] x [z, z + len)
};

Box run_box(const Run& r, glm::vec2 light, float grow) {
    const glm::vec2 lo(float(r.x0), float(r.z));
    const glm::vec2 size = r.vertical ? glm::vec2(1.0f, float(r.len)) : glm::vec2(float(r.len), 1.0f);
    return {lo - light - grow, lo + size - light + grow};
}

bool contains_origin(const Box& b) { return b.lo.x <= 0.0f && b.hi.x >= 0.0f && b.lo.y <= 0.0f && b.hi.y >= 0.0f; }

// A unit direction with pseudo-angle a (the inverse of pseudo_angle).
glm::vec2 direction_of(float a) {
    glm::vec2 d;
    if (a < 1.0f) d = {1.0f - a, a};
    else if (a < 2.0f) d = {1.0f - a, 2.0f - a};
    else if (a < 3.0f) d = {a - 3.0f, 2.0f - a};
    else d = {a - 3.0f, a - 4.0f};
    return d / std::sqrt(d.x * d.x + d.y * d.y);
}

// Where the ray t * u (t >= 0, u unit) enters and leaves box b; false when it misses.
bool ray_box(glm::vec2 u, const Box& b, float& t_in, float& t_out) {
    t_in = -inf;
    t_out = inf;
    for (int a = 0; a < 2; ++a) {
        if (u[a] == 0.0f) {
            if (0.0f < b.lo[a] || 0.0f > b.hi[a]) return false;
            continue;
        }
        const float t1 = b.lo[a] / u[a], t2 = b.hi[a] / u[a];
        t_in = std::max(t_in, std::min(t1, t2));
        t_out = std::min(t_out, std::max(t1, t2));
    }
    if (t_in > t_out || t_out < 0.0f) return false;
    t_in = std::max(t_in, 0.0f);
    return true;
}

// True when the pseudo-angle a lies in [lo, lo + width] (modulo 4), with `slack` either side.
bool in_wedge(float a, float lo, float width, float slack) {
    float d = a - (lo - slack);
    d -= 4.0f * std::floor(d * 0.25f);
    return d <= width + 2.0f * slack;
}

// The pseudo-angle interval [lo, hi] (hi - lo < 2, lo may be < 0 or hi > 4) of a box that
// does not contain the origin: its corners' angles around the centre's.
void angle_interval(const Box& b, float& lo, float& hi) {
    const float c = pseudo_angle(0.5f * (b.lo + b.hi));
    lo = inf;
    hi = -inf;
    for (glm::vec2 corner : {b.lo, b.hi, glm::vec2(b.lo.x, b.hi.y), glm::vec2(b.hi.x, b.lo.y)}) {
        float d = pseudo_angle(corner) - c;
        if (d > 2.0f) d -= 4.0f;
        if (d <= -2.0f) d += 4.0f;
        lo = std::min(lo, c + d);
        hi = std::max(hi, c + d);
    }
}

struct LightMap {
    int bins = 0;
    float width = 0.0f; // pseudo-angle per bin
    std::vector<float> lit1, lit2, shadow;
    std::vector<std::uint32_t> run1;

    void offer_lit(int b, float d, std::uint32_t run) {
        const auto i = std::size_t(b);
        if (d < lit1[i]) {
            lit2[i] = lit1[i];
            lit1[i] = d;
            run1[i] = run;
        } else if (d < lit2[i]) {
            lit2[i] = d;
        }
    }
};

std::uint32_t run_code(const Run& r, glm::ivec2 light_tile) {
    return std::uint32_t(r.x0 - light_tile.x + 128) | std::uint32_t(r.z - light_tile.y + 128) << 8 |
           std::uint32_t(r.len) << 16;
}

// The nearest distance at which wedge b meets the widened run `e`: the box's nearest point
// when it lies in the wedge, else the nearer entry of the wedge's two edge rays (the nearest
// point of a convex set cut by a wedge lies on the wedge's edge when not inside it).
float near_in_wedge(const LightMap& m, int b, const Box& e) {
    const glm::vec2 nearest = glm::clamp(glm::vec2(0.0f), e.lo, e.hi);
    const float a0 = float(b) * m.width;
    if (in_wedge(pseudo_angle(nearest), a0, m.width, angle_slack))
        return std::sqrt(nearest.x * nearest.x + nearest.y * nearest.y);
    float best = inf, t_in, t_out;
    if (ray_box(direction_of(a0), e, t_in, t_out)) best = t_in;
    if (ray_box(direction_of(float(b + 1) * m.width), e, t_in, t_out)) best = std::min(best, t_in);
    return best;
}

// The farthest distance at which a ray of wedge b leaves the narrowed run `s` (the wedge lies
// inside the run's angle): the edge rays' exits and the corners inside the wedge; inf when an
// edge ray misses (float doubt).
float far_in_wedge(const LightMap& m, int b, const Box& s) {
    const float a0 = float(b) * m.width;
    float t_in, t_out, far = 0.0f;
    if (!ray_box(direction_of(a0), s, t_in, t_out)) return inf;
    far = t_out;
    if (!ray_box(direction_of(float(b + 1) * m.width), s, t_in, t_out)) return inf;
    far = std::max(far, t_out);
    for (glm::vec2 corner : {s.lo, s.hi, glm::vec2(s.lo.x, s.hi.y), glm::vec2(s.hi.x, s.lo.y)})
        if (in_wedge(pseudo_angle(corner), a0, m.width, angle_slack))
            far = std::max(far, std::sqrt(corner.x * corner.x + corner.y * corner.y));
    return far;
}

int wrap_bin(int b, int bins) {
    b %= bins;
    return b < 0 ? b + bins : b;
}

// The margin for a light at `pos` with radius r in a window whose coordinates reach `extent`:
// well above the DDA's float error there (its start point and accumulated boundary distances).
float margin_for(glm::vec2 pos, float radius, float extent) {
    const float c = std::max({std::abs(pos.x), std::abs(pos.y), extent});
    return 2.5e-4f + 2e-6f * c + 4e-6f * radius;
}

void build_one(const WallView& walls, glm::vec2 pos, float radius, float margin, int bins, PointMaps& out) {
    LightMap m;
    m.bins = bins;
    m.width = 4.0f / float(bins);
    const auto n = std::size_t(bins);
    m.lit1.assign(n, inf);
    m.lit2.assign(n, inf);
    m.shadow.assign(n, inf);
    m.run1.assign(n, point_map_no_run);

    const glm::ivec2 tile(int(std::floor(pos.x)), int(std::floor(pos.y)));
    const int tiles = int(std::ceil(radius)) + 3;
    const glm::ivec2 lo = glm::max(tile - tiles, walls.origin);
    const glm::ivec2 hi = glm::min(tile + tiles + 1, walls.origin + glm::ivec2(walls.width, walls.height)); // exclusive
    std::vector<Run> runs;
    for (int z = lo.y; z < hi.y; ++z)
        for (int x = lo.x; x < hi.x;) {
            if (!walls.is_wall(x, z)) {
                ++x;
                continue;
            }
            const int x0 = x;
            while (x < hi.x && walls.is_wall(x, z)) ++x;
            runs.push_back({x0, z, x - x0, false});
        }
    const std::size_t horizontal = runs.size();
    for (int x = lo.x; x < hi.x; ++x)
        for (int z = lo.y; z < hi.y;) {
            if (!walls.is_wall(x, z)) {
                ++z;
                continue;
            }
            const int z0 = z;
            while (z < hi.y && walls.is_wall(x, z)) ++z;
            if (z - z0 > 1) runs.push_back({x, z0, z - z0, true}); // single tiles are horizontal runs already
        }

    // Lit: every wall tile once, in horizontal runs, widened.
    for (std::size_t i = 0; i < horizontal; ++i) {
        const Box e = run_box(runs[i], pos, margin);
        const std::uint32_t code = run_code(runs[i], tile);
        if (contains_origin(e)) {
            for (int b = 0; b < bins; ++b) m.offer_lit(b, 0.0f, code);
            continue;
        }
        float a_lo, a_hi;
        angle_interval(e, a_lo, a_hi);
        const int b0 = int(std::floor((a_lo - angle_slack) / m.width)), b1 = int(std::floor((a_hi + angle_slack) / m.width));
        for (int k = b0; k <= std::min(b1, b0 + bins - 1); ++k) {
            const int b = wrap_bin(k, bins);
            const float d = near_in_wedge(m, b, e);
            if (d < inf) m.offer_lit(b, d, code);
        }
    }
    // Shadow: runs both ways, narrowed, over the wedges they cover whole.
    for (const Run& r : runs) {
        const Box s = run_box(r, pos, -margin);
        if (contains_origin(s)) { // the light is inside a wall: every ray starts in it
            const float far = std::max({glm::length(s.lo), glm::length(s.hi), glm::length(glm::vec2(s.lo.x, s.hi.y)),
                                        glm::length(glm::vec2(s.hi.x, s.lo.y))});
            for (int b = 0; b < bins; ++b) m.shadow[std::size_t(b)] = std::min(m.shadow[std::size_t(b)], far);
            continue;
        }
        float a_lo, a_hi;
        angle_interval(s, a_lo, a_hi);
        const int b0 = int(std::ceil((a_lo + angle_slack) / m.width)), b1 = int(std::floor((a_hi - angle_slack) / m.width)) - 1;
        for (int k = b0; k <= std::min(b1, b0 + bins - 1); ++k) {
            const int b = wrap_bin(k, bins);
            m.shadow[std::size_t(b)] = std::min(m.shadow[std::size_t(b)], far_in_wedge(m, b, s));
        }
    }

    out.headers.emplace_back(float(out.bins.size()), margin);
    // Fractions of the reach, rounded the safe way (distances beyond it never occur: targets
    // lie within radius + 1.01 of the light).
    const float reach = radius + 3.0f;
    const auto down = [&](float d, float steps) {
        return d < inf ? std::uint32_t(std::clamp(std::floor(std::max(d - distance_slack, 0.0f) / reach * steps), 0.0f, steps))
                       : std::uint32_t(steps);
    };
    const auto up = [&](float d) {
        return d < inf ? std::uint32_t(std::clamp(std::ceil((d + distance_slack) / reach * 65535.0f), 0.0f, 65535.0f)) : 65535u;
    };
    for (std::size_t b = 0; b < n; ++b)
        out.bins.emplace_back(down(m.lit1[b], 65535.0f) | up(m.shadow[b]) << 16, m.run1[b] | down(m.lit2[b], 255.0f) << 24);
}

// Segment 0 -> d against box b (relative to the segment's start): true when they meet.
bool segment_meets(glm::vec2 d, const Box& b) {
    float t0 = 0.0f, t1 = 1.0f;
    for (int a = 0; a < 2; ++a) {
        if (d[a] == 0.0f) {
            if (0.0f < b.lo[a] || 0.0f > b.hi[a]) return false;
            continue;
        }
        const float inv = 1.0f / d[a];
        const float ta = b.lo[a] * inv, tb = b.hi[a] * inv;
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    return t0 <= t1;
}

// Run `code` against the segment from the light to the target: 1 misses it (widened by the
// margin), 0 crosses it (narrowed), -1 unsure.
int run_test(std::uint32_t code, glm::vec2 pos, glm::vec2 d, float margin) {
    if (code == point_map_no_run) return -1;
    const glm::vec2 tile(std::floor(pos.x), std::floor(pos.y));
    const glm::vec2 lo = tile + glm::vec2(float(int(code & 0xffu) - 128), float(int((code >> 8) & 0xffu) - 128)) - pos;
    const glm::vec2 hi = lo + glm::vec2(float((code >> 16) & 0xffu), 1.0f);
    if (!segment_meets(d, Box{lo - margin, hi + margin})) return 1;
    if (segment_meets(d, Box{lo + margin, hi - margin})) return 0;
    return -1;
}

float hand_to_dda(const WallView& walls, glm::vec2 pos, glm::vec2 target, float radius, int* count) {
    if (count) ++*count;
    return shadow_dda(walls, pos, target, radius);
}

} // namespace

float pseudo_angle(glm::vec2 d) {
    const float t = d.x / (std::abs(d.x) + std::abs(d.y)); // one division, no branch: cheap on lavapipe
    return d.y >= 0.0f ? 1.0f - t : 3.0f + t;
}

int point_map_bins(float radius, int res) {
    return 4 * int(std::clamp(std::ceil(bins_per_rim_texel * radius * float(res)), 4.0f, float(max_bins / 4)));
}

PointMaps build_point_maps(const FrameInputs& in) {
    PointMaps out;
    const GiWindow& w = in.window;
    out.resolution = w.resolution;
    const float extent = std::max({std::abs(w.view.min_x), std::abs(w.view.min_z), std::abs(w.view.min_x + w.view.width),
                                   std::abs(w.view.min_z + w.view.height)});
    for (const GpuPointLight& l : in.point_lights) {
        const glm::vec2 pos(l.position_radius.x, l.position_radius.y);
        const float radius = l.position_radius.z;
        const int bins = point_map_bins(radius, w.resolution);
        // Beyond 2^24 bins a base is no longer exact as a float: those lights take the DDA.
        if (!(radius >= point_map_min_radius && radius <= point_map_max_radius) || !std::isfinite(pos.x) ||
            !std::isfinite(pos.y) || std::max(std::abs(pos.x), std::abs(pos.y)) > 1e6f ||
            out.bins.size() + std::size_t(bins) > (std::size_t(1) << 24)) {
            out.headers.emplace_back(-1.0f, 0.0f);
            continue;
        }
        build_one(in.walls, pos, radius, margin_for(pos, radius, extent), bins, out);
    }
    if (out.headers.empty()) out.headers.emplace_back(-1.0f, 0.0f);
    if (out.bins.empty()) out.bins.emplace_back(0u);
    return out;
}

float point_map_lookup(const PointMaps& maps, std::size_t light, glm::vec2 pos, glm::vec2 target, float radius) {
    const glm::vec2 h = maps.headers[light];
    if (h.x < 0.0f) return -1.0f;
    const glm::vec2 d = target - pos;
    const float dist = std::sqrt(d.x * d.x + d.y * d.y);
    if (dist < 2e-4f) return -1.0f;
    const int bins = point_map_bins(radius, maps.resolution);
    int b = int(pseudo_angle(d) * (float(bins) * 0.25f));
    if (b >= bins) b -= bins;
    b = std::max(b, 0);
    const glm::uvec2 e = maps.bins[std::size_t(h.x) + std::size_t(b)];
    const float step = (radius + 3.0f) / 65535.0f;
    if (dist < float(e.x & 0xffffu) * step) return 1.0f;
    if (dist > float(e.x >> 16) * step) return 0.0f;
    const int r1 = run_test(e.y & 0xffffffu, pos, d, h.y);
    if (r1 == 0) return 0.0f;
    if (r1 > 0 && dist < float(e.y >> 24) * ((radius + 3.0f) / 255.0f)) return 1.0f;
    return -1.0f;
}

float point_map_visibility(const PointMaps& maps, const WallView& walls, std::size_t light, glm::vec2 pos,
                           glm::vec2 target, float radius, int* handed_to_dda) {
    const float v = point_map_lookup(maps, light, pos, target, radius);
    return v >= 0.0f ? v : hand_to_dda(walls, pos, target, radius, handed_to_dda);
}

} // namespace lantern::gi
