// Photon paths on the domain's texel grid (Amanatides-Woo over texels; walls are whole
// tiles, so a wall is entered exactly when a step lands in a wall texel). Positions are in
// domain texel units, in double: a ray crosses a few hundred texels at most.
#include "tracer.hpp"

#include "lantern/core/hash.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lantern::transport {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// splitmix64 (lantern::mix64 is its finaliser): tiny state, independent streams by seed.
class Rng {
  public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    double uniform() { // [0, 1) with 53 random bits
        state_ += 0x9e3779b97f4a7c15ull;
        return double(mix64(state_) >> 11) * 0x1.0p-53;
    }

  private:
    std::uint64_t state_;
};

struct Ray {
    glm::dvec2 origin; // domain texel units
    glm::dvec2 dir;    // unit
    glm::ivec2 texel;  // the air texel the ray starts in
};

struct Hit {
    glm::ivec2 air;   // last air texel
    glm::ivec2 wall;  // first wall texel
    int face = 0;     // the wall's face that was hit
    glm::dvec2 point; // domain texel units
};

double first_crossing(double origin, int texel, double dir) {
    if (dir > 0.0) return std::max(0.0, (double(texel) + 1.0 - origin) / dir);
    if (dir < 0.0) return std::max(0.0, (origin - double(texel)) / -dir);
    return infinity;
}

void deposit(const Domain& d, Tally& tally, glm::ivec2 texel, glm::dvec3 value) {
    const glm::ivec2 w = d.to_window(texel);
    if (!d.in_window(w)) return;
    std::int64_t* t =
        &tally.ground[(std::size_t(w.y) * std::size_t(d.window_width) + std::size_t(w.x)) * 3];
    for (int c = 0; c < 3; ++c) t[c] += std::int64_t(value[c] + 0.5); // value >= 0
}

void deposit_face(const Domain& d, const FaceLayout& layout, Tally& tally, const Hit& hit,
                  glm::dvec3 value) {
    const glm::ivec2 w = d.to_window(hit.wall);
    if (!d.in_window(w)) return;
    std::int64_t* t = &tally.faces[layout.segment(hit.face, w.x, w.y) * 3];
    for (int c = 0; c < 3; ++c) t[c] += std::int64_t(value[c] + 0.5); // value >= 0
}

// Follows the ray, adding weight x track length to every window texel it crosses. True with
// `hit` filled when it reaches a wall, false when it leaves the domain.
bool fly(const Domain& d, const Ray& r, glm::dvec3 weight, Tally& tally, Hit& hit) {
    const glm::ivec2 step(r.dir.x > 0.0 ? 1 : -1, r.dir.y > 0.0 ? 1 : -1);
    double next_x = first_crossing(r.origin.x, r.texel.x, r.dir.x);
    double next_z = first_crossing(r.origin.y, r.texel.y, r.dir.y);
    const double delta_x = r.dir.x != 0.0 ? 1.0 / std::abs(r.dir.x) : infinity;
    const double delta_z = r.dir.y != 0.0 ? 1.0 / std::abs(r.dir.y) : infinity;
    glm::ivec2 texel = r.texel;
    double t = 0.0;
    for (;;) {
        const bool along_x = next_x <= next_z;
        const double t_next = along_x ? next_x : next_z;
        deposit(d, tally, texel, weight * (t_next - t));
        t = t_next;
        glm::ivec2 next = texel;
        if (along_x) {
            next.x += step.x;
            next_x += delta_x;
        } else {
            next.y += step.y;
            next_z += delta_z;
        }
        if (!d.contains(next)) return false;
        if (d.is_wall(next)) {
            hit.air = texel;
            hit.wall = next;
            hit.point = r.origin + r.dir * t;
            if (along_x) { // on the boundary exactly, whatever the rounding of t
                hit.face = step.x > 0 ? gi::face_neg_x : gi::face_pos_x;
                hit.point.x = double(step.x > 0 ? next.x : texel.x);
            } else {
                hit.face = step.y > 0 ? gi::face_neg_z : gi::face_pos_z;
                hit.point.y = double(step.y > 0 ? next.y : texel.y);
            }
            return true;
        }
        texel = next;
    }
}

// 2D Lambertian reflection: direction density cos(theta) / 2 about the normal, so
// sin(theta) is uniform in [-1, 1].
glm::dvec2 diffuse_direction(int face, Rng& rng) {
    const glm::dvec2 n(face_normal(face));
    const double s = 2.0 * rng.uniform() - 1.0;
    const double c = std::sqrt(std::max(0.0, 1.0 - s * s));
    return n * c + glm::dvec2(-n.y, n.x) * s;
}

