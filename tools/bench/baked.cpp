// lantern-bench baked: what the bake costs and saves (docs/baked.md, "Measured").
//
// A world of the procedural caves with their lava and crystal veins (chunks x chunks
// streaming chunks) and `lights` point lights on open tiles:
//   1. the bake: every chunk with the game's bake settings on 1 and on 2 threads (seconds,
//      per chunk), into a fresh folder each time;
//   2. memory: the baked ground light as a dense RGBM8 grid, as RGB halves, and as seed 002's
//      bricks at several eps, with the error each adds (relative RMS against the dense
//      floats);
//   3. the frame on the device, all passes planned, medians of `repeats` frames: the lights
//      realtime (and the veins' glow live, with the gather method), then mixed (direct light
//      live, bounce baked), then baked, for each method;
//   4. where the atlas is sampled: once per GI texel (the game) against once per pixel (seed
//      002's per fragment), the baked_sample pass's cost and the ground light's difference.
#include "bench.hpp"

#include "lantern/bake/bake.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/machine.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/scene/procedural.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace lantern::bench {
namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

scene::Scene caves_world(int chunks, int lights, scene::LightMode mode) {
    scene::Scene s;
    const scene::CaveParams params{1, 0.47f, true};
    s.walls = scene::generate_caves({0, 0}, {chunks * bake::chunk_tiles, chunks * bake::chunk_tiles}, params);
    s.materials = scene::cave_materials();
    // Lights on open tiles, spread by a fixed stride over the world.
    std::uint32_t h = 12345u;
    for (int placed = 0, tries = 0; placed < lights && tries < lights * 200; ++tries) {
        h = h * 1664525u + 1013904223u;
        const int x = int((h >> 8) % std::uint32_t(s.walls.width)), z = int((h >> 20) % std::uint32_t(s.walls.height));
        if (s.walls.is_wall_tile(x, z)) continue;
        const glm::vec3 colors[] = {{1.0f, 0.7f, 0.4f}, {0.5f, 0.7f, 1.0f}, {1.0f, 0.9f, 0.8f}};
        s.point_lights.push_back({{float(x) + 0.5f, float(z) + 0.5f}, 1.0f, colors[placed % 3], 1.5f, 8.0f, mode});
        ++placed;
    }
    const float mid = float(chunks * bake::chunk_tiles) * 0.5f;
    s.view = scene::OrthoView{{mid, mid}, {30.0f, 16.875f}};
    s.gi.resolution = 4;
    return s;
}

struct FrameNumbers {
    double total = 0.0;
    std::map<gi::Pass, double> passes;
};

Result<FrameNumbers> time_frames(gi::vk::Renderer& renderer, const gi::FrameInputs& in, int repeats) {
    const gi::PassPlan plan = gi::plan_passes(in, false);
    std::vector<double> totals;
    std::map<gi::Pass, std::vector<double>> samples;
    for (int rep = 0; rep <= repeats; ++rep) { // rep 0 warms up (pipelines, uploads)
        auto frame = gi::run_vulkan_frame(renderer, in, plan, false);
        if (!frame) return frame.error();
        if (rep == 0) continue;
        totals.push_back(frame->total_ms);
        for (const gi::PassReport& p : frame->passes)
            if (p.ran) samples[p.pass].push_back(p.gpu_ms);
    }
    FrameNumbers n;
    n.total = median(totals);
    for (auto& [pass, v] : samples) n.passes[pass] = median(v);
    return n;
}

} // namespace

