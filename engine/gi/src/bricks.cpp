// Adaptive bricks (bricks.hpp).
#include "lantern/gi/bricks.hpp"

#include "lantern/core/assert.hpp"

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::gi {
namespace {

int clampi(int v, int lo, int hi) { return std::min(std::max(v, lo), hi); }

// Wall texels take the mean of their open neighbours, twice, so bilinear filtering across a
// wall's edge does not pull light to black (lightmap dilation). Open texels keep their value.
Field dilated(const Field& f) {
    Field out = f;
    std::vector<std::uint8_t> known = f.air;
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<float> rgb = out.rgb;
        std::vector<std::uint8_t> next = known;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(f.width) + std::size_t(x);
                if (known[i]) continue;
                glm::vec3 sum(0.0f);
                int n = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if (nx < 0 || ny < 0 || nx >= f.width || ny >= f.height) continue;
                        const std::size_t j = std::size_t(ny) * std::size_t(f.width) + std::size_t(nx);
                        if (!known[j]) continue;
                        sum += out.at(nx, ny);
                        ++n;
                    }
                if (n == 0) continue;
                for (int c = 0; c < 3; ++c) rgb[i * 3 + std::size_t(c)] = sum[c] / float(n);
                next[i] = 1;
            }
        out.rgb = std::move(rgb);
        known = std::move(next);
    }
    return out;
}

// One layer's bricks: appended to the shared brick list, its cells in cell_brick/cell_level
// at `cell_base` (the layer's first cell).
struct Builder {
    const Field& f; // dilated
    const Field& original;
    float eps;
    BrickAtlas& out;
    std::vector<std::vector<std::uint8_t>>& bricks; // 6 x 6 x RGBA8 each, every layer's
    std::vector<int>& cell_brick;                   // per level-0 cell of every layer; -1 empty
    std::vector<int>& cell_level;
    std::size_t cell_base = 0;
    int max_level = brick_levels - 1;
    std::span<const std::uint8_t> finest_level; // per level-0 cell (build_bricks'), or empty

    // The coarsest level the cell at o (level-0 cells `cells` a side) may stop at whatever its
    // range: the least of its cells' finest levels, capped at max_level.
    int floor_level(glm::ivec2 o, int cells) const {
        if (finest_level.empty()) return 0;
        int floor = brick_levels - 1;
        const int x0 = o.x / brick_probes, y0 = o.y / brick_probes;
        for (int y = y0; y < std::min(y0 + cells, out.cells_y); ++y)
            for (int x = x0; x < std::min(x0 + cells, out.cells_x); ++x)
                floor = std::min(floor, int(finest_level[std::size_t(y) * std::size_t(out.cells_x) + std::size_t(x)]));
        return std::min(floor, max_level);
    }

    // The probe (i, j) of a level-`level` brick at grid origin o: the box mean of its s x s
    // texels (clamped to the field).
    glm::vec3 probe(glm::ivec2 o, int level, int i, int j) const {
        const int s = 1 << level;
        glm::vec3 sum(0.0f);
        for (int y = 0; y < s; ++y)
            for (int x = 0; x < s; ++x)
                sum += f.at(clampi(o.x + i * s + x, 0, f.width - 1), clampi(o.y + j * s + y, 0, f.height - 1));
        return sum / float(s * s);
    }

    // Colour range over the cell and its apron (one probe spacing around it).
    float range(glm::ivec2 o, int level) const {
        const int s = 1 << level, side = brick_probes * s;
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (int y = o.y - s; y < o.y + side + s; ++y)
            for (int x = o.x - s; x < o.x + side + s; ++x) {
                const glm::vec3 v = f.at(clampi(x, 0, f.width - 1), clampi(y, 0, f.height - 1));
                lo = glm::min(lo, v);
                hi = glm::max(hi, v);
            }
        const glm::vec3 r = hi - lo;
        return std::max({r.x, r.y, r.z});
    }

    // An open texel within one level-0 brick (4 texels) of the cell (the seed's margin).
    bool near_air(glm::ivec2 o, int side) const {
        for (int y = std::max(0, o.y - brick_probes); y < std::min(f.height, o.y + side + brick_probes); ++y)
            for (int x = std::max(0, o.x - brick_probes); x < std::min(f.width, o.x + side + brick_probes); ++x)
                if (original.air[std::size_t(y) * std::size_t(f.width) + std::size_t(x)]) return true;
        return false;
    }

