// Reference of the indirect half of the pipeline. See reference_indirect.hpp.
#include "lantern/gi/reference_indirect.hpp"

#include "reference_util.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::gi {
namespace {

using ref_util::air_at;
using ref_util::for_each_row;
using ref_util::load4;
using ref_util::store4;

constexpr glm::vec3 luma(0.299f, 0.587f, 0.114f);
constexpr float soft_cap = 2.0f;

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }

// The eight neighbour directions with their distance weights (diagonals 1/sqrt(2)).
struct Direction {
    glm::vec2 offset;
    float weight;
};
constexpr Direction directions[8] = {
    {{-1, -1}, 0.70710678f}, {{0, -1}, 1.0f}, {{1, -1}, 0.70710678f}, {{-1, 0}, 1.0f},
    {{1, 0}, 1.0f},          {{-1, 1}, 0.70710678f}, {{0, 1}, 1.0f}, {{1, 1}, 0.70710678f},
};

} // namespace

HeatGrid heat_grid(const GiWindow& w, scene::HeatScale scale) {
    HeatGrid g;
    g.scale = int(scale);
    g.width = (w.width + g.scale - 1) / g.scale;
    g.height = (w.height + g.scale - 1) / g.scale;
    g.texels_per_unit = float(w.resolution) / float(g.scale);
    g.origin = {w.view.min_x, w.view.min_z};
    return g;
}

std::vector<HeatTap> heat_taps(float d) {
    std::vector<HeatTap> taps;
    auto add_ring = [&](float distance, float share) {
        for (const Direction& dir : directions) {
            const glm::vec2 offset = dir.offset * distance;
            // The tapped texel is floor(i + 0.5 + offset): does the step skip a texel?
            const glm::vec2 k = glm::floor(offset + 0.5f);
            taps.push_back({offset, dir.weight * share, std::abs(k.x) > 1.0f || std::abs(k.y) > 1.0f});
        }
    };
    if (heat_tap_rings(d)) {
        add_ring(1.5f, 0.3f);     // near: fills holes between sparse taps
        add_ring(d * 0.5f, 0.3f); // mid: bridges near and far
        add_ring(d, 0.4f);        // far: long-range transport
    } else {
        add_ring(d, 1.0f);
    }
    return taps;
}

Texture reference_emission(const FrameInputs& in, const Texture& direct, const RefOptions& options) {
    Texture out("emission", TexFormat::rgba16f, direct.width, direct.height);
    const float strength = in.settings.emission_strength;
    for_each_row(direct.height, options, [&](int y) {
        for (int x = 0; x < direct.width; ++x) {
            const glm::vec4 d = load4(direct, x, y);
            const float max_channel = std::max(d.r, std::max(d.g, d.b));
            const float curve = 1.0f - std::exp(-max_channel * 2.0f);
            const float scale = strength * curve / (max_channel + 0.001f);
            glm::vec4 e = d * scale;
            const float lum = glm::dot(glm::vec3(e), luma);
            const glm::vec3 boosted = glm::max(glm::vec3(lum) + (glm::vec3(e) - lum) * 1.2f, glm::vec3(0.0f));
            store4(out, x, y, glm::vec4(boosted, e.a));
        }
    });
    return out;
}

