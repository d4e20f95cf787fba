// Baked GI (seed 004's light maps, adapted to the grid; docs/baked.md): the light of a
// world's static lights, solved once per streaming chunk by the converged physical method
// (gi.method = gather, lantern/gi/gather.hpp) and kept in cache files keyed by everything
// the light depends on.
//
// What a chunk's bake holds, at BakeSettings::resolution texels a tile over its 32 x 32
// tiles (the game's streaming chunk):
//   ground       baked direct light (lights of mode `baked`) + baked indirect light (the
//                bounce light of `mixed` and `baked` lights and the glow of emissive
//                materials), fluence at texel centres, 0 in walls;
//   faces[f]     the same on wall face f (+X, -X, +Z, -Z) at wall texels, as Lantern's wall
//                textures hold it;
//   probes       light probes for things that move (probes.hpp): every 2 tiles, at the
//                centres of tiles (32 x + 2 i + 0.5, 32 z + 2 j + 0.5), the same light as
//                circular harmonics (the baked lights' direct light as point sources, the
//                bounce light by rays); none in walls.
//   pulse_*      the same three for the glow of pulsing materials alone (seed 004's pulsing
//                emission, scaled at run time), when any reaches the chunk.
//   sun_keys     with BakeSettings::sun_keys, the same three for each key: the mixed sun's
//                bounce at unit colour at that time of the day's path (seed 004's
//                precomputed GI for the moving sun; the steady part then leaves it out).
// Light from outside the chunk is included: lights in reach of it, and walls within
// BakeSettings::margin tiles that reflect light into it (the gather's margin).
//
// Determinism: a chunk's bake is a function of its inputs alone (the gather's rays are
// fixed in the world, no random numbers, one thread per chunk), so any split of the
// chunks over threads, processes or machines (bake_world's shards) gives the same bytes.
//
// Cache files: <dir>/chunk_<x>_<z>.lbk, written atomically; a file is used only when its
// size, format version and key all check out (load_chunk says why not otherwise).
//
// Threads: every function is reentrant; bake_world runs chunks on a JobSystem's workers
// and must be called from its main thread.
#pragma once

#include "lantern/bake/probes.hpp"
#include "lantern/core/result.hpp"
#include "lantern/gi/baked_light.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/scene/scene.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace lantern::jobs {
class JobSystem;
}
namespace lantern::cli {
class Parser;
}