    void store(glm::ivec2 o, int level) {
        std::vector<std::uint8_t> b(brick_texels * brick_texels * 4);
        for (int j = -1; j <= brick_probes; ++j)
            for (int i = -1; i <= brick_probes; ++i)
                encode_rgbm(probe(o, level, i, j), &b[std::size_t(((j + 1) * brick_texels + (i + 1)) * 4)]);
        const int index = int(bricks.size());
        bricks.push_back(std::move(b));
        ++out.bricks_per_level[level];
        const int cells = 1 << level; // level-0 cells a side
        for (int cy = 0; cy < cells; ++cy)
            for (int cx = 0; cx < cells; ++cx) {
                const int x = o.x / brick_probes + cx, y = o.y / brick_probes + cy;
                if (x >= out.cells_x || y >= out.cells_y) continue;
                cell_brick[cell_base + std::size_t(y * out.cells_x + x)] = index;
                cell_level[cell_base + std::size_t(y * out.cells_x + x)] = level;
            }
    }

    void visit(glm::ivec2 o, int level) {
        const int side = brick_probes << level;
        if (o.x >= f.width || o.y >= f.height) return;
        if (!near_air(o, side)) return; // wholly inside rock: empty
        if (level == 0 || (level <= max_level && (level <= floor_level(o, 1 << level) || range(o, level) <= eps))) {
            store(o, level);
            return;
        }
        const int half = side / 2;
        for (int k = 0; k < 4; ++k) visit(o + glm::ivec2((k & 1) * half, (k >> 1) * half), level - 1);
    }
};

glm::vec4 texel_normalised(const BrickAtlas& a, int x, int y) {
    const std::size_t i = (std::size_t(y) * std::size_t(a.atlas_bricks_x * brick_texels) + std::size_t(x)) * 4;
    return glm::vec4(a.atlas[i], a.atlas[i + 1], a.atlas[i + 2], a.atlas[i + 3]) / 255.0f;
}

} // namespace

void encode_rgbm(glm::vec3 c, std::uint8_t out[4]) {
    c = glm::max(c, glm::vec3(0.0f));
    const float m = std::clamp(std::max({c.r, c.g, c.b}) / rgbm_range, 0.0f, 1.0f);
    const int m8 = std::max(1, int(std::ceil(m * 255.0f))); // rounded up: no channel clips
    const float scale = 255.0f / (rgbm_range * float(m8) / 255.0f);
    for (int k = 0; k < 3; ++k) out[k] = std::uint8_t(std::clamp(int(std::lround(c[k] * scale)), 0, 255));
    out[3] = std::uint8_t(m8);
}

glm::vec3 decode_rgbm(const std::uint8_t in[4]) {
    return glm::vec3(in[0], in[1], in[2]) / 255.0f * (float(in[3]) / 255.0f) * rgbm_range;
}

BrickAtlas build_bricks(const Field& field, float eps, int bricks_per_row, int max_level) {
    return build_bricks(std::span<const Field>(&field, 1), eps, bricks_per_row, max_level);
}

