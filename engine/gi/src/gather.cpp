// The gather method's reference (gather.hpp). gi_gather.comp.glsl mirrors every integer
// step here and sums the same floats in the same order.
#include "lantern/gi/gather.hpp"

#include "lantern/gi/blue_noise.hpp"
#include "lantern/gi/radiosity.hpp"
#include "reference_util.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace lantern::gi {
namespace {

using ref_util::for_each_row;
using ref_util::load4;
using ref_util::store4;

constexpr float pi = 3.14159265f;
// The table index of each face's outward normal (radiosity_directions: x = cos, z = sin).
constexpr int normal_index[4] = {0, 2048, 1024, 3072};
constexpr glm::ivec2 normal_of[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};

int floor_div(int a, int b) { // b > 0
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}
int floor_mod(int a, int b) { return a - floor_div(a, b) * b; }

int blue_noise_at(const GatherFrame& f, int x, int y) {
    const int nx = (x + f.noise_origin.x) & (blue_noise_size - 1), ny = (y + f.noise_origin.y) & (blue_noise_size - 1);
    return int(blue_noise_ranks()[std::size_t(ny * blue_noise_size + nx)]);
}

// B = albedo x (direct + indirect) + emission of face `face` at window texel t, by the
// material of t's tile.
glm::vec3 radiosity_at(const FrameInputs& in, const GatherFrame& f, const FaceTextures& direct, const Texture* faces,
                       int face, glm::ivec2 t, float ambient = 0.0f) {
    glm::vec3 e(ambient);
    if (direct[std::size_t(face)]) e += glm::vec3(load4(*direct[std::size_t(face)], t.x, t.y));
    if (faces) e += glm::vec3(load4(*faces, t.x, face * in.window.height + t.y));
    const glm::ivec2 tile = f.origin_tile + (f.offset + t) / f.resolution; // both non-negative
    const GpuMaterial m = material_of(in, in.walls.cell(tile.x, tile.y));
    return glm::vec3(m.albedo) * e + glm::vec3(m.emission);
}

// Fixed-point centre of window texel coordinate i (with offset) along one axis: exact for
// every resolution that divides 2048, within 1/8192 tile otherwise (the same on both backends).
int texel_center_fixed(int i_with_offset, int span, int resolution) {
    return ((2 * i_with_offset + span) * gather_unit) / (2 * resolution);
}

} // namespace

glm::vec3 gather_radiosity(const FrameInputs& in, const FaceTextures& direct, const Texture* faces, int face,
                           glm::ivec2 t, float ambient) {
    return radiosity_at(in, gather_frame(in), direct, faces, face, t, ambient);
}

float GatherHit::distance(glm::ivec2 d) const {
    // The entry point is p + (t_num / t_den) d in fixed point; |d| is about gather_unit.
    const float length = std::sqrt(float(d.x) * float(d.x) + float(d.y) * float(d.y));
    return float(t_num) / float(t_den) * length / float(gather_unit);
}

HeatGrid gather_grid(const FrameInputs& in) {
    return heat_grid(in.window, in.settings.gather.scale);
}

GatherFrame gather_frame(const FrameInputs& in) {
    const GiWindow& w = in.window;
    GatherFrame f;
    f.resolution = w.resolution;
    f.size = {w.width, w.height};
    f.origin_tile = {int(std::floor(w.view.min_x)), int(std::floor(w.view.min_z))};
    f.offset = {int(std::lround((w.view.min_x - float(f.origin_tile.x)) * float(w.resolution))),
                int(std::lround((w.view.min_z - float(f.origin_tile.y)) * float(w.resolution)))};
    f.tiles = {floor_div(f.offset.x + w.width + w.resolution - 1, w.resolution),
               floor_div(f.offset.y + w.height + w.resolution - 1, w.resolution)};
    const glm::ivec2 world_texel = f.origin_tile * w.resolution + f.offset;
    f.noise_origin = {floor_mod(world_texel.x, blue_noise_size), floor_mod(world_texel.y, blue_noise_size)};
    return f;
}