namespace lantern::bake {

inline constexpr int chunk_tiles = 32;               // the game's streaming chunk
inline constexpr int probe_spacing = 2;              // tiles between light probes
inline constexpr int chunk_probes = chunk_tiles / probe_spacing; // probes a side
inline constexpr std::uint32_t bake_code_version = 2; // raise when the bake's output changes

// How the bounce light is solved (scene::BakeSolver).
//   gather   the converged physical method (gi.method = gather): every bounce, in the
//            transport model's units, so the bake agrees with engine/transport.
//   seed002  seed 002's own bake, stylised: one bounce, each ray's hit counted
//            1 / (1 + (d / falloff)^2) (d its length in tiles: near walls dominate, the
//            bounce gathers at seams), every hit face receiving `ambient` besides its direct
//            light (the seed's ambient fill), misses adding nothing. Same rays and units as
//            the gather (fluence: the seed's average over rays times pi), so with no falloff
//            and no ambient it is the gather's first bounce.
using BakeSolver = scene::BakeSolver;
const char* solver_name(BakeSolver solver);

// The bake's settings (scene::BakeSettings: a world keeps its own in its scene file).
using BakeSettings = scene::BakeSettings;
// Errors read "bake.<field>: <what is wrong>" (exit status 2).
Result<void> validate_settings(const BakeSettings& settings);
// The settings as command-line options `<prefix>resolution`, `<prefix>margin`,
// `<prefix>rays`, `<prefix>face-rays`, `<prefix>solver`, `<prefix>falloff`,
// `<prefix>ambient`, `<prefix>non-directional`, `<prefix>sun-keys`, `<prefix>eps`, `<prefix>max-level`
// (lantern-bake: "--", lantern-render and the game: "--bake-"), parsed into `settings`; the
// help names `defaults`' values as the defaults.
void add_settings_options(cli::Parser& parser, BakeSettings& settings, const std::string& prefix,
                          const BakeSettings& defaults = {});
// The bake options a command line gave: their values (add_settings_options') and which
// were given, to lay over a world's own settings (the command line wins).
struct GivenSettings {
    BakeSettings values;
    std::vector<std::string> given; // option names without the prefix ("resolution", ...)
    BakeSettings over(const BakeSettings& world) const;
};
// After parser.parse(): what it was given of the options add_settings_options declared.
GivenSettings given_settings(const cli::Parser& parser, const BakeSettings& values, const std::string& prefix);

// Chunk (x, z) covers the tiles [32 x, 32 x + 32) x [32 z, 32 z + 32).
struct ChunkId {
    int x = 0, z = 0;
    friend bool operator==(const ChunkId&, const ChunkId&) = default;
};

// The chunks a scene's wall grid touches, row by row (z, then x).
std::vector<ChunkId> scene_chunks(const scene::Scene& scene);
// Shard `shard` of `shards` (0 <= shard < shards): every shards-th chunk of the list,
// starting at index shard, so the shards partition the list whatever its order of baking.
std::vector<ChunkId> shard_of(const std::vector<ChunkId>& chunks, int shard, int shards);

// A part of a chunk's light apart from the steady one: ground, faces and probes, laid out as
// ChunkBake's.
struct LightPart {
    std::vector<float> ground;
    std::array<std::vector<float>, 4> faces;
    std::vector<CircularHarmonics> probes;
    friend bool operator==(const LightPart&, const LightPart&) = default;
};

struct ChunkBake {
    ChunkId id;
    std::uint64_t key = 0;
    int resolution = 0;
    // No baked light reaches the chunk: no textures (ground and faces empty, all zero).
    bool empty = true;
    // RGB per texel, row-major, (32 x resolution)^2 texels each.
    std::vector<float> ground;
    std::array<std::vector<float>, 4> faces;
    // chunk_probes^2, row-major; probe_valid[i] 0 where the probe's tile is a wall.
    std::vector<CircularHarmonics> probes;
    std::vector<std::uint8_t> probe_valid;
    // Seed 004's pulsing emission: the light of the pulsing materials' glow alone, at full
    // emission (the steady part above leaves it out). Empty when no pulsing glow reaches the
    // chunk. The run time adds it scaled by scene::pulse_factor: a colour-only update, not a
    // re-bake.
    LightPart pulse;
    // The moving sun's keys (BakeSettings::sun_keys; empty without): key k holds the mixed
    // sun's bounce at scene::sun_key_time(k, keys), colour 1, intensity 1 (x its `indirect`).
    std::vector<LightPart> sun_keys;

    int side() const { return chunk_tiles * resolution; }
    bool pulses() const { return !pulse.ground.empty(); }
    friend bool operator==(const ChunkBake&, const ChunkBake&) = default;
};

// The settings chunk `chunk` bakes with: `settings` at the chunk's own resolution
// (BakeSettings::resolution_at, seed 004's texel density per chunk), without the density
// list, so a chunk's key and bytes depend on its own resolution alone.
BakeSettings chunk_settings(const BakeSettings& settings, ChunkId chunk);

// Hash of everything the chunk's bake depends on: the solver (name, code version, its
// settings at the chunk's resolution and the scene's gi settings), the chunk, the walls and
// materials within reach, and the mixed and baked lights and shadow proxies that reach it.
std::uint64_t chunk_key(const scene::Scene& scene, ChunkId chunk, const BakeSettings& settings);
// Solves the chunk at its resolution (chunk_settings; one thread; about a second at the defaults). With `samples`, also what each
// probe was captured from (chunk_probes^2 entries, empty where no probe is), for measuring the
// harmonics' order (ProbeOrderError).
ChunkBake bake_chunk(const scene::Scene& scene, ChunkId chunk, const BakeSettings& settings,
                     std::vector<ProbeSamples>* samples = nullptr);

// The baked light at world point p for a surface facing angle phi, interpolated bilinearly
// between the four probes around p, over those that exist (`probe(ix, iz)`: the probe at
// (2 ix + 0.5, 2 iz + 0.5), nullptr in a wall or an unbaked chunk). Zero when none does.
// Large objects sample a few points over their footprint (the LPPV equivalent).
template <typename ProbeAt>
CircularHarmonics interpolate_probes(ProbeAt&& probe, glm::vec2 p) {
    const glm::vec2 g = (p - 0.5f) / float(probe_spacing);
    const glm::ivec2 i0(int(std::floor(g.x)), int(std::floor(g.y)));
    const glm::vec2 f = g - glm::vec2(i0);
    CircularHarmonics sum;
    float weight = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const int dx = k & 1, dz = k >> 1;
        const CircularHarmonics* h = probe(i0.x + dx, i0.y + dz);
        if (!h) continue;
        const float w = (dx ? f.x : 1.0f - f.x) * (dz ? f.y : 1.0f - f.y);
        sum += *h * w;
        weight += w;
    }
    return weight > 0.0f ? sum * (1.0f / weight) : CircularHarmonics{};
}

