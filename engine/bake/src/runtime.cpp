// Baked light at run time (bake.hpp, "At run time"): chunk bakes into the frame's brick atlas.
#include "lantern/bake/bake.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/cli.hpp"
#include "lantern/core/hash.hpp"

#include <algorithm>
#include <charconv>
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
    p.custom(prefix + "sun-keys", "K",
             "bake the mixed sun's bounce at K times of the day's path (2-32; 0, the default: at its own direction), "
             "blended at run time as the sun moves (seed 004's precomputed GI for the moving sun)",
             [&s](std::string_view v) -> std::optional<std::string> {
                 int k = -1;
                 const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), k);
                 if (ec != std::errc{} || ptr != v.data() + v.size() || k == 1 || k < 0 || k > 32)
                     return "must be 0 or an integer in [2, 32], got '" + std::string(v.substr(0, 40)) + "'";
                 s.sun_keys = k;
                 return std::nullopt;
             });
    p.number(prefix + "eps", "E", "at run time: the bricks' colour range (seed 002's eps; default " + text_of(d.eps) + ")", s.eps, 0.0f, 1000.0f);
    p.integer(prefix + "max-level", "L", "at run time: the coarsest brick level, 0-3 (seed 002's maxLevel; default " +
                  std::to_string(d.max_level) + ")",
              s.max_level, 0, 3);
    p.custom(prefix + "density", "X0,Z0,X1,Z1,R",
             "the chunks X0..X1, Z0..Z1 (inclusive) bake at R texels a tile (seed 004's texel density per chunk); "
             "repeatable, the last region holding a chunk wins; replaces the world's \"density\"",
             [&s](std::string_view v) -> std::optional<std::string> {
                 scene::BakeDensity region;
                 int* fields[5] = {&region.min.x, &region.min.y, &region.max.x, &region.max.y, &region.resolution};
                 std::size_t at = 0;
                 for (int k = 0; k < 5; ++k) {
                     const std::size_t end = k < 4 ? v.find(',', at) : v.size();
                     if (end == std::string_view::npos) return "must be five integers X0,Z0,X1,Z1,R";
                     const std::string_view part = v.substr(at, end - at);
                     const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), *fields[k]);
                     if (ec != std::errc{} || ptr != part.data() + part.size() || part.empty())
                         return "must be five integers X0,Z0,X1,Z1,R, got '" + std::string(v.substr(0, 60)) + "'";
                     at = end + 1;
                 }
                 constexpr int limit = (1 << 24) / chunk_tiles;
                 for (int k = 0; k < 4; ++k)
                     if (*fields[k] < -limit || *fields[k] > limit)
                         return "chunk coordinates must be within [" + std::to_string(-limit) + ", " + std::to_string(limit) + "]";
                 if (region.resolution < 1 || region.resolution > 16) return "R must be in [1, 16], got " + std::to_string(region.resolution);
                 if (region.max.x < region.min.x || region.max.y < region.min.y) return "X1,Z1 must not be below X0,Z0";
                 if (s.density.size() >= std::size_t(scene::max_bake_density_regions))
                     return "at most " + std::to_string(scene::max_bake_density_regions) + " regions";
                 s.density.push_back(region);
                 return std::nullopt;
             },
             /*repeatable=*/true);
}

namespace {
constexpr const char* setting_options[] = {"resolution", "margin",          "rays",     "face-rays", "solver",
                                           "falloff",    "ambient",         "sun-keys", "eps",       "max-level",
                                           "non-directional", "density"};
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
    take("sun-keys", &BakeSettings::sun_keys);
    take("eps", &BakeSettings::eps);
    take("max-level", &BakeSettings::max_level);
    take("density", &BakeSettings::density);
    return s;
}

