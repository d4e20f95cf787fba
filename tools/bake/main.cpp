// lantern-bake: bakes a world's static light into chunk cache files (docs/baked.md).
//
//   lantern-bake WORLD --out DIR [--shard I/N] [--resolution R] [--margin M] [--rays N] [--face-rays N]
//                [--solver gather|seed002] [--falloff TILES] [--ambient E] [--non-directional] [--sun-keys K] [--eps E]
//                [--max-level L] [--density X0,Z0,X1,Z1,R ...]
//                [--threads N] [--force] [--image FILE.png] [--bricks EPS,...]
//
// The settings start from the scene's own "bake" section (seed 002: saved with the world);
// options given here win.
//
// WORLD is a scene file (docs/scenes.md) or a Moving AI map (walls only: then only glowing
// materials could light it, and a map has none, so every chunk is empty). A second run
// reuses every cache file whose key still matches; unusable files are named and re-baked.
#include "lantern/bake/bake.hpp"
#include "lantern/gi/bricks.hpp"
#include "lantern/core/cli.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/png.hpp"
#include "lantern/gi/shading.hpp"

#include <glm/common.hpp>
#include "lantern/jobs/job_system.hpp"
#include "lantern/scene/loader.hpp"
#include "lantern/transport/progress.hpp"

#include <algorithm>
#include <mutex>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

using namespace lantern;

namespace {

Result<scene::Scene> load_world(const std::string& path) {
    if (path.ends_with(".map")) {
        auto map = scene::import_moving_ai_map(path);
        if (!map) return map.error();
        scene::Scene s;
        s.source = path;
        s.walls = std::move(map->walls);
        return s;
    }
    return scene::load_scene(path);
}

std::optional<std::string> parse_shard(std::string_view text, int& shard, int& shards) {
    const std::size_t slash = text.find('/');
    auto number = [](std::string_view t, int& out) {
        const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
        return r.ec == std::errc() && r.ptr == t.data() + t.size();
    };
    if (slash == std::string_view::npos || !number(text.substr(0, slash), shard) ||
        !number(text.substr(slash + 1), shards) || shards < 1 || shards > 1000000 || shard < 0 || shard >= shards)
        return "expected I/N with 0 <= I < N (e.g. 0/4), got '" + std::string(text.substr(0, 40)) + "'";
    return std::nullopt;
}

// The finest resolution any of the chunks bakes at (texel density per chunk: the pictures
// and fields below are laid out at it, coarser chunks' texels repeated).
int finest_resolution(const std::vector<bake::ChunkId>& chunks, const bake::BakeSettings& b) {
    int r = 1;
    for (const bake::ChunkId c : chunks) r = std::max(r, b.resolution_at(c.x, c.z));
    return r;
}
// The index of a chunk's texel (RGB triple) under texel (x, y) of a grid of `res` texels a tile.
std::size_t chunk_texel(const bake::ChunkBake& chunk, int res, int x, int y) {
    const int cx = x * chunk.resolution / res, cy = y * chunk.resolution / res;
    return (std::size_t(cy) * std::size_t(chunk.side()) + std::size_t(cx)) * 3;
}

// The baked light of every chunk of this shard as one picture, top down: ground light
// tone-mapped (ACES), walls grey with their brightest face's light.
Result<void> write_picture(const scene::Scene& scene, const std::string& dir, const bake::BakeSettings& b,
                           const bake::BakeOptions& o, const std::string& path) {
    const std::vector<bake::ChunkId> all = bake::scene_chunks(scene);
    if (all.empty()) return make_error("lantern-bake: --image: the world has no chunks");
    const std::vector<bake::ChunkId> chunks = bake::shard_of(all, o.shard, o.shards);
    int x0 = all.front().x, x1 = all.front().x, z0 = all.front().z, z1 = all.front().z;
    for (const bake::ChunkId c : all)
        x0 = std::min(x0, c.x), x1 = std::max(x1, c.x), z0 = std::min(z0, c.z), z1 = std::max(z1, c.z);
    const int res = finest_resolution(all, b), side = bake::chunk_tiles * res;
    const int w = (x1 - x0 + 1) * side, h = (z1 - z0 + 1) * side;
    if (std::int64_t(w) * h > (std::int64_t(1) << 28)) return make_error("lantern-bake: --image: the picture would be too large");
    std::vector<std::uint8_t> rgb(std::size_t(w) * std::size_t(h) * 3, 0);
    for (const bake::ChunkId c : chunks) {
        auto chunk = bake::load_chunk(dir, c, bake::chunk_key(scene, c, b));
        if (!chunk || chunk->empty) continue;
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                const std::size_t i = chunk_texel(*chunk, res, x, y);
                glm::vec3 v(chunk->ground[i], chunk->ground[i + 1], chunk->ground[i + 2]);
                for (const auto& f : chunk->faces) v = glm::max(v, glm::vec3(f[i], f[i + 1], f[i + 2]) * 0.5f);
                const glm::vec3 t = gi::tone_map(v, scene::ToneMap::aces, 4.0f);
                const std::size_t o8 = (std::size_t((c.z - z0) * side + y) * std::size_t(w) + std::size_t((c.x - x0) * side + x)) * 3;
                for (int k = 0; k < 3; ++k) rgb[o8 + std::size_t(k)] = std::uint8_t(std::lround(std::clamp(t[k], 0.0f, 1.0f) * 255.0f));
            }
    }
    return write_png(path, w, h, 3, rgb);
}