namespace {

// Heat seed at the heat grid: box average of the emission (rgb) and of the direct
// visibility max(R, G) (stored in alpha, which the rounds carry along untouched).
Texture heat_seed(const HeatGrid& g, const Texture& emission, const Texture& shadow, const RefOptions& options) {
    Texture seed("heat", TexFormat::rgba16f, g.width, g.height);
    for_each_row(g.height, options, [&](int j) {
        for (int i = 0; i < g.width; ++i) {
            glm::vec3 sum(0.0f);
            float visibility = 0.0f;
            int n = 0;
            for (int y = j * g.scale; y < std::min((j + 1) * g.scale, emission.height); ++y)
                for (int x = i * g.scale; x < std::min((i + 1) * g.scale, emission.width); ++x) {
                    sum += glm::vec3(load4(emission, x, y));
                    const float* s = shadow.at(x, y);
                    visibility += std::max(s[0], s[1]);
                    ++n;
                }
            store4(seed, i, j, glm::vec4(sum / float(n), visibility / float(n)));
        }
    });
    return seed;
}

glm::vec4 heat_texel(const FrameInputs& in, const HeatGrid& g, const std::vector<HeatTap>& taps, const Texture& heat,
                     int i, int j) {
    const scene::GiSettings& s = in.settings;
    const glm::vec4 center = load4(heat, i, j);
    const glm::vec2 center_pos = g.texel_center(i, j);
    if (!air_at(in.walls, center_pos)) return center; // no conduction in walls
    const float in_shadow = 1.0f - center.a;
    const float rate = s.diffusion_rate;
    const float segment_radius = s.diffusion_distance * 2.0f + 2.0f;
    glm::vec3 accum(0.0f), wsum(0.0f);
    for (const HeatTap& tap : taps) {
        const int ti = std::clamp(int(std::floor(float(i) + 0.5f + tap.offset.x)), 0, g.width - 1);
        const int tj = std::clamp(int(std::floor(float(j) + 0.5f + tap.offset.y)), 0, g.height - 1);
        const glm::vec2 tap_pos = g.texel_center(ti, tj);
        if (!air_at(in.walls, tap_pos)) continue;
        if (s.segment_check && tap.segment_check && shadow_dda(in.walls, center_pos, tap_pos, segment_radius) == 0.0f)
            continue; // the tap would jump through a wall
        const float weight = tap.weight * rate;
        const glm::vec3 n = glm::vec3(load4(heat, ti, tj));
        const glm::vec3 w = s.per_channel ? weight * glm::clamp(n + 0.1f, 0.0f, 1.0f) : glm::vec3(weight);
        accum += n * w;
        wsum += w;
    }
    accum /= glm::max(wsum, glm::vec3(1e-4f));
    const float blend = glm::mix(0.5f, 0.8f, in_shadow) * rate;
    glm::vec3 next = glm::mix(glm::vec3(center), accum, blend);
    const float darkness = 1.0f - saturate(glm::dot(glm::vec3(center), luma));
    next *= 1.0f + s.range_boost * darkness * in_shadow;
    next *= s.intensity_multiplier;
    const float max_channel = std::max(next.r, std::max(next.g, next.b));
    if (max_channel > soft_cap) next *= soft_cap / max_channel;
    return glm::vec4(next, center.a);
}

} // namespace

// Full-resolution indirect light from the heat grid: copy at scale 1, otherwise bilinear
// over the conductive heat texels around the texel centre (nearest when none conducts).
Texture reference_upsample(const FrameInputs& in, const HeatGrid& g, const Texture& heat, const RefOptions& options) {
    const GiWindow& w = in.window;
    Texture out("indirect", TexFormat::rgba16f, w.width, w.height);
    for_each_row(w.height, options, [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            glm::vec3 value;
            if (g.scale == 1) {
                value = glm::vec3(load4(heat, x, y));
            } else {
                const glm::vec2 p = w.texel_center(x, y);
                const glm::vec2 u = (p - g.origin) * g.texels_per_unit - 0.5f;
                const glm::ivec2 i0(int(std::floor(u.x)), int(std::floor(u.y)));
                const glm::vec2 f = u - glm::vec2(i0);
                glm::vec3 sum(0.0f);
                float wsum = 0.0f;
                for (int dy = 0; dy <= 1; ++dy)
                    for (int dx = 0; dx <= 1; ++dx) {
                        const int hi = std::clamp(i0.x + dx, 0, g.width - 1), hj = std::clamp(i0.y + dy, 0, g.height - 1);
                        if (!air_at(in.walls, g.texel_center(hi, hj))) continue;
                        const float wt = (dx ? f.x : 1.0f - f.x) * (dy ? f.y : 1.0f - f.y);
                        sum += glm::vec3(load4(heat, hi, hj)) * wt;
                        wsum += wt;
                    }
                if (wsum > 0.0f) {
                    value = sum / wsum;
                } else {
                    const int ni = std::clamp(int(std::floor(u.x + 0.5f)), 0, g.width - 1);
                    const int nj = std::clamp(int(std::floor(u.y + 0.5f)), 0, g.height - 1);
                    value = glm::vec3(load4(heat, ni, nj));
                }
            }
            store4(out, x, y, glm::vec4(value, 1.0f));
        }
    });
    return out;
}