namespace {

// A part of a chunk's light, as the run time's layers hold them: 0 the steady light, 1 the
// pulsing glow's, 2 + k sun key k's.
constexpr int steady_part = 0, pulsing_part = 1, first_sun_key_part = 2;

bool has_part(const ChunkBake& c, int part) {
    if (c.empty) return false;
    if (part == steady_part) return true;
    if (part == pulsing_part) return c.pulses();
    return std::size_t(part - first_sun_key_part) < c.sun_keys.size();
}

// Which texels of layer `layer` (of any part) hold light (open ground; the faces a wall tile
// shows).
bool holds_light(const gi::WallView& walls, int layer, glm::ivec2 tile) {
    static constexpr glm::ivec2 across[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    layer %= gi::baked_layers;
    const bool wall = walls.is_wall(tile.x, tile.y);
    if (layer == 0) return !wall;
    const glm::ivec2 a = across[layer - 1];
    return wall && !walls.is_wall(tile.x + a.x, tile.y + a.y);
}

// A chunk's texel (x, y) (of `side` a row) of part `part`'s layer `layer` (0: ground, 1 + f:
// face f; the chunk must have the part).
const float* texel_of(const ChunkBake& c, int part, int layer, int x, int y) {
    const std::size_t i = (std::size_t(y) * std::size_t(c.side()) + std::size_t(x)) * 3;
    if (part == steady_part) return (layer == 0 ? c.ground : c.faces[std::size_t(layer - 1)]).data() + i;
    const LightPart& p = part == pulsing_part ? c.pulse : c.sun_keys[std::size_t(part - first_sun_key_part)];
    const std::vector<float>& v = layer == 0 ? p.ground : p.faces[std::size_t(layer - 1)];
    return v.data() + i;
}

// Chunk `c`'s light at the centre of texel (x, y) of a grid of `res` texels a tile over it,
// when c was baked at a coarser resolution: bilinear between c's four texels around that
// point (clamped at c's border), over those that hold light in the layer; the nearest texel
// when none of them does.
glm::vec3 resample(const ChunkBake& c, const gi::WallView& walls, int part, int layer, int res, int x, int y) {
    const int r = c.resolution, side = c.side();
    const glm::vec2 g = (glm::vec2(float(x), float(y)) + 0.5f) * (float(r) / float(res)) - 0.5f;
    const glm::ivec2 i0(int(std::floor(g.x)), int(std::floor(g.y)));
    const glm::vec2 f = g - glm::vec2(i0);
    glm::vec3 sum(0.0f);
    float weight = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const int dx = k & 1, dy = k >> 1;
        const int sx = std::clamp(i0.x + dx, 0, side - 1), sy = std::clamp(i0.y + dy, 0, side - 1);
        const glm::ivec2 tile(c.id.x * chunk_tiles + sx / r, c.id.z * chunk_tiles + sy / r);
        if (!holds_light(walls, layer, tile)) continue;
        const float w = (dx ? f.x : 1.0f - f.x) * (dy ? f.y : 1.0f - f.y);
        const float* t = texel_of(c, part, layer, sx, sy);
        sum += w * glm::vec3(t[0], t[1], t[2]);
        weight += w;
    }
    if (weight > 0.0f) return sum / weight;
    const int nx = std::clamp(int(std::floor(g.x + 0.5f)), 0, side - 1), ny = std::clamp(int(std::floor(g.y + 0.5f)), 0, side - 1);
    const float* t = texel_of(c, part, layer, nx, ny);
    return {t[0], t[1], t[2]};
}

} // namespace