GatherHit gather_trace(const FrameInputs& in, const GatherFrame& f, glm::ivec2 p, glm::ivec2 cell, glm::ivec2 d) {
    const int sx = d.x > 0 ? 1 : d.x < 0 ? -1 : 0, sz = d.y > 0 ? 1 : d.y < 0 ? -1 : 0;
    const int ax = d.x < 0 ? -d.x : d.x, az = d.y < 0 ? -d.y : d.y;
    // Distances (fixed point, along each axis) from p to the next tile boundary.
    int nx = sx > 0 ? (cell.x + 1) * gather_unit - p.x : p.x - cell.x * gather_unit;
    int nz = sz > 0 ? (cell.y + 1) * gather_unit - p.y : p.y - cell.y * gather_unit;
    // At most 255 tiles: the products below stay under 2^32 (light from farther is lost).
    const int max_steps = std::min(f.tiles.x + f.tiles.y + 2, gather_max_steps);
    for (int s = 0; s < max_steps; ++s) {
        // The nearer boundary: nx / ax against nz / az (an axis the ray does not move along
        // is never crossed); a tie steps x first.
        const bool step_x =
            az == 0 || (ax != 0 && std::uint32_t(nx) * std::uint32_t(az) <= std::uint32_t(nz) * std::uint32_t(ax));
        int face, along, t_num;
        if (step_x) {
            cell.x += sx;
            t_num = nx;
            nx += gather_unit;
            face = sx > 0 ? 1 : 0;
        } else {
            cell.y += sz;
            t_num = nz;
            nz += gather_unit;
            face = sz > 0 ? 3 : 2;
        }
        if (cell.x < 0 || cell.y < 0 || cell.x >= f.tiles.x || cell.y >= f.tiles.y) return {};
        if (!in.walls.is_wall(f.origin_tile.x + cell.x, f.origin_tile.y + cell.y)) continue;
        // The entry point's coordinate along the face (non-negative operands throughout).
        GatherHit h;
        h.face = face;
        h.t_num = t_num;
        h.t_den = step_x ? ax : az;
        const int r = f.resolution;
        if (step_x) {
            const int dz = int((std::uint32_t(az) * std::uint32_t(t_num)) / std::uint32_t(ax));
            along = sz >= 0 ? p.y + dz : p.y - dz;
            const int row = std::clamp((along * r) / gather_unit, cell.y * r, cell.y * r + r - 1);
            h.texel = {(face == 1 ? cell.x * r : cell.x * r + r - 1) - f.offset.x, row - f.offset.y};
        } else {
            const int dx = int((std::uint32_t(ax) * std::uint32_t(t_num)) / std::uint32_t(az));
            along = sx >= 0 ? p.x + dx : p.x - dx;
            const int col = std::clamp((along * r) / gather_unit, cell.x * r, cell.x * r + r - 1);
            h.texel = {col - f.offset.x, (face == 3 ? cell.y * r : cell.y * r + r - 1) - f.offset.y};
        }
        if (h.texel.x < 0 || h.texel.y < 0 || h.texel.x >= f.size.x || h.texel.y >= f.size.y) return {};
        return h;
    }
    return {};
}

bool gather_face_texel(const FrameInputs& in, const GatherFrame& f, int x, int y, int face) {
    const int r = f.resolution;
    const int gx = f.offset.x + x, gy = f.offset.y + y; // texels from the origin tile's corner
    const glm::ivec2 tile = f.origin_tile + glm::ivec2(gx / r, gy / r);
    if (!in.walls.is_wall(tile.x, tile.y)) return false;
    const bool edge = face == 0 ? gx % r == r - 1 : face == 1 ? gx % r == 0 : face == 2 ? gy % r == r - 1 : gy % r == 0;
    return edge && !in.walls.is_wall(tile.x + normal_of[face].x, tile.y + normal_of[face].y);
}

namespace {
// The fixed-point centre of gather-grid texel (i, j) and its tile, from the origin tile.
glm::ivec2 ground_center(const GatherFrame& f, const HeatGrid& g, int i, int j) {
    return {texel_center_fixed(f.offset.x + i * g.scale, g.scale, f.resolution),
            texel_center_fixed(f.offset.y + j * g.scale, g.scale, f.resolution)};
}
} // namespace

bool gather_ground_texel_in_air(const FrameInputs& in, const GatherFrame& f, const HeatGrid& g, int i, int j) {
    const glm::ivec2 p = ground_center(f, g, i, j);
    return !in.walls.is_wall(f.origin_tile.x + p.x / gather_unit, f.origin_tile.y + p.y / gather_unit);
}

glm::ivec2 gather_face_size(const FrameInputs& in) {
    return {in.window.width, 4 * in.window.height};
}