Texture reference_heat(const FrameInputs& in, const Texture& emission, const Texture& shadow, const RefOptions& options,
                       int rounds_override) {
    Texture heat = reference_heat_seed(in, emission, shadow, options);
    const int rounds = rounds_override >= 0 ? rounds_override : in.settings.heat_rounds;
    for (int r = 0; r < rounds; ++r) heat = reference_heat_round(in, heat, options);
    return reference_heat_upsample(in, heat, options);
}

Texture reference_heat_seed(const FrameInputs& in, const Texture& emission, const Texture& shadow,
                            const RefOptions& options) {
    return heat_seed(heat_grid(in.window, in.settings.heat_scale), emission, shadow, options);
}

Texture reference_heat_round(const FrameInputs& in, const Texture& heat, const RefOptions& options) {
    const HeatGrid g = heat_grid(in.window, in.settings.heat_scale);
    const auto taps = heat_taps(in.settings.diffusion_distance * g.texels_per_unit);
    Texture out(heat.name, TexFormat::rgba16f, g.width, g.height);
    for_each_row(g.height, options, [&](int j) {
        for (int i = 0; i < g.width; ++i) store4(out, i, j, heat_texel(in, g, taps, heat, i, j));
    });
    return out;
}

Texture reference_heat_upsample(const FrameInputs& in, const Texture& heat, const RefOptions& options) {
    return reference_upsample(in, heat_grid(in.window, in.settings.heat_scale), heat, options);
}

Texture reference_blur(const FrameInputs& in, const Texture& indirect, const Texture& conduction, const RefOptions& options) {
    static constexpr float kernel[5] = {0.13533528f, 0.60653066f, 1.0f, 0.60653066f, 0.13533528f};
    const GiWindow& w = in.window;
    auto conductive = [&](int x, int y) { return *conduction.at(x, y) > 0.5f; };
    auto pass = [&](const Texture& src, glm::ivec2 axis) {
        Texture dst(indirect.name, TexFormat::rgba16f, w.width, w.height);
        for_each_row(w.height, options, [&](int y) {
            for (int x = 0; x < w.width; ++x) {
                const bool center_air = conductive(x, y);
                glm::vec3 sum(0.0f);
                float wsum = 0.0f;
                for (int k = -2; k <= 2; ++k) {
                    const int sx = x + axis.x * k, sy = y + axis.y * k;
                    if (sx < 0 || sy < 0 || sx >= w.width || sy >= w.height) continue;
                    if (conductive(sx, sy) != center_air) continue; // never across a boundary
                    sum += glm::vec3(load4(src, sx, sy)) * kernel[k + 2];
                    wsum += kernel[k + 2];
                }
                store4(dst, x, y, glm::vec4(sum / wsum, load4(src, x, y).a)); // wsum >= 1 (centre)
            }
        });
        return dst;
    };
    return pass(pass(indirect, {1, 0}), {0, 1});
}

std::array<Texture, 4> reference_wall_indirect(const FrameInputs& in, const Texture& indirect, const RefOptions& options) {
    const GiWindow& w = in.window;
    const std::uint32_t computed = computed_faces(in.settings);
    std::array<Texture, 4> faces;
    for (int f = 0; f < 4; ++f)
        if (computes_face(computed, f))
            faces[f] = Texture(std::string("wall_indirect_") + face_suffix[f], TexFormat::rgba16f, w.width, w.height);
    static constexpr glm::vec2 across[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for_each_row(w.height, options, [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            const glm::ivec2 cell(int(std::floor(p.x)), int(std::floor(p.y)));
            if (!in.walls.is_wall(cell.x, cell.y)) continue; // ground texels stay zero
            const glm::vec4 mask = wall_face_mask(in.walls, cell);
            for (int f = 0; f < 4; ++f) {
                if (!computes_face(computed, f)) continue;
                glm::vec3 value(0.0f);
                if (mask[f] > 0.0f) {
                    const glm::vec2 q = p + across[f];
                    const int sx = std::clamp(int(std::floor((q.x - w.view.min_x) * float(w.resolution))), 0, w.width - 1);
                    const int sy = std::clamp(int(std::floor((q.y - w.view.min_z) * float(w.resolution))), 0, w.height - 1);
                    value = glm::vec3(load4(indirect, sx, sy));
                }
                store4(faces[f], x, y, glm::vec4(value, 1.0f));
            }
        }
    });
    return faces;
}

} // namespace lantern::gi