// ---- cache files

std::string chunk_file_name(ChunkId chunk); // "chunk_<x>_<z>.lbk"
std::vector<std::byte> encode_chunk(const ChunkBake& bake);
// Errors name what is wrong: "truncated", "not a Lantern bake file", "format version N",
// "sizes do not match" ... (never trusts a size it read before checking it against the bytes).
Result<ChunkBake> decode_chunk(std::span<const std::uint8_t> bytes);
// The chunk's cache file in `dir` when it exists, decodes and holds `key`; otherwise
// nullopt and, in `why`, the reason ("missing", "stale: made for other inputs", a decode
// error).
std::optional<ChunkBake> load_chunk(const std::string& dir, ChunkId chunk, std::uint64_t key,
                                    std::string* why = nullptr);
// Writes the cache file atomically (a bake killed midway leaves the previous file).
Result<void> save_chunk(const std::string& dir, const ChunkBake& bake);

// ---- a whole world

struct BakeProgress {
    int done = 0, total = 0; // chunks
    int baked = 0, reused = 0;
    double seconds = 0.0;
};

struct BakeOptions {
    jobs::JobSystem* jobs = nullptr; // chunks in parallel when set
    int shard = 0, shards = 1;       // bake only shard_of(scene_chunks(scene), shard, shards)
    bool force = false;              // bake even where a valid cache exists
    // Called on the calling thread as chunks finish (progress bars).
    std::function<void(const BakeProgress&)> progress;
    // Called on the calling thread for each cache file found unusable (and re-baked).
    std::function<void(const std::string& message)> warn;
};

struct BakeReport {
    int chunks = 0; // in this shard
    int baked = 0, reused = 0;
    int empty = 0; // chunks no baked light reaches (their files hold no textures)
    double seconds = 0.0;
};

// Bakes the world's chunks (of this shard) into `dir`, reusing every valid cache file.
// Errors (exit status 2): invalid settings or shard, a folder that cannot be written.
Result<BakeReport> bake_world(const scene::Scene& scene, const std::string& dir, const BakeSettings& settings,
                              const BakeOptions& options = {});

// ---- at run time (docs/baked.md, "At run time")

// The chunks' baked light over the rectangle of whole chunks they cover, as the frame reads
// it (FrameInputs::baked): each chunk's ground and faces laid side by side and stored in
// seed 002's bricks at `eps`, none coarser than `max_level`. `walls` decides which texels
// hold light (open ground; the exposed faces of wall tiles). A chunk without baked light
// (empty) holds zero. Chunks baked at different resolutions (texel density per chunk) are
// laid out at the finest one: a coarser chunk's texels are resampled bilinearly, over the
// texels of its own that hold light in that layer (open ground; the face's exposed wall
// texels), clamped at its border. Empty `chunks`: nullptr.
// nullptr too when the rectangle needs more bricks than one atlas addresses (a world far
// larger than a frame's window: compose the chunks around it), saying so in `why`.
std::shared_ptr<const gi::BakedLight> runtime_light(std::span<const ChunkBake* const> chunks, const gi::WallView& walls,
                                                    float eps = gi::baked_eps, int max_level = gi::brick_levels - 1,
                                                    std::string* why = nullptr);

// The scene as the live passes light it once its bake is used: without the `baked` lights
// and the materials' glow, which the baked light holds. (Mixed lights stay: their direct
// light is live.)
scene::Scene live_scene(const scene::Scene& scene);

// Bakes the world's chunks into `dir` (bake_world: reusing every valid cache file), then
// reads them back as the frame's baked light. Errors as bake_world's.
Result<std::shared_ptr<const gi::BakedLight>> load_world_light(const scene::Scene& scene, const std::string& dir,
                                                               const BakeSettings& settings, const BakeOptions& options = {});

} // namespace lantern::bake
