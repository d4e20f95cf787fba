// Seed 003's radiosity on the reference (radiosity.hpp). Every rule here is mirrored by
// shaders/gi_jump_flood.comp.glsl, gi_radiosity_light.comp.glsl and gi_radiosity.comp.glsl.
#include "lantern/gi/radiosity.hpp"

#include "lantern/gi/blue_noise.hpp"
#include "reference_util.hpp"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lantern::gi {
namespace {

using ref_util::air_at;
using ref_util::for_each_row;
using ref_util::load4;
using ref_util::store4;

std::uint32_t jfa_at(const Texture& jfa, int x, int y) {
    const float* v = jfa.at(x, y);
    return v[0] < 0.0f ? jfa_none : jfa_pack(int(v[0]), int(v[1]));
}
void jfa_put(Texture& jfa, int x, int y, std::uint32_t v) {
    float* out = jfa.at(x, y);
    const glm::ivec2 c = jfa_unpack(v);
    out[0] = v == jfa_none ? -1.0f : float(c.x);
    out[1] = v == jfa_none ? -1.0f : float(c.y);
}

int steps_at(const Texture& steps, int x, int y) {
    return int(steps.at(x, y)[0]);
}

float max3(glm::vec3 v) {
    return std::max(v.r, std::max(v.g, v.b));
}

// The smallest t >= 0 with t * den >= num (num >= 0, den > 0): a float estimate corrected
// by integer products, so that every backend gets the same integer.
int ceil_div(int num, int den) {
    int t = int(float(num) / float(den));
    if (t * den < num) ++t;
    if (t > 0 && (t - 1) * den >= num) --t;
    return t;
}

// Along one axis: the step (1/256 texel) that takes position p (1/4096) out of cell c.
int exit_steps(int p, int c, int d) {
    if (d > 0) return ceil_div(((c + 1) * radiosity_position_unit - p) * radiosity_step_unit, d);
    if (d < 0) return ceil_div((p - c * radiosity_position_unit) * radiosity_step_unit + 1, -d);
    return 65535;
}

} // namespace

HeatGrid radiosity_grid(const FrameInputs& in) {
    return heat_grid(in.window, in.settings.radiosity.scale);
}

std::vector<int> jump_flood_offsets(glm::ivec2 size) {
    std::vector<int> offsets{1}; // 1+JFA+1: a first pass at offset 1 and a last one
    int k = 1;
    while (k * 2 < std::max(size.x, size.y)) k *= 2;
    for (; k >= 1; k /= 2) offsets.push_back(k);
    offsets.push_back(1);
    return offsets;
}

Tex jump_flood_result(const FrameInputs& in) {
    const HeatGrid g = radiosity_grid(in);
    // Pass 0 seeds jfa_a, pass i (1..offsets) writes jfa_a when i is even (rows/radiosity.cpp).
    return jump_flood_offsets({g.width, g.height}).size() % 2 == 0 ? Tex::jfa_a : Tex::jfa_b;
}

std::uint32_t distance_steps_of(std::uint32_t d2) {
    if (d2 > 65535u) return 65535u;
    const std::uint32_t v = d2 * 65536u;
    std::uint32_t s = std::uint32_t(std::sqrt(float(v)));
    if (s * s > v) --s;
    if (s < 65535u && (s + 1u) * (s + 1u) <= v) ++s;
    return std::min(s, 65535u);
}

Texture reference_jump_flood_seed(const FrameInputs& in) {
    const HeatGrid g = radiosity_grid(in);
    Texture jfa("jfa_a", TexFormat::rgba16f, g.width, g.height);
    for (int j = 0; j < g.height; ++j)
        for (int i = 0; i < g.width; ++i)
            jfa_put(jfa, i, j, air_at(in.walls, g.texel_center(i, j)) ? jfa_none : jfa_pack(i, j));
    return jfa;
}