BrickAtlas build_bricks(std::span<const Field> fields, float eps, int bricks_per_row, int max_level,
                        std::span<const std::uint8_t> finest_level) {
    BrickAtlas out;
    LANTERN_ASSERT(!fields.empty(), "build_bricks needs a field");
    const int width = fields[0].width, height = fields[0].height;
    for (const Field& f : fields)
        LANTERN_ASSERT(f.width == width && f.height == height && f.rgb.size() == std::size_t(width) * std::size_t(height) * 3 &&
                           f.air.size() == std::size_t(width) * std::size_t(height),
                       "build_bricks: the layers differ in size");
    out.layers = int(fields.size());
    out.cells_x = (width + brick_probes - 1) / brick_probes;
    out.cells_y = (height + brick_probes - 1) / brick_probes;
    const std::size_t layer_cells = std::size_t(out.cells_x) * std::size_t(out.cells_y);
    LANTERN_ASSERT(finest_level.empty() || finest_level.size() == layer_cells, "build_bricks: finest_level is one value per cell");
    std::vector<std::vector<std::uint8_t>> bricks;
    std::vector<int> cell_brick(layer_cells * fields.size(), -1), cell_level(cell_brick.size(), 0);
    const int top = brick_probes << (brick_levels - 1);
    for (std::size_t layer = 0; layer < fields.size(); ++layer) {
        const Field f = dilated(fields[layer]);
        Builder b{f, fields[layer], eps, out, bricks, cell_brick, cell_level, layer * layer_cells,
                  std::clamp(max_level, 0, brick_levels - 1), finest_level};
        for (int y = 0; y < height; y += top)
            for (int x = 0; x < width; x += top) b.visit({x, y}, brick_levels - 1);
    }
    // Atlas: bricks in rows of a square's width.
    const int n = int(bricks.size());
    out.atlas_bricks_x = bricks_per_row > 0 ? std::min(bricks_per_row, brick_max_atlas)
                                            : std::max(1, int(std::ceil(std::sqrt(double(n)))));
    out.atlas_bricks_y = std::max(1, (n + out.atlas_bricks_x - 1) / out.atlas_bricks_x);
    if (out.atlas_bricks_x > brick_max_atlas || out.atlas_bricks_y > brick_max_atlas) {
        // More bricks than 12-bit indices address: the caller reports it (nothing stored).
        out.too_many = n;
        out.atlas_bricks_x = out.atlas_bricks_y = 0;
        return out;
    }
    const int aw = out.atlas_width();
    out.atlas.assign(std::size_t(aw) * std::size_t(out.atlas_height()) * 4, 0);
    for (int k = 0; k < n; ++k) {
        const int bx = k % out.atlas_bricks_x, by = k / out.atlas_bricks_x;
        for (int y = 0; y < brick_texels; ++y)
            std::copy_n(&bricks[std::size_t(k)][std::size_t(y * brick_texels * 4)], brick_texels * 4,
                        &out.atlas[(std::size_t(by * brick_texels + y) * std::size_t(aw) + std::size_t(bx * brick_texels)) * 4]);
    }
    out.indirection.assign(cell_brick.size() * 4, 0);
    for (std::size_t c = 0; c < cell_brick.size(); ++c) {
        const int k = cell_brick[c];
        if (k < 0) {
            ++out.empty_cells;
            continue;
        }
        const int bx = k % out.atlas_bricks_x, by = k / out.atlas_bricks_x;
        out.indirection[c * 4 + 0] = std::uint8_t(bx & 0xFF);
        out.indirection[c * 4 + 1] = std::uint8_t(by & 0xFF);
        out.indirection[c * 4 + 2] = std::uint8_t(((bx >> 8) & 0xF) | (((by >> 8) & 0xF) << 4));
        out.indirection[c * 4 + 3] = std::uint8_t(cell_level[c] + 1);
    }
    return out;
}

int brick_level(const BrickAtlas& a, float x, float y, int layer) {
    const int cx = clampi(int(std::floor(x / float(brick_probes))), 0, a.cells_x - 1);
    const int cy = clampi(int(std::floor(y / float(brick_probes))), 0, a.cells_y - 1);
    const std::size_t row = std::size_t(layer) * std::size_t(a.cells_y) + std::size_t(cy);
    return int(a.indirection[(row * std::size_t(a.cells_x) + std::size_t(cx)) * 4 + 3]) - 1;
}

glm::vec3 sample_bricks(const BrickAtlas& a, float x, float y, int layer) {
    const int cx = clampi(int(std::floor(x / float(brick_probes))), 0, a.cells_x - 1);
    const int cy = clampi(int(std::floor(y / float(brick_probes))), 0, a.cells_y - 1);
    const std::size_t row = std::size_t(layer) * std::size_t(a.cells_y) + std::size_t(cy);
    const std::uint8_t* ind = &a.indirection[(row * std::size_t(a.cells_x) + std::size_t(cx)) * 4];
    if (ind[3] == 0) return glm::vec3(0.0f);
    const int level = ind[3] - 1, s = 1 << level, side = brick_probes * s;
    const int bx = ind[0] | ((ind[2] & 0xF) << 8), by = ind[1] | ((ind[2] >> 4) << 8);
    const glm::vec2 o(std::floor(x / float(side)) * float(side), std::floor(y / float(side)) * float(side));
    // Continuous probe index, then the brick texel (apron at 0): in [0.5, 4.5].
    const float tx = (x - o.x) / float(s) - 0.5f + 1.0f, ty = (y - o.y) / float(s) - 0.5f + 1.0f;
    const int x0 = clampi(int(std::floor(tx)), 0, brick_texels - 2), y0 = clampi(int(std::floor(ty)), 0, brick_texels - 2);
    const float fx = tx - float(x0), fy = ty - float(y0);
    auto at = [&](int i, int j) { return texel_normalised(a, bx * brick_texels + i, by * brick_texels + j); };
    // Bilinear on the stored RGBM values, then decode: what a hardware sampler gives.
    const glm::vec4 v = (at(x0, y0) * (1.0f - fx) + at(x0 + 1, y0) * fx) * (1.0f - fy) +
                        (at(x0, y0 + 1) * (1.0f - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
    return glm::vec3(v) * v.a * rgbm_range;
}

} // namespace lantern::gi