Texture reference_gather_faces(const FrameInputs& in, const FaceTextures& direct, const Texture* previous,
                               const RefOptions& options, const GatherWeighting& weighting) {
    const GatherFrame f = gather_frame(in);
    const int w = in.window.width, h = in.window.height, r = f.resolution;
    const int rays = in.settings.gather.face_rays;
    const std::vector<glm::ivec2>& dirs = radiosity_directions();
    Texture out("gather_face", TexFormat::rgba16f, w, 4 * h);
    for_each_row(h, options, [&](int y) {
        for (int x = 0; x < w; ++x)
            for (int face = 0; face < 4; ++face) {
                store4(out, x, face * h + y, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
                if (!gather_face_texel(in, f, x, y, face)) continue;
                const int gx = f.offset.x + x, gy = f.offset.y + y;
                // The face point: on the face's line, at the texel's centre along it; the ray
                // starts in the air tile across.
                glm::ivec2 p, cell(gx / r, gy / r);
                if (face < 2) {
                    p = {(cell.x + (face == 0 ? 1 : 0)) * gather_unit, texel_center_fixed(gy, 1, r)};
                    cell.x += normal_of[face].x;
                } else {
                    p = {texel_center_fixed(gx, 1, r), (cell.y + (face == 2 ? 1 : 0)) * gather_unit};
                    cell.y += normal_of[face].y;
                }
                // Rays equally spaced over the open half circle, turned by the texel's noise.
                const int base = normal_index[face] - 1024, noise = blue_noise_at(f, x, y) / 2;
                glm::vec3 sum(0.0f);
                for (int k = 0; k < rays; ++k) {
                    const glm::ivec2 d = dirs[std::size_t((base + (k * 2048 + noise) / rays) & 4095)];
                    const int cosine = d.x * normal_of[face].x + d.y * normal_of[face].y; // x 4096
                    if (cosine <= 0) continue;
                    const GatherHit hit = gather_trace(in, f, p, cell, d);
                    if (hit.face < 0) continue;
                    sum += radiosity_at(in, f, direct, previous, hit.face, hit.texel, weighting.ambient) *
                           (float(cosine) * weighting.weight(hit.distance(d)));
                }
                // E = integral of (B / 2) cos over the half circle: (pi / rays) x sum (B / 2) cos.
                const glm::vec3 e = sum * (pi / (2.0f * 4096.0f * float(rays)));
                store4(out, x, face * h + y, glm::vec4(e, 1.0f));
            }
    });
    return out;
}

std::array<Texture, 4> reference_gather_fill(const FrameInputs& in, const Texture& faces,
                                             const RefOptions& options) {
    const GatherFrame f = gather_frame(in);
    const int w = in.window.width, h = in.window.height, r = f.resolution;
    const std::uint32_t computed = computed_faces(in.settings);
    std::array<Texture, 4> out;
    for (int face = 0; face < 4; ++face)
        if (computes_face(computed, face))
            out[std::size_t(face)] = Texture(std::string("wall_indirect_") + face_suffix[face], TexFormat::rgba16f, w, h);
    for_each_row(h, options, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const int gx = f.offset.x + x, gy = f.offset.y + y;
            for (int face = 0; face < 4; ++face) {
                if (!computes_face(computed, face)) continue;
                // The edge texel of this texel's tile on `face`, in the same row or column.
                glm::ivec2 e(x, y);
                if (face == 0) e.x = x + (r - 1 - gx % r);
                if (face == 1) e.x = x - gx % r;
                if (face == 2) e.y = y + (r - 1 - gy % r);
                if (face == 3) e.y = y - gy % r;
                glm::vec4 v(0.0f, 0.0f, 0.0f, 1.0f);
                if (e.x >= 0 && e.y >= 0 && e.x < w && e.y < h && gather_face_texel(in, f, e.x, e.y, face))
                    v = glm::vec4(glm::vec3(load4(faces, e.x, face * h + e.y)), 1.0f);
                store4(out[std::size_t(face)], x, y, v);
            }
        }
    });
    return out;
}

Texture reference_gather_ground(const FrameInputs& in, const FaceTextures& direct, const Texture& faces,
                                const RefOptions& options, const GatherWeighting& weighting) {
    const GatherFrame f = gather_frame(in);
    const HeatGrid g = gather_grid(in);
    const int rays = in.settings.gather.rays;
    const std::vector<glm::ivec2>& dirs = radiosity_directions();
    Texture out("gather_ground", TexFormat::rgba16f, g.width, g.height);
    for_each_row(g.height, options, [&](int j) {
        for (int i = 0; i < g.width; ++i) {
            // Grid texels in walls gather nothing and stay zero.
            if (!gather_ground_texel_in_air(in, f, g, i, j)) continue;
            const glm::ivec2 p = ground_center(f, g, i, j);
            const glm::ivec2 cell(p.x / gather_unit, p.y / gather_unit);
            glm::vec3 sum(0.0f);
            const int noise = blue_noise_at(f, i * g.scale, j * g.scale);
            for (int k = 0; k < rays; ++k) {
                const glm::ivec2 d = dirs[std::size_t(((k * 4096 + noise) / rays) & 4095)];
                const GatherHit hit = gather_trace(in, f, p, cell, d);
                if (hit.face >= 0)
                    sum += radiosity_at(in, f, direct, &faces, hit.face, hit.texel, weighting.ambient) *
                           weighting.weight(hit.distance(d));
            }
            // Fluence = integral of B / 2 over the circle: (2 pi / rays) x sum B / 2.
            store4(out, i, j, glm::vec4(sum * (pi / float(rays)), 1.0f));
        }
    });
    return out;
}

} // namespace lantern::gi