// The world's baked ground light as one field (every chunk of the world found in `dir`).
std::optional<gi::Field> world_field(const scene::Scene& scene, const std::string& dir, const bake::BakeSettings& b) {
    const std::vector<bake::ChunkId> all = bake::scene_chunks(scene);
    if (all.empty()) return std::nullopt;
    int x0 = all.front().x, x1 = x0, z0 = all.front().z, z1 = z0;
    for (const bake::ChunkId c : all)
        x0 = std::min(x0, c.x), x1 = std::max(x1, c.x), z0 = std::min(z0, c.z), z1 = std::max(z1, c.z);
    const int res = finest_resolution(all, b), side = bake::chunk_tiles * res;
    gi::Field f;
    f.width = (x1 - x0 + 1) * side;
    f.height = (z1 - z0 + 1) * side;
    f.rgb.assign(std::size_t(f.width) * std::size_t(f.height) * 3, 0.0f);
    f.air.assign(std::size_t(f.width) * std::size_t(f.height), 0);
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const int tx = x0 * bake::chunk_tiles + x / res, tz = z0 * bake::chunk_tiles + y / res;
            f.air[std::size_t(y) * std::size_t(f.width) + std::size_t(x)] = scene.walls.is_wall_tile(tx, tz) ? 0 : 1;
        }
    for (const bake::ChunkId c : all) {
        auto chunk = bake::load_chunk(dir, c, bake::chunk_key(scene, c, b));
        if (!chunk || chunk->empty) continue;
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x)
                std::copy_n(&chunk->ground[chunk_texel(*chunk, res, x, y)], 3,
                            &f.rgb[(std::size_t((c.z - z0) * side + y) * std::size_t(f.width) + std::size_t((c.x - x0) * side + x)) * 3]);
    }
    return f;
}

// Seed 002's claim measured: memory of the adaptive bricks against a dense grid, and the
// error each adds (RGBM included), over the open ground.
void brick_report(const gi::Field& f, const std::vector<float>& eps_list) {
    const double dense_rgbm = double(f.width) * f.height * 4, dense_half = double(f.width) * f.height * 6;
    std::printf("\n%d x %d probes; dense: %.2f MB as RGBM8, %.2f MB as RGB half\n", f.width, f.height, dense_rgbm / 1e6,
                dense_half / 1e6);
    std::printf("| eps | bricks (level 0/1/2/3) | empty cells | atlas + indirection | vs dense RGBM8 | rel. RMS error | max error |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (float eps : eps_list) {
        const gi::BrickAtlas a = gi::build_bricks(f, eps);
        double err2 = 0.0, ref2 = 0.0, worst = 0.0;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                if (!f.air[std::size_t(y) * std::size_t(f.width) + std::size_t(x)]) continue;
                const glm::vec3 want = f.at(x, y), got = gi::sample_bricks(a, float(x) + 0.5f, float(y) + 0.5f);
                for (int c = 0; c < 3; ++c) {
                    const double d = double(got[c]) - double(want[c]);
                    err2 += d * d;
                    ref2 += double(want[c]) * double(want[c]);
                    worst = std::max(worst, std::abs(d));
                }
            }
        std::printf("| %g | %d (%d/%d/%d/%d) | %d | %.3f MB | %.1f %% | %.2f %% | %.4f |\n", double(eps), a.bricks(),
                    a.bricks_per_level[0], a.bricks_per_level[1], a.bricks_per_level[2], a.bricks_per_level[3], a.empty_cells,
                    double(a.bytes()) / 1e6, 100.0 * double(a.bytes()) / dense_rgbm,
                    ref2 > 0.0 ? 100.0 * std::sqrt(err2 / ref2) : 0.0, worst);
    }
}