Texture reference_jump_flood_pass(const Texture& jfa, int offset, const RefOptions& options) {
    Texture out(jfa.name, jfa.format, jfa.width, jfa.height);
    for_each_row(jfa.height, options, [&](int y) {
        for (int x = 0; x < jfa.width; ++x) {
            std::uint32_t best = jfa_none;
            int best_d2 = 0;
            // The seed's 3x3 neighbourhood at this offset; the first nearest wins.
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int sx = x + dx * offset, sy = y + dy * offset;
                    if (sx < 0 || sy < 0 || sx >= jfa.width || sy >= jfa.height) continue;
                    const std::uint32_t v = jfa_at(jfa, sx, sy);
                    if (v == jfa_none) continue;
                    const glm::ivec2 c = jfa_unpack(v);
                    const int d2 = (c.x - x) * (c.x - x) + (c.y - y) * (c.y - y);
                    if (best == jfa_none || d2 < best_d2) best = v, best_d2 = d2;
                }
            jfa_put(out, x, y, best);
        }
    });
    return out;
}

DistanceTextures reference_distance_field(const Texture& jfa, const RefOptions& options) {
    DistanceTextures d{Texture("distance_field", TexFormat::rgba16f, jfa.width, jfa.height),
                       Texture("distance_steps", TexFormat::r8, jfa.width, jfa.height)};
    for_each_row(jfa.height, options, [&](int y) {
        for (int x = 0; x < jfa.width; ++x) {
            const std::uint32_t v = jfa_at(jfa, x, y);
            glm::vec4 field(max_half, 0.0f, 0.0f, 0.0f);
            std::uint32_t steps = 65535u;
            if (v != jfa_none) {
                const glm::ivec2 c = jfa_unpack(v);
                const int dx = c.x - x, dy = c.y - y;
                const std::uint32_t d2 = std::uint32_t(dx * dx + dy * dy);
                const float len = std::sqrt(float(d2));
                field = d2 == 0 ? glm::vec4(0.0f)
                                : glm::vec4(len, float(dx) / len, float(dy) / len, 0.0f);
                steps = distance_steps_of(d2);
            }
            store4(d.field, x, y, field);
            d.steps.at(x, y)[0] = float(steps); // raw (internal: 32-bit words on the GPU)
        }
    });
    return d;
}

const std::vector<glm::ivec2>& radiosity_directions() {
    static const std::vector<glm::ivec2> table = [] {
        std::vector<glm::ivec2> t(4096);
        for (int a = 0; a < 4096; ++a) {
            const double angle = 2.0 * std::numbers::pi * double(a) / 4096.0;
            t[std::size_t(a)] = {int(std::lround(std::cos(angle) * 4096.0)),
                                 int(std::lround(std::sin(angle) * 4096.0))};
        }
        return t;
    }();
    return table;
}

int radiosity_frame_shift(scene::NoiseShift noise, int frame) {
    const double t = double(frame);
    double turns = 0.0;
    if (noise == scene::NoiseShift::rotate)
        turns = t / (4.0 * std::numbers::pi * std::numbers::pi); // t / 2pi rad
    if (noise == scene::NoiseShift::golden) turns = t * std::numbers::phi;
    return int(std::floor((turns - std::floor(turns)) * 4096.0)) & 4095;
}

RadiosityMarch radiosity_march_params(const FrameInputs& in, int history) {
    const scene::RadiositySettings& s = in.settings.radiosity;
    const HeatGrid g = radiosity_grid(in);
    RadiosityMarch m;
    m.rays = s.rays;
    m.steps = s.steps;
    m.epsilon_steps = std::max(1, int(std::floor(double(s.epsilon) * radiosity_step_unit)));
    m.noise = s.noise != scene::NoiseShift::off;
    m.shift = radiosity_frame_shift(s.noise, history);
    const auto origin = [&](float min) {
        const long texel = std::lround(double(min) * double(g.texels_per_unit));
        return int(((texel % blue_noise_size) + blue_noise_size) % blue_noise_size);
    };
    m.noise_origin = {origin(g.origin.x), origin(g.origin.y)};
    const int frames = std::min(history + 1, std::max(1, s.accumulate));
    m.accumulate_weight = history == 0 || frames <= 1 ? 1.0f : 1.0f / float(frames);
    m.own_weight = history > 0 ? s.feedback : 0.0f;
    return m;
}

