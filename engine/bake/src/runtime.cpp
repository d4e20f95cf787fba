// Baked light at run time (bake.hpp, "At run time"): chunk bakes into the frame's brick atlas.
#include "lantern/bake/bake.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/cli.hpp"
#include "lantern/core/hash.hpp"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <string>

#include <glm/common.hpp>

namespace lantern::bake {
namespace {
// A default for a help text: the shortest %g form ("0.01", "4").
std::string text_of(float v) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", double(v));
    return buffer;
}
} // namespace

void add_settings_options(cli::Parser& p, BakeSettings& s, const std::string& prefix, const BakeSettings& d) {
    p.integer(prefix + "resolution", "R", "baked texels per tile (default " + std::to_string(d.resolution) + ")", s.resolution, 1, 16);
    p.integer(prefix + "margin", "M",
              "tiles around a chunk whose walls reflect light into it (default " + std::to_string(d.margin) + ")", s.margin, 0, 64);
    p.integer(prefix + "rays", "N", "gather rays per ground texel and light probe (default " + std::to_string(d.rays) + ")",
              s.rays, 1, 1024);
    p.integer(prefix + "face-rays", "N", "gather rays per wall-face texel (default " + std::to_string(d.face_rays) + ")",
              s.face_rays, 1, 1024);
    p.custom(prefix + "solver", "gather|seed002",
             "how the bounce light is solved: the converged gather (default) or seed 002's one-bounce bake with "
             "its falloff and ambient fill",
             [&s](std::string_view v) -> std::optional<std::string> {
                 if (v == "gather") s.solver = BakeSolver::gather;
                 else if (v == "seed002") s.solver = BakeSolver::seed002;
                 else return "must be gather or seed002, got '" + std::string(v.substr(0, 40)) + "'";
                 return std::nullopt;
             });
    p.number(prefix + "falloff", "TILES",
             "seed002: a hit at this distance counts half (default " + text_of(d.falloff) + ")", s.falloff,
             1.0f / 64.0f, 4096.0f);
    p.number(prefix + "ambient", "E", "seed002: ambient fill every hit wall receives (default " + text_of(d.ambient) + ")", s.ambient, 0.0f,
             1000.0f);
    p.flag(prefix + "non-directional", "probes keep the light's amount, not its direction (seed 004's non-directional bake)",
           [&s] { s.directional = false; });
    p.number(prefix + "eps", "E", "at run time: the bricks' colour range (seed 002's eps; default " + text_of(d.eps) + ")", s.eps, 0.0f, 1000.0f);
    p.integer(prefix + "max-level", "L", "at run time: the coarsest brick level, 0-3 (seed 002's maxLevel; default " +
                  std::to_string(d.max_level) + ")",
              s.max_level, 0, 3);
}

namespace {
constexpr const char* setting_options[] = {"resolution", "margin",          "rays", "face-rays", "solver",
                                           "falloff",    "ambient", "non-directional", "eps",  "max-level"};
}

GivenSettings given_settings(const cli::Parser& p, const BakeSettings& values, const std::string& prefix) {
    GivenSettings g;
    g.values = values;
    for (const char* option : setting_options)
        if (p.given(prefix + option)) g.given.emplace_back(option);
    return g;
}

BakeSettings GivenSettings::over(const BakeSettings& world) const {
    BakeSettings s = world;
    auto take = [&](const char* option, auto member) {
        if (std::find(given.begin(), given.end(), option) != given.end()) s.*member = values.*member;
    };
    take("resolution", &BakeSettings::resolution);
    take("margin", &BakeSettings::margin);
    take("rays", &BakeSettings::rays);
    take("face-rays", &BakeSettings::face_rays);
    take("solver", &BakeSettings::solver);
    take("falloff", &BakeSettings::falloff);
    take("ambient", &BakeSettings::ambient);
    take("non-directional", &BakeSettings::directional);
    take("eps", &BakeSettings::eps);
    take("max-level", &BakeSettings::max_level);
    return s;
}

