// Live light probes' reference (probes.hpp). gi_probes.comp.glsl mirrors every integer step
// here and sums the same floats in the same order.
#include "lantern/gi/probes.hpp"

#include "lantern/gi/radiosity.hpp"
#include "reference_util.hpp"

#include <algorithm>
#include <array>

namespace lantern::gi {
namespace {

using ref_util::load4;
using ref_util::store4;

int floor_div(int a, int b) { // b > 0
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

} // namespace

float probe_dtheta(int rays) { return 6.28318531f / float(rays); }

ProbeGrid probe_grid(const FrameInputs& in) {
    const GatherFrame f = gather_frame(in);
    constexpr int s = live_probe_spacing;
    ProbeGrid g;
    g.first_tile = {-floor_div(-f.origin_tile.x, s) * s, -floor_div(-f.origin_tile.y, s) * s}; // rounded up
    const glm::ivec2 last = f.origin_tile + f.tiles - 1;
    g.count = {std::max(0, floor_div(last.x - g.first_tile.x, s) + 1), std::max(0, floor_div(last.y - g.first_tile.y, s) + 1)};
    return g;
}

glm::ivec2 probe_texture_size(const FrameInputs& in) {
    const ProbeGrid g = probe_grid(in);
    return {std::max(1, live_probe_coefficients * g.count.x), std::max(1, g.count.y)};
}

Texture reference_probes(const FrameInputs& in, const FaceTextures& direct, const FaceTextures& indirect) {
    const GatherFrame f = gather_frame(in);
    const ProbeGrid g = probe_grid(in);
    const glm::ivec2 size = probe_texture_size(in);
    Texture out("probes", TexFormat::rgba16f, size.x, size.y);
    const int rays = in.settings.probe_rays;
    const std::vector<glm::ivec2>& dirs = radiosity_directions();
    auto face_light = [&](int face, glm::ivec2 t) {
        const std::size_t k = std::size_t(face);
        glm::vec3 e(0.0f);
        if (direct[k]) e = glm::vec3(load4(*direct[k], t.x, t.y));
        if (indirect[k]) e += glm::vec3(load4(*indirect[k], t.x, t.y));
        return e;
    };
    for (int j = 0; j < g.count.y; ++j)
        for (int i = 0; i < g.count.x; ++i) {
            const glm::ivec2 cell = g.first_tile - f.origin_tile + live_probe_spacing * glm::ivec2(i, j);
            std::array<glm::vec3, live_probe_coefficients> sum{};
            const glm::ivec2 tile = f.origin_tile + cell;
            const bool open = !in.walls.is_wall(tile.x, tile.y);
            if (open && rays > 0) {
                const glm::ivec2 p = cell * gather_unit + gather_unit / 2;
                const float dtheta = probe_dtheta(rays);
                for (int k = 0; k < rays; ++k) {
                    const glm::ivec2 d = dirs[std::size_t((k * 4096) / rays)];
                    const GatherHit hit = gather_trace(in, f, p, cell, d);
                    if (hit.face < 0) continue;
                    const glm::ivec2 hit_tile = f.origin_tile + (f.offset + hit.texel) / f.resolution;
                    const GpuMaterial m = material_of(in, in.walls.cell(hit_tile.x, hit_tile.y));
                    const glm::vec3 b = glm::vec3(m.albedo) * face_light(hit.face, hit.texel) + glm::vec3(m.emission);
                    const glm::vec3 ld = (b * 0.5f) * dtheta;
                    const float c = float(d.x) / 4096.0f, s = float(d.y) / 4096.0f;
                    const float c2 = c * c - s * s, s2 = 2.0f * c * s;
                    sum[0] += ld;
                    sum[1] += ld * c;
                    sum[2] += ld * s;
                    sum[3] += ld * c2;
                    sum[4] += ld * s2;
                }
            }
            store4(out, live_probe_coefficients * i, j, glm::vec4(sum[0], open ? 1.0f : 0.0f));
            for (int k = 1; k < live_probe_coefficients; ++k)
                store4(out, live_probe_coefficients * i + k, j, glm::vec4(sum[std::size_t(k)], 0.0f));
        }
    return out;
}

} // namespace lantern::gi