// Order 1 against order 2 (issue 18: "order 2, or order 1 if measured good enough"): up to
// `count` of the shard's chunks that hold baked light, spread over it, baked again with what
// each probe was captured from; each probe's harmonics against the exact irradiance of its
// samples, at 64 orientations.
void probe_order_report(const scene::Scene& scene, const bake::BakeSettings& b, const bake::BakeOptions& o, int count,
                        jobs::JobSystem& jobs) {
    std::vector<bake::ChunkId> chunks = bake::shard_of(bake::scene_chunks(scene), o.shard, o.shards);
    std::vector<bake::ChunkId> picked;
    const std::size_t step = std::max<std::size_t>(1, chunks.size() / std::size_t(count));
    for (std::size_t i = 0; i < chunks.size() && int(picked.size()) < count; i += step) picked.push_back(chunks[i]);
    std::vector<bake::ProbeOrderError> errors(picked.size());
    std::vector<std::uint8_t> lit(picked.size(), 0);
    transport::ProgressBar bar("probe orders");
    std::mutex progress;
    int done = 0;
    jobs.parallel_for("probe orders", 0, std::uint32_t(picked.size()), 1, [&](std::uint32_t first, std::uint32_t last, std::uint32_t) {
        for (std::uint32_t i = first; i < last; ++i) {
            std::vector<bake::ProbeSamples> samples;
            const bake::ChunkBake c = bake::bake_chunk(scene, picked[i], b, &samples);
            for (std::size_t k = 0; k < c.probes.size(); ++k)
                if (c.probe_valid[k]) errors[i].add(c.probes[k], samples[k]);
            lit[i] = c.empty ? 0 : 1;
            const std::lock_guard lock(progress);
            ++done;
            bar.update(double(done) / double(picked.size()), std::to_string(done) + "/" + std::to_string(picked.size()) + " chunks");
        }
    });
    bake::ProbeOrderError all;
    int with_light = 0;
    for (std::size_t i = 0; i < picked.size(); ++i) {
        if (!lit[i]) continue;
        ++with_light;
        const bake::ProbeOrderError& e = errors[i];
        all.probes += e.probes, all.samples += e.samples, all.exact1 += e.exact1, all.exact2 += e.exact2;
        for (std::size_t k = 0; k < 2; ++k) {
            all.err1[k] += e.err1[k], all.err2[k] += e.err2[k];
            all.worst_probe[k] = std::max(all.worst_probe[k], e.worst_probe[k]);
        }
    }
    bar.finish(std::to_string(with_light) + " of " + std::to_string(picked.size()) + " chunks with baked light, " +
               std::to_string(all.probes) + " probes");
    std::printf("\nprobes: %lld in %d chunks, 64 orientations each, %d rays a probe\n", all.probes, with_light, b.rays);
    std::printf("| order | floats per probe | rel. RMS error | rel. mean abs. error | worst probe (rel. RMS) |\n");
    std::printf("|---|---|---|---|---|\n");
    for (int order = 1; order <= 2; ++order)
        std::printf("| %d | %d | %.2f %% | %.2f %% | %.1f %% |\n", order, order == 1 ? 9 : 15, 100.0 * all.relative_rms(order),
                    100.0 * all.relative_mean_abs(order), 100.0 * all.worst_probe[std::size_t(order - 1)]);
}

} // namespace