std::shared_ptr<const gi::BakedLight> runtime_light(std::span<const ChunkBake* const> chunks, const gi::WallView& walls,
                                                    float eps, int max_level) {
    if (chunks.empty()) return nullptr;
    const int res = chunks[0]->resolution;
    glm::ivec2 lo(INT_MAX), hi(INT_MIN);
    Hasher key;
    key.add(res).add(eps);
    if (max_level != gi::brick_levels - 1) key.add(max_level);
    for (const ChunkBake* c : chunks) {
        LANTERN_ASSERT(c->resolution == res, "runtime_light: chunks of different resolutions");
        lo = glm::min(lo, glm::ivec2(c->id.x, c->id.z));
        hi = glm::max(hi, glm::ivec2(c->id.x, c->id.z));
        key.add(c->id.x).add(c->id.z).add(c->key);
    }
    const int side = chunk_tiles * res;
    const glm::ivec2 chunks_wide = hi - lo + 1;
    const int width = chunks_wide.x * side, height = chunks_wide.y * side;
    std::array<gi::Field, gi::baked_layers> layers;
    for (gi::Field& f : layers) f = gi::Field(width, height);
    static constexpr glm::ivec2 across[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const ChunkBake* c : chunks) {
        const glm::ivec2 at = (glm::ivec2(c->id.x, c->id.z) - lo) * side;
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                const std::size_t src = std::size_t(y) * std::size_t(side) + std::size_t(x);
                const std::size_t dst = std::size_t(at.y + y) * std::size_t(width) + std::size_t(at.x + x);
                const glm::ivec2 tile(c->id.x * chunk_tiles + x / res, c->id.z * chunk_tiles + y / res);
                const bool wall = walls.is_wall(tile.x, tile.y);
                // Which texels hold light: open ground, and the faces a wall tile shows.
                layers[0].air[dst] = wall ? 0 : 1;
                for (int f = 0; f < 4; ++f)
                    layers[std::size_t(1 + f)].air[dst] =
                        wall && !walls.is_wall(tile.x + across[f].x, tile.y + across[f].y) ? 1 : 0;
                if (c->empty) continue; // no baked light reaches it: zero
                for (int k = 0; k < 3; ++k) {
                    layers[0].rgb[dst * 3 + std::size_t(k)] = c->ground[src * 3 + std::size_t(k)];
                    for (int f = 0; f < 4; ++f)
                        layers[std::size_t(1 + f)].rgb[dst * 3 + std::size_t(k)] = c->faces[std::size_t(f)][src * 3 + std::size_t(k)];
                }
            }
    }
    return std::make_shared<const gi::BakedLight>(
        gi::make_baked_light(lo * chunk_tiles, res, layers, eps, key.value(), max_level));
}

scene::Scene live_scene(const scene::Scene& s) {
    scene::Scene out = s;
    auto baked = [](const auto& l) { return l.mode == scene::LightMode::baked; };
    std::erase_if(out.point_lights, baked);
    std::erase_if(out.emissive_lights, baked);
    std::erase_if(out.directional_lights, baked);
    for (scene::Material& m : out.materials) // the bake holds the glow of `baked` materials
        if (m.emission_gi == scene::EmissionGi::baked) m.emission = glm::vec3(0.0f);
    return out;
}

Result<std::shared_ptr<const gi::BakedLight>> load_world_light(const scene::Scene& scene, const std::string& dir,
                                                               const BakeSettings& settings, const BakeOptions& options) {
    Result<BakeReport> report = bake_world(scene, dir, settings, options);
    if (!report) return report.error();
    std::vector<ChunkBake> bakes;
    for (ChunkId c : shard_of(scene_chunks(scene), options.shard, options.shards)) {
        std::string why;
        std::optional<ChunkBake> b = load_chunk(dir, c, chunk_key(scene, c, settings), &why);
        if (!b) return make_error(dir + "/" + chunk_file_name(c) + ": " + why + " right after the bake");
        bakes.push_back(std::move(*b));
    }
    std::vector<const ChunkBake*> pointers;
    for (const ChunkBake& b : bakes) pointers.push_back(&b);
    return runtime_light(pointers, gi::WallView::of(scene.walls), settings.eps, settings.max_level);
}

} // namespace lantern::bake