std::shared_ptr<const gi::BakedLight> runtime_light(std::span<const ChunkBake* const> chunks, const gi::WallView& walls,
                                                    float eps, int max_level, std::string* why) {
    if (chunks.empty()) return nullptr;
    int res = 1; // the finest chunk's (texel density per chunk)
    for (const ChunkBake* c : chunks) res = std::max(res, c->resolution);
    glm::ivec2 lo(INT_MAX), hi(INT_MIN);
    Hasher key;
    key.add(res).add(eps);
    if (max_level != gi::brick_levels - 1) key.add(max_level);
    for (const ChunkBake* c : chunks) {
        lo = glm::min(lo, glm::ivec2(c->id.x, c->id.z));
        hi = glm::max(hi, glm::ivec2(c->id.x, c->id.z));
        key.add(c->id.x).add(c->id.z).add(c->key);
    }
    const int side = chunk_tiles * res;
    const glm::ivec2 chunks_wide = hi - lo + 1;
    const int width = chunks_wide.x * side, height = chunks_wide.y * side;
    // With any chunk's pulsing part, five more layers hold the pulsing glow's light; then five
    // for each sun key (the moving sun), as many as the chunks have.
    const bool pulsing = std::any_of(chunks.begin(), chunks.end(), [](const ChunkBake* c) { return !c->empty && c->pulses(); });
    std::size_t sun_keys = 0;
    for (const ChunkBake* c : chunks)
        if (!c->empty) sun_keys = std::max(sun_keys, c->sun_keys.size());
    std::vector<int> parts = {steady_part};
    if (pulsing) parts.push_back(pulsing_part);
    for (std::size_t k = 0; k < sun_keys; ++k) parts.push_back(first_sun_key_part + int(k));
    std::vector<gi::Field> layers(parts.size() * std::size_t(gi::baked_layers));
    for (gi::Field& f : layers) f = gi::Field(width, height);
    for (const ChunkBake* c : chunks) {
        const glm::ivec2 at = (glm::ivec2(c->id.x, c->id.z) - lo) * side;
        const bool coarser = c->resolution != res;
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                const std::size_t dst = std::size_t(at.y + y) * std::size_t(width) + std::size_t(at.x + x);
                const glm::ivec2 tile(c->id.x * chunk_tiles + x / res, c->id.z * chunk_tiles + y / res);
                for (int index = 0; index < int(layers.size()); ++index) {
                    gi::Field& field = layers[std::size_t(index)];
                    const int part = parts[std::size_t(index / gi::baked_layers)], layer = index % gi::baked_layers;
                    // Every part's layers hold light where the steady part's do.
                    field.air[dst] = index < gi::baked_layers ? (holds_light(walls, layer, tile) ? 1 : 0)
                                                              : layers[std::size_t(layer)].air[dst];
                    if (!has_part(*c, part)) continue; // no such light reaches it: zero
                    glm::vec3 v;
                    if (coarser) {
                        v = resample(*c, walls, part, layer, res, x, y);
                    } else {
                        const float* t = texel_of(*c, part, layer, x, y);
                        v = {t[0], t[1], t[2]};
                    }
                    for (int k = 0; k < 3; ++k) field.rgb[dst * 3 + std::size_t(k)] = v[k];
                }
            }
    }
    // A chunk baked at res / 2^L holds no detail below brick level L: its cells stop there.
    const int cells_x = (width + gi::brick_probes - 1) / gi::brick_probes, cells_y = (height + gi::brick_probes - 1) / gi::brick_probes;
    std::vector<std::uint8_t> finest(std::size_t(cells_x) * std::size_t(cells_y), 0);
    bool coarser = false;
    for (const ChunkBake* c : chunks) {
        int level = 0;
        while (level + 1 < gi::brick_levels && c->resolution << (level + 1) <= res && res % (c->resolution << (level + 1)) == 0) ++level;
        if (level == 0) continue;
        coarser = true;
        const int cells = side / gi::brick_probes;
        const glm::ivec2 at = (glm::ivec2(c->id.x, c->id.z) - lo) * cells;
        for (int y = 0; y < cells; ++y)
            for (int x = 0; x < cells; ++x) finest[std::size_t(at.y + y) * std::size_t(cells_x) + std::size_t(at.x + x)] = std::uint8_t(level);
    }
    auto light = std::make_shared<const gi::BakedLight>(gi::make_baked_light(lo * chunk_tiles, res, layers, eps, key.value(), max_level,
                                                                             coarser ? std::span<const std::uint8_t>(finest)
                                                                                     : std::span<const std::uint8_t>(),
                                                                             int(sun_keys)));
    if (light->bricks.too_many > 0) {
        if (why)
            *why = "the baked light of " + std::to_string(chunks.size()) + " chunks (" + std::to_string(width) + " x " +
                   std::to_string(height) + " texels a layer) needs " + std::to_string(light->bricks.too_many) +
                   " bricks, more than one atlas holds (" + std::to_string(gi::baked_bricks_per_row * gi::brick_max_atlas) +
                   "): read a smaller part of the world, or coarsen it (eps, density)";
        return nullptr;
    }
    return light;
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
    std::string why;
    auto light = runtime_light(pointers, gi::WallView::of(scene.walls), settings.eps, settings.max_level, &why);
    if (!light && !why.empty()) return make_error(dir + ": " + why);
    return light;
}

} // namespace lantern::bake