// Russian roulette below `threshold`: survive with probability max / threshold, weight
// raised to keep the estimate unbiased.
bool survive(glm::dvec3& weight, double threshold, Rng& rng) {
    const double m = std::max(weight.x, std::max(weight.y, weight.z));
    if (m >= threshold) return true;
    if (!(m > 0.0) || rng.uniform() * threshold >= m) return false;
    weight *= threshold / m;
    return true;
}

// The ray leaving the point at parameter s (in [0, 1], inside the emitter's segment) of
// the emitter's face.
Ray launch(const Domain& d, const Emitter& e, double s, Rng& rng) {
    const double res = double(d.resolution);
    const glm::ivec2 tile = e.face.tile - d.min_tile;
    const glm::dvec2 corner = glm::dvec2(tile) * res;
    Ray r;
    r.dir = diffuse_direction(e.face.face, rng);
    const int along = e.segment; // texel along the face inside the tile
    switch (e.face.face) {
    case gi::face_pos_x:
        r.texel = {(tile.x + 1) * d.resolution, tile.y * d.resolution + along};
        r.origin = {corner.x + res, corner.y + s * res};
        break;
    case gi::face_neg_x:
        r.texel = {tile.x * d.resolution - 1, tile.y * d.resolution + along};
        r.origin = {corner.x, corner.y + s * res};
        break;
    case gi::face_pos_z:
        r.texel = {tile.x * d.resolution + along, (tile.y + 1) * d.resolution};
        r.origin = {corner.x + s * res, corner.y + res};
        break;
    default:
        r.texel = {tile.x * d.resolution + along, tile.y * d.resolution - 1};
        r.origin = {corner.x + s * res, corner.y};
        break;
    }
    return r;
}

// One photon from emission until it is absorbed, leaves the domain or runs out of bounces.
void trace_path(const Problem& p, const FaceLayout& layout, const TraceParams& params, Ray ray,
                glm::dvec3 weight, Rng& rng, Tally& tally) {
    const double scale = params.fixed_point;
    Hit hit;
    for (int reflections = 1;; ++reflections) {
        if (!fly(p.domain, ray, weight * scale, tally, hit)) return;
        deposit_face(p.domain, layout, tally, hit, weight * scale);
        if (reflections >= params.max_bounces) return;
        weight *= p.albedo(p.domain.cell(hit.wall)); // the hit tile's material
        if (!(std::max(weight.x, std::max(weight.y, weight.z)) > 0.0)) return; // a black wall
        if (!survive(weight, params.roulette_weight, rng)) return;
        ray = Ray{hit.point, diffuse_direction(hit.face, rng), hit.air};
    }
}

} // namespace

void Tally::reset(std::size_t ground_values, std::size_t face_values) {
    ground.assign(ground_values, 0);
    faces.assign(face_values, 0);
}

double fixed_point_scale(double weight_bound, int resolution, int max_bounces,
                         std::uint32_t photons) {
    // The largest deposit is weight_bound x resolution x sqrt(2) texels of track; 2 leaves
    // room for rounding.
    const double largest = weight_bound * double(resolution) * 2.0;
    return std::ldexp(1.0, 62) / (largest * double(photons) * double(max_bounces + 1));
}

void trace_photons(const Problem& p, const EmitterTable& emitters, const FaceLayout& layout,
                   const TraceParams& params, std::uint64_t stream, std::uint32_t photons,
                   Tally& tally) {
    Rng rng(stream);
    const double res = double(p.domain.resolution);
    // A photon of the segment (length 1/res) carries (albedo x E, or the emission) x length /
    // pdf, pdf = bound / total: at most total / res (each channel <= bound).
    const double emit_scale = emitters.total_bound() / res;
    // Deposits are fluence (weight x track / texel area = weight x t_texels x res) and
    // irradiance (weight / segment length = weight x res).
    TraceParams scaled = params;
    scaled.fixed_point = params.fixed_point * res;
    for (std::uint32_t n = 0; n < photons; ++n) {
        const Emitter& e = emitters.pick(rng.uniform());
        const double s = (double(e.segment) + rng.uniform()) / res;
        const std::uint8_t cell = p.inputs.walls.cell(e.face.tile.x, e.face.tile.y);
        const glm::dvec3 sent =
            e.emission ? p.emission(cell)
                       : p.albedo(cell) * glm::dvec3(source_face_irradiance(p.inputs, e.source, e.face,
                                                                            face_point(e.face, float(s))));
        glm::dvec3 weight = sent * (emit_scale / double(e.bound));
        if (!survive(weight, params.roulette_weight, rng)) continue;
        trace_path(p, layout, scaled, launch(p.domain, e, s, rng), weight, rng, tally);
    }
}

} // namespace lantern::transport