int main(int argc, char** argv) {
    std::string world, out;
    bake::BakeSettings settings;
    bake::BakeOptions options;
    int threads = int(std::max(1u, std::thread::hardware_concurrency()));
    cli::Parser p("lantern-bake", "WORLD --out DIR [options]",
                  "Bakes the static light of a scene (or map) into one cache file per 32 x 32-tile chunk:\n"
                  "the direct light of lights with \"mode\": \"baked\" and the bounce light of \"mixed\" and\n"
                  "\"baked\" lights and glowing materials, solved by the converged gather method. A second run\n"
                  "reuses every file whose inputs did not change (docs/baked.md).");
    p.positionals("WORLD", "a scene file (.json) or a Moving AI map (.map)", [&](std::string_view v) -> std::optional<std::string> {
        if (!world.empty()) return "one WORLD only, got a second: '" + std::string(v.substr(0, 40)) + "'";
        world = std::string(v);
        return std::nullopt;
    });
    p.text("--out", "DIR", "the cache folder (created if missing)", out);
    p.custom("--shard", "I/N", "bake only shard I of N (every N-th chunk from the I-th); all N shards "
                               "together write the same files as one run", [&](std::string_view v) {
        return parse_shard(v, options.shard, options.shards);
    });
    bake::add_settings_options(p, settings, "--");
    p.integer("--threads", "N", "threads (default: the machine's cores)", threads, 1, 256);
    p.flag("--force", "bake every chunk, even where a valid cache file exists", options.force);
    std::string image;
    std::vector<float> brick_eps;
    p.custom("--bricks", "EPS,...", "then report the adaptive brick storage of the baked light (seed 002) at these colour "
                                    "ranges: memory against a dense grid and the error each adds",
             [&](std::string_view v) -> std::optional<std::string> {
                 brick_eps.clear();
                 std::string list(v);
                 for (std::size_t at = 0; at <= list.size();) {
                     const std::size_t comma = std::min(list.find(',', at), list.size());
                     float e = 0.0f;
                     const auto r = std::from_chars(list.data() + at, list.data() + comma, e);
                     if (r.ec != std::errc() || r.ptr != list.data() + comma || !(e >= 0.0f) || e > 1e6f)
                         return "expected numbers >= 0 separated by commas, got '" + list.substr(0, 40) + "'";
                     brick_eps.push_back(e);
                     at = comma + 1;
                 }
                 return std::nullopt;
             });
    p.text("--image", "FILE.png", "also draw this shard's baked light, top down, as one picture", image);
    int probe_chunks = 0;
    p.integer("--probe-orders", "N", "then report how well the probes' harmonics of order 1 and 2 give the irradiance "
                                     "of what they were captured from, over N of the shard's chunks (baked again)",
              probe_chunks, 1, 1 << 20);
    p.epilog("Exit status: 0 done, 2 bad input (a message names the file, line and column).");
    if (auto exit = p.parse(argc, argv)) return *exit;
    if (world.empty()) {
        std::fprintf(stderr, "%s\n", p.message("WORLD is required").c_str());
        return 2;
    }
    if (out.empty()) {
        std::fprintf(stderr, "%s\n", p.message("--out DIR is required").c_str());
        return 2;
    }
    auto scene = load_world(world);
    if (!scene) {
        std::fprintf(stderr, "%s\n", scene.error().message.c_str());
        return scene.error().exit_code;
    }
    // The world's own settings (its scene file's "bake"), the options given here over them.
    settings = bake::given_settings(p, settings, "--").over(scene->bake);
    jobs::JobSystem::Config config;
    config.worker_threads = threads - 1;
    jobs::JobSystem jobs(config);
    options.jobs = &jobs;
    transport::ProgressBar bar("bake");
    options.progress = [&](const bake::BakeProgress& pr) {
        char status[128];
        std::snprintf(status, sizeof(status), "%d/%d chunks (%d reused) %.1f s", pr.done, pr.total, pr.reused, pr.seconds);
        bar.update(pr.total ? double(pr.done) / double(pr.total) : 1.0, status);
    };
    options.warn = [](const std::string& m) { std::fprintf(stderr, "lantern-bake: %s\n", m.c_str()); };
    auto report = bake::bake_world(*scene, out, settings, options);
    if (!report) {
        std::fprintf(stderr, "lantern-bake: %s\n", report.error().message.c_str());
        return report.error().exit_code;
    }
    char status[160];
    std::snprintf(status, sizeof(status), "%d chunks: %d baked, %d reused, %d without baked light, %.2f s", report->chunks,
                  report->baked, report->reused, report->empty, report->seconds);
    if (!image.empty())
        if (auto ok = write_picture(*scene, out, settings, options, image); !ok) {
            std::fprintf(stderr, "%s\n", ok.error().message.c_str());
            return ok.error().exit_code;
        }
    if (!brick_eps.empty())
        if (auto f = world_field(*scene, out, settings)) brick_report(*f, brick_eps);
    if (probe_chunks > 0) probe_order_report(*scene, settings, options, probe_chunks, jobs);
    bar.finish(std::string(status) + " (shard " + std::to_string(options.shard) + "/" +
               std::to_string(options.shards) + ") in " + out);
    return 0;
}