int baked(const BakedOptions& o) {
    namespace fs = std::filesystem;
    std::printf("lantern-bench baked: %d x %d chunks of the caves (seed 1, lava and crystal veins), %d point lights\n",
                o.chunks, o.chunks, o.lights);
    std::printf("Machine: %s\n", describe_machine().c_str());
    bake::BakeSettings settings;
    settings.resolution = o.resolution;
    settings.margin = o.margin;
    settings.rays = o.rays;
    settings.face_rays = o.face_rays;
    settings.solver = o.solver == "seed002" ? bake::BakeSolver::seed002 : bake::BakeSolver::gather;
    settings.falloff = o.falloff;
    settings.ambient = o.ambient;
    if (o.coarse > 0) // texel density per chunk: the west half of the world at its own resolution
        settings.density.push_back({{0, 0}, {o.chunks / 2 - 1, o.chunks - 1}, o.coarse});
    scene::Scene baked_world = caves_world(o.chunks, o.lights, scene::LightMode::baked);
    if (o.steady)
        for (scene::Material& m : baked_world.materials) m.pulse = 0.0f;
    // --dir: the cache folder is kept, and what it holds for these inputs is read, not baked.
    const bool keep = !o.dir.empty();
    const fs::path dir = keep ? fs::path(o.dir) : fs::temp_directory_path() / ("lantern-bench-baked-" + std::to_string(now_ns()));

    // 1. The bake, on 1 and 2 threads.
    std::printf("\n## Bake (solver %s, resolution %d, margin %d, %d ground and %d face rays)\n\n",
                bake::solver_name(settings.solver), settings.resolution, settings.margin, settings.rays, settings.face_rays);
    if (o.coarse > 0) std::printf("texel density: the west half (chunks x < %d) at resolution %d\n\n", o.chunks / 2, o.coarse);
    if (settings.solver == bake::BakeSolver::seed002)
        std::printf("seed002: falloff %g tiles, ambient %g\n\n", double(settings.falloff), double(settings.ambient));
    std::printf("| threads | chunks | seconds | per chunk |\n|---|---|---|---|\n");
    const std::vector<int> thread_counts = o.threads > 0 ? std::vector<int>{o.threads} : std::vector<int>{1, 2};
    for (int threads : thread_counts) {
        jobs::JobSystem::Config config;
        config.worker_threads = threads - 1;
        jobs::JobSystem jobs(config);
        bake::BakeOptions options;
        options.jobs = &jobs;
        options.force = !keep;
        int shown = -1; // progress on stderr, every 5 %, for large worlds
        options.progress = [&](const bake::BakeProgress& p) {
            const int pct = p.total ? p.done * 100 / p.total : 100;
            if (pct / 5 == shown / 5 && p.done != p.total) return;
            shown = pct;
            std::fprintf(stderr, "\rbake (%d threads): %d / %d chunks (%d %%), %.0f s", threads, p.done, p.total, pct, p.seconds);
            if (p.done == p.total) std::fprintf(stderr, "\n");
        };
        const fs::path out = dir / (threads == thread_counts.front() ? "first" : "t" + std::to_string(threads));
        auto report = bake::bake_world(baked_world, out.string(), settings, options);
        if (!report) {
            std::fprintf(stderr, "lantern-bench baked: %s\n", report.error().message.c_str());
            return report.error().exit_code;
        }
        std::printf("| %d | %d | %.2f | %.3f |\n", threads, report->chunks, report->seconds,
                    report->seconds / std::max(1, report->chunks));
    }

    // The cache files on disk (deflated) against their payloads.
    {
        std::uintmax_t disk = 0, raw = 0;
        int files = 0, empty = 0;
        for (const auto& e : fs::directory_iterator(dir / "first")) {
            if (e.path().extension() != ".lbk") continue;
            disk += e.file_size();
            ++files;
            std::ifstream f(e.path(), std::ios::binary);
            const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
            auto b = bake::decode_chunk(bytes);
            if (b && b->empty) ++empty;
            if (b && !b->empty) {
                const std::size_t side = std::size_t(b->side());
                raw += side * side * 3 * 2 * 5 + b->probes.size() * (15 * 4 + 1);
            }
        }
        std::printf("\nCache files: %d (%d without baked light), %.3f MB on disk (deflated) for %.3f MB of payload: %.1fx\n",
                    files, empty, double(disk) / 1e6, double(raw) / 1e6, disk ? double(raw) / double(disk) : 0.0);
    }

    // 2. Memory: dense against bricks.
    std::vector<bake::ChunkBake> chunks;
    for (bake::ChunkId c : bake::scene_chunks(baked_world)) {
        auto b = bake::load_chunk((dir / "first").string(), c, bake::chunk_key(baked_world, c, settings));
        if (b) chunks.push_back(std::move(*b));
    }
    std::vector<const bake::ChunkBake*> pointers;
    for (const auto& b : chunks) pointers.push_back(&b);
    const int side = o.chunks * bake::chunk_tiles * std::max(settings.resolution, o.coarse); // the finest chunk's
    const std::size_t texels = std::size_t(side) * std::size_t(side);
    std::printf("\n## Memory of the baked light (ground and four face layers, %d x %d texels each)\n\n", side, side);
    std::printf("dense RGBM8, five layers: %.3f MB; dense RGB halves: %.3f MB\n", double(texels * 5 * 4) / 1e6,
                double(texels * 5 * 6) / 1e6);
    if (o.coarse > 0) {
        std::size_t own = 0; // dense, each chunk at its own resolution
        for (const auto& b : chunks) own += std::size_t(b.side()) * std::size_t(b.side());
        std::printf("dense RGBM8 at each chunk's own resolution: %.3f MB\n", double(own * 5 * 4) / 1e6);
    }
    std::printf("\n");
    // One atlas addresses 262,144 bricks: a larger world is composed in blocks of at most
    // 16 x 16 chunks (a frame never reads more than a few), their bricks and bytes summed.
    // (A block's border cells see their apron clamped instead of the neighbour's texels, which
    // can only keep them finer: the sum is an upper bound, equal for worlds of one block.)
    constexpr int block = 16;
    const int blocks = (o.chunks + block - 1) / block;
    if (blocks > 1) std::printf("composed in %d x %d blocks of up to %d x %d chunks (one atlas each)\n\n", blocks, blocks, block, block);
    std::printf("| eps | bricks (level 0/1/2/3) | atlas + indirection | of dense RGBM8 | rel. RMS error (ground) |\n|---|---|---|---|---|\n");
    const gi::WallView walls = gi::WallView::of(baked_world.walls);
    const std::vector<float> eps_list = o.chunks > block ? std::vector<float>{0.01f, 0.2f} : std::vector<float>{0.0f, 0.01f, 0.05f, 0.2f};
    for (float eps : eps_list) {
        double err2 = 0.0, ref2 = 0.0;
        std::size_t bytes = 0;
        int per_level[gi::brick_levels] = {0, 0, 0, 0};
        for (int bz = 0; bz < blocks; ++bz)
            for (int bx = 0; bx < blocks; ++bx) {
                std::vector<const bake::ChunkBake*> in_block;
                for (const auto& b : chunks)
                    if (b.id.x / block == bx && b.id.z / block == bz) in_block.push_back(&b);
                if (in_block.empty()) continue;
                std::string why;
                auto light = bake::runtime_light(in_block, walls, eps, gi::brick_levels - 1, &why);
                if (!light) {
                    std::fprintf(stderr, "lantern-bench baked: %s\n", why.c_str());
                    return 1;
                }
                for (const bake::ChunkBake* b : in_block) {
                    if (b->empty) continue;
                    const int s = b->side();
                    for (int y = 0; y < s; ++y)
                        for (int x = 0; x < s; ++x) {
                            const glm::vec2 p = glm::vec2(float(b->id.x * bake::chunk_tiles), float(b->id.z * bake::chunk_tiles)) +
                                                (glm::vec2(float(x), float(y)) + 0.5f) / float(b->resolution);
                            if (baked_world.walls.is_wall_tile(int(std::floor(p.x)), int(std::floor(p.y)))) continue;
                            const std::size_t i = (std::size_t(y) * std::size_t(s) + std::size_t(x)) * 3;
                            const glm::vec3 want(b->ground[i], b->ground[i + 1], b->ground[i + 2]);
                            const glm::vec3 d = light->sample(0, p) - want;
                            err2 += double(glm::dot(d, d));
                            ref2 += double(glm::dot(want, want));
                        }
                }
                bytes += light->bricks.bytes();
                for (int l = 0; l < gi::brick_levels; ++l) per_level[l] += light->bricks.bricks_per_level[l];
            }
        std::printf("| %g | %d (%d/%d/%d/%d) | %.3f MB | %.1f %% | %.2f %% |\n", double(eps),
                    per_level[0] + per_level[1] + per_level[2] + per_level[3], per_level[0], per_level[1], per_level[2],
                    per_level[3], double(bytes) / 1e6, 100.0 * double(bytes) / double(texels * 5 * 4),
                    100.0 * std::sqrt(err2 / std::max(ref2, 1e-30)));
        std::fflush(stdout);
    }

    // 3. The frame. A failure says why and leaves no temporary folder behind.
    const auto fail = [&](const std::string& message) {
        std::fprintf(stderr, "lantern-bench baked: %s\n", message.c_str());
        if (!keep) fs::remove_all(dir);
        return 1;
    };
    if (!o.frame) {
        if (!keep) fs::remove_all(dir);
        return 0;
    }
    auto device = gpu::Device::create();
    if (!device) return fail(device.error().message);
    // Without dirty light bins: the same still frame repeats, and with them every repeat
    // after the first would record no direct work at all (docs/gi.md, "Dirty light bins").
    // This measures a frame whose lights all changed, as when torches flicker.
    auto renderer = gi::vk::Renderer::create(**device, {.dirty_bins = false});
    if (!renderer) return fail(renderer.error().message);
    auto light = bake::runtime_light(pointers, walls);
    std::printf("\n## The frame on %s (GPU ms, median of %d; every pass planned runs, dirty light bins off)\n\n", (*device)->name().c_str(), o.repeats);
    std::printf("| method | lights | total | direct | mixed | baked | the method's own passes |\n|---|---|---|---|---|---|---|\n");
    for (scene::GiMethod method : {scene::GiMethod::heat, scene::GiMethod::gather}) {
        for (scene::LightMode mode : {scene::LightMode::realtime, scene::LightMode::mixed, scene::LightMode::baked}) {
            scene::Scene s = caves_world(o.chunks, o.lights, mode);
            s.gi.method = method;
            std::string why;
            auto window = gi::compute_window(s.view, s.gi, &why);
            if (!window) continue;
            gi::FrameInputs in;
            if (mode == scene::LightMode::realtime) {
                in = gi::gather_frame_inputs(s, *window);
            } else {
                in = gi::gather_frame_inputs(bake::live_scene(s), *window);
                in.baked = light;
                gi::split_for_bake(in, bake::live_scene(s));
            }
            auto n = time_frames(**renderer, in, o.repeats);
            if (!n) {
                std::fprintf(stderr, "lantern-bench baked: %s\n", n.error().message.c_str());
                return n.error().exit_code;
            }
            auto at = [&](gi::Pass p) { return n->passes.count(p) ? n->passes.at(p) : 0.0; };
            const double own = n->total - at(gi::Pass::direct) - at(gi::Pass::mixed) - at(gi::Pass::baked) -
                               at(gi::Pass::conduction) - at(gi::Pass::ao);
            const char* mode_name = mode == scene::LightMode::realtime ? "realtime" : mode == scene::LightMode::mixed ? "mixed" : "baked";
            std::printf("| %s | %zu %s | %.2f | %.2f | %.2f | %.2f | %.2f |\n", method == scene::GiMethod::heat ? "heat" : "gather",
                        s.point_lights.size(), mode_name, n->total, at(gi::Pass::direct), at(gi::Pass::mixed),
                        at(gi::Pass::baked), own);
        }
    }

    // 4. Where the atlas is sampled: seed 002 samples its probe volume per vertex or per
    // fragment. Lantern samples it once per GI texel (the `baked_sample` pass), and the raster
    // shows each GI texel flat over its pixels, as it shows the rest of the GI. Per fragment
    // would sample once per pixel: at the game's 480x270 over 30 tiles, 16 a tile. The pass
    // at gi.resolution 16 samples exactly there, so it measures that density's cost; its
    // ground light is what per-fragment sampling would show, and the coarser rows' differ
    // from it by what flat texels leave out.
    constexpr int pixel_density = 16;
    std::printf("\n## Where the atlas is sampled: per GI texel or per pixel (seed 002's per vertex or per fragment)\n\n");
    std::printf("The game samples the baked light once per GI texel (gi.resolution 4) and the raster shows each texel flat over\n"
                "its 4 x 4 pixels; per fragment would be gi.resolution %d (480x270 over 30 tiles). Ground light of open tiles,\n"
                "relative RMS against the per-pixel field, each texel's value taken over the pixels it covers.\n\n",
                pixel_density);
    std::printf("| samples a tile | texels sampled a frame | baked_sample ms | x the game's | error against per pixel |\n|---|---|---|---|---|\n");
    struct Field {
        gi::GiWindow window;
        gi::Texture ground;
    };
    auto sample_at = [&](int resolution, FrameNumbers* numbers) -> Result<Field> {
        scene::Scene s = caves_world(o.chunks, o.lights, scene::LightMode::baked);
        s.gi.resolution = resolution;
        std::string why;
        auto window = gi::compute_window(s.view, s.gi, &why);
        if (!window) return make_error("gi.resolution " + std::to_string(resolution) + ": " + why);
        gi::FrameInputs in = gi::gather_frame_inputs(bake::live_scene(s), *window);
        in.baked = light;
        gi::split_for_bake(in, bake::live_scene(s));
        auto n = time_frames(**renderer, in, o.repeats);
        if (!n) return n.error();
        *numbers = *n;
        return Field{*window, (*renderer)->read_back(gi::Tex::baked_ground)};
    };
    FrameNumbers fine_numbers;
    auto fine = sample_at(pixel_density, &fine_numbers);
    if (!fine) return fail(fine.error().message);
    const scene::WallGrid cave_walls = caves_world(o.chunks, 0, scene::LightMode::baked).walls;
    double game_ms = 0.0; // the first row's: gi.resolution 4
    // One row: `coarse` against the per-pixel field, each per-pixel texel against the coarse
    // texel over it, open ground only.
    auto row = [&](int resolution, const FrameNumbers& numbers, const Field& coarse) {
        const double ms = numbers.passes.count(gi::Pass::baked_sample) ? numbers.passes.at(gi::Pass::baked_sample) : 0.0;
        if (game_ms == 0.0) game_ms = ms;
        double err = 0.0, norm = 0.0;
        const gi::GiWindow& fw = fine->window;
        const gi::GiWindow& cw = coarse.window;
        for (int j = 0; j < fw.height; ++j)
            for (int i = 0; i < fw.width; ++i) {
                const glm::vec2 p = fw.texel_center(i, j);
                if (cave_walls.is_wall_tile(int(std::floor(p.x)), int(std::floor(p.y)))) continue;
                const int ci = int(std::floor((p.x - cw.view.min_x) * float(cw.resolution)));
                const int cj = int(std::floor((p.y - cw.view.min_z) * float(cw.resolution)));
                if (ci < 0 || cj < 0 || ci >= cw.width || cj >= cw.height) continue;
                for (int c = 0; c < 3; ++c) {
                    const double a = coarse.ground.at(ci, cj)[c], b = fine->ground.at(i, j)[c];
                    err += (a - b) * (a - b);
                    norm += b * b;
                }
            }
        // No baked light on the open ground in view (a world too small for the window): no error to give.
        char error[48] = "no baked light in view";
        if (norm > 0.0) std::snprintf(error, sizeof error, "%.2f %%", 100.0 * std::sqrt(err / norm));
        std::printf("| %d x %d | %d | %.2f | %.1f | %s |\n", resolution, resolution, cw.width * cw.height, ms,
                    game_ms > 0.0 ? ms / game_ms : 0.0, error);
        return ms;
    };
    for (int resolution : {4, 8}) {
        FrameNumbers numbers;
        auto coarse = sample_at(resolution, &numbers);
        if (!coarse) return fail(coarse.error().message);
        row(resolution, numbers, *coarse);
    }
    const double fine_ms = row(pixel_density, fine_numbers, *fine);
    // The window is padded beyond the screen (gi.padding, window.hpp); a fragment shader
    // samples only what is on screen.
    constexpr int screen = 480 * 270;
    const int window_texels = fine->window.width * fine->window.height;
    std::printf("\nThe window is padded: at %d a tile it holds %d texels for %d pixels on screen, so sampling per\n"
                "fragment would cost about %.2f ms (the pass's time x pixels / texels), %.1f x the game's per-texel pass.\n",
                pixel_density, window_texels, screen, fine_ms * screen / window_texels,
                game_ms > 0.0 ? fine_ms * screen / window_texels / game_ms : 0.0);
    if (!keep) fs::remove_all(dir);
    return 0;
}

} // namespace lantern::bench