Texture reference_radiosity_light(const FrameInputs& in, const Texture& emission,
                                  const Texture* previous, float feedback,
                                  const RefOptions& options) {
    const HeatGrid g = radiosity_grid(in);
    Texture light("radiosity_light", TexFormat::rgba16f, g.width, g.height);
    for_each_row(g.height, options, [&](int j) {
        for (int i = 0; i < g.width; ++i) {
            glm::vec3 value(0.0f);
            if (air_at(in.walls, g.texel_center(i, j))) {
                glm::vec3 sum(0.0f);
                int n = 0;
                for (int y = j * g.scale; y < std::min((j + 1) * g.scale, emission.height); ++y)
                    for (int x = i * g.scale; x < std::min((i + 1) * g.scale, emission.width);
                         ++x) {
                        sum += glm::vec3(load4(emission, x, y));
                        ++n;
                    }
                value = sum / float(std::max(n, 1));
                if (previous) value += glm::vec3(load4(*previous, i, j)) * feedback;
            }
            store4(light, i, j, glm::vec4(value, 1.0f));
        }
    });
    return light;
}

glm::vec3 radiosity_texel(const Texture& light, const Texture& steps, const Texture* previous,
                          const RadiosityMarch& m, int i, int j) {
    // The seed's early out: inside a wall, the texel keeps its light image.
    if (steps_at(steps, i, j) < m.epsilon_steps) return glm::vec3(load4(light, i, j));
    // The seed's own term: the texel's last light (its base texture holds the last frame).
    const glm::vec3 own = previous && m.own_weight > 0.0f
                              ? glm::vec3(load4(*previous, i, j)) * m.own_weight
                              : glm::vec3(0.0f);
    const std::vector<glm::ivec2>& dirs = radiosity_directions();
    const int w = light.width, h = light.height;
    int base = 0;
    if (m.noise) {
        const int nx = (i + m.noise_origin.x) & (blue_noise_size - 1),
                  ny = (j + m.noise_origin.y) & (blue_noise_size - 1);
        base = int(blue_noise_ranks()[std::size_t(ny * blue_noise_size + nx)]);
    }
    glm::vec3 sum = own;
    float brightness = max3(own);
    for (int k = 0; k < m.rays; ++k) {
        const glm::ivec2 d = dirs[std::size_t((base + m.shift + k * 4096 / m.rays) & 4095)];
        glm::ivec2 p(i * radiosity_position_unit + radiosity_position_unit / 2,
                     j * radiosity_position_unit + radiosity_position_unit / 2);
        glm::ivec2 c(i, j);
        int dq = steps_at(steps, i, j);
        glm::vec3 hit(0.0f);
        for (int s = 0; s < m.steps; ++s) {
            const int t =
                std::min(std::max(dq - radiosity_step_margin,
                                  std::min(exit_steps(p.x, c.x, d.x), exit_steps(p.y, c.y, d.y))),
                         65535);
            p.x += (d.x * t) >> 8;
            p.y += (d.y * t) >> 8;
            c = {p.x >> 12, p.y >> 12};
            if (c.x < 0 || c.y < 0 || c.x >= w || c.y >= h) break; // left the window: no light
            dq = steps_at(steps, c.x, c.y);
            if (dq < m.epsilon_steps) {
                // The seed's hit: the surface's colour and the colour one texel back in empty
                // space.
                const int bx = std::clamp((p.x - d.x) >> 12, 0, w - 1),
                          by = std::clamp((p.y - d.y) >> 12, 0, h - 1);
                hit = glm::max(glm::vec3(load4(light, c.x, c.y)), glm::vec3(load4(light, bx, by)));
                break;
            }
        }
        sum += hit;
        brightness += max3(hit);
    }
    // The seed's normalisation: light / brightness x brightness / rays (no light: none).
    return brightness > 0.0f ? (sum / brightness) * (brightness / float(m.rays)) : glm::vec3(0.0f);
}

void reference_radiosity_march(const Texture& light, const Texture& steps, const RadiosityMarch& m,
                               Texture& radiosity, const RefOptions& options) {
    for_each_row(light.height, options, [&](int j) {
        for (int i = 0; i < light.width; ++i) {
            glm::vec3 value = radiosity_texel(light, steps, &radiosity, m, i, j);
            if (m.accumulate_weight < 1.0f) {
                const glm::vec3 previous(load4(radiosity, i, j));
                value = previous + (value - previous) * m.accumulate_weight;
            }
            store4(radiosity, i, j, glm::vec4(value, 1.0f));
        }
    });
}

} // namespace lantern::gi
