// lantern-demo: the engine demo. 100k agents simulated by ECS systems on the job graph for
// a few hundred frames; prints the profiler's per-system report and writes a Chrome trace.
//
//   lantern-demo [--frames N] [--agents N] [--workers N] [--trace FILE] [--quiet]
#include "lantern/core/cli.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/file.hpp"
#include "lantern/core/machine.hpp"
#include "lantern/ecs/schedule.hpp"
#include "lantern/profile/profiler.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace lantern;
using ecs::Entity;
using ecs::SystemContext;

struct Position {
    float x, y;
};
struct Velocity {
    float x, y;
};
struct Energy {
    float value;
};

constexpr float world_size = 1024.0f;
constexpr int grid_cells = 64; // density grid, grid_cells^2 cells over the world
constexpr float dt = 1.0f / 60.0f;

// Agents per cell. Each thread counts into its own histogram (no shared atomics in the
// hot loop), then the histograms are summed.
struct DensityGrid {
    std::vector<std::uint32_t> counts = std::vector<std::uint32_t>(grid_cells * grid_cells);
    std::vector<std::vector<std::uint32_t>> per_thread;
    static int cell(float v) { return std::clamp(int(v / world_size * grid_cells), 0, grid_cells - 1); }
    std::uint32_t at(int cx, int cy) const {
        cx = std::clamp(cx, 0, grid_cells - 1);
        cy = std::clamp(cy, 0, grid_cells - 1);
        return counts[cy * grid_cells + cx];
    }
};

struct Stats {
    std::uint32_t agents = 0;
    double mean_speed = 0.0;
    std::uint64_t respawned = 0;
    float camera_x = 0, camera_y = 0;
};

// Deterministic per-entity random numbers (no shared RNG state between jobs).
float hash01(std::uint32_t a, std::uint32_t b) {
    std::uint32_t h = a * 0x9E3779B1u ^ (b + 0x7F4A7C15u) * 0x85EBCA77u;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    return float(h & 0xFFFFFF) / float(0xFFFFFF);
}

void spawn_agent(ecs::CommandBuffer& cb, std::uint32_t seed) {
    Entity e = cb.create();
    cb.emplace<Position>(e, hash01(seed, 1) * world_size, hash01(seed, 2) * world_size);
    float angle = hash01(seed, 3) * 6.2831853f;
    cb.emplace<Velocity>(e, std::cos(angle) * 20.0f, std::sin(angle) * 20.0f);
    cb.emplace<Energy>(e, 1.0f + 5.0f * hash01(seed, 4));
}

void add_systems(ecs::Schedule& schedule) {
    schedule.add("density_grid", [](SystemContext& ctx) {
        auto& grid = ctx.world.resource<DensityGrid>();
        grid.per_thread.resize(ctx.jobs.thread_count(), std::vector<std::uint32_t>(grid.counts.size()));
        for (auto& h : grid.per_thread) std::fill(h.begin(), h.end(), 0u);
        ctx.world.view<Position>().par_each(ctx.jobs, 4096, [&](const Position& p) {
            grid.per_thread[ctx.jobs.current_worker()][DensityGrid::cell(p.y) * grid_cells + DensityGrid::cell(p.x)]++;
        }, "density_grid.chunk");
        std::fill(grid.counts.begin(), grid.counts.end(), 0u);
        for (const auto& h : grid.per_thread)
            for (std::size_t i = 0; i < h.size(); ++i) grid.counts[i] += h[i];
    }).reads<Position>().writes_resource<DensityGrid>();

    schedule.add("steer", [](SystemContext& ctx) {
        const auto& grid = ctx.world.resource<DensityGrid>();
        ctx.world.view<Position, Velocity>().par_each(ctx.jobs, 4096, [&](const Position& p, Velocity& v) {
            // Move down the density gradient, keep speed bounded.
            int cx = DensityGrid::cell(p.x), cy = DensityGrid::cell(p.y);
            float gx = float(grid.at(cx + 1, cy)) - float(grid.at(cx - 1, cy));
            float gy = float(grid.at(cx, cy + 1)) - float(grid.at(cx, cy - 1));
            v.x -= gx * 0.5f * dt;
            v.y -= gy * 0.5f * dt;
            float speed = std::sqrt(v.x * v.x + v.y * v.y);
            if (speed > 40.0f) {
                v.x *= 40.0f / speed;
                v.y *= 40.0f / speed;
            }
        }, "steer.chunk");
    }).reads<Position>().writes<Velocity>().reads_resource<DensityGrid>();

    schedule.add("integrate", [](SystemContext& ctx) {
        ctx.world.view<Position, Velocity>().par_each(ctx.jobs, 4096, [](Position& p, Velocity& v) {
            p.x += v.x * dt;
            p.y += v.y * dt;
            if (p.x < 0 || p.x > world_size) v.x = -v.x, p.x = std::clamp(p.x, 0.0f, world_size);
            if (p.y < 0 || p.y > world_size) v.y = -v.y, p.y = std::clamp(p.y, 0.0f, world_size);
        }, "integrate.chunk");
    }).writes<Position, Velocity>();

    schedule.add("metabolism", [](SystemContext& ctx) {
        std::uint32_t tick = ctx.this_run;
        std::atomic<std::uint64_t> died{0};
        ctx.world.view<Energy, Velocity>().par_each(ctx.jobs, 4096, [&](Entity e, Energy& energy, const Velocity& v) {
            energy.value -= (0.5f + 0.02f * std::sqrt(v.x * v.x + v.y * v.y)) * dt;
            if (energy.value <= 0.0f) {
                // Structural changes from inside a parallel iteration: per-worker buffers.
                auto& cb = ctx.commands();
                cb.destroy(e);
                spawn_agent(cb, e.index * 7919u + tick);
                died.fetch_add(1, std::memory_order_relaxed);
            }
        }, "metabolism.chunk");
        ctx.world.resource<Stats>().respawned += died.load();
    }).writes<Energy>().reads<Velocity>().writes_resource<Stats>();

    schedule.add("statistics", [](SystemContext& ctx) {
        auto& pool = ctx.world.assure<Velocity>();
        const Velocity* v = pool.data();
        double sum = ctx.jobs.parallel_reduce("statistics.chunk", 0, pool.size(), 16384, 0.0,
            [&](std::uint32_t b, std::uint32_t e) {
                double s = 0;
                for (std::uint32_t i = b; i < e; ++i) s += std::sqrt(v[i].x * v[i].x + v[i].y * v[i].y);
                return s;
            }, [](double a, double b) { return a + b; });
        auto& stats = ctx.world.resource<Stats>();
        stats.agents = pool.size();
        stats.mean_speed = pool.size() ? sum / pool.size() : 0.0;
    }).reads<Velocity>().writes_resource<Stats>();

    // Stands in for the window/GPU systems that must run on the main thread.
    schedule.add("camera_follow", [](SystemContext& ctx) {
        auto& stats = ctx.world.resource<Stats>();
        const auto& grid = ctx.world.resource<DensityGrid>();
        std::uint32_t best = 0;
        int bx = 0, by = 0;
        for (int y = 0; y < grid_cells; ++y)
            for (int x = 0; x < grid_cells; ++x)
                if (grid.at(x, y) > best) best = grid.at(x, y), bx = x, by = y;
        float tx = (bx + 0.5f) * world_size / grid_cells, ty = (by + 0.5f) * world_size / grid_cells;
        stats.camera_x += (tx - stats.camera_x) * 0.1f;
        stats.camera_y += (ty - stats.camera_y) * 0.1f;
    }).main_thread().reads_resource<DensityGrid>().writes_resource<Stats>();
}

struct Options {
    int frames = 300;
    int agents = 100000;
    int workers = -1;
    std::string trace = "out/demo_trace.json";
    bool quiet = false;
};

} // namespace

int main(int argc, char** argv) {
    Options opt;
    cli::Parser p("lantern-demo", "[options]",
                  "Simulates N agents with ECS systems on the job graph, prints the profiler report and\n"
                  "writes a Chrome trace (open it in ui.perfetto.dev).");
    p.integer("--frames", "N", "frames to simulate (default 300)", opt.frames, 1, 100000000);
    p.integer("--agents", "N", "agents (default 100000)", opt.agents, 0, 100000000);
    p.integer("--workers", "N", "job-system worker threads (default: cores - 1)", opt.workers, 0, 256);
    p.text("--trace", "FILE", "the Chrome trace (default out/demo_trace.json)", opt.trace);
    p.flag("--quiet", "no progress output on stderr", opt.quiet);
    if (auto exit = p.parse(argc, argv)) return *exit;

    jobs::JobSystem::Config config;
    config.worker_threads = opt.workers;
    jobs::JobSystem jobs(config);
    profile::set_enabled(true);
    std::printf("lantern-demo: %d agents, %d frames, %u threads (%u workers + main)\n", opt.agents, opt.frames,
                jobs.thread_count(), jobs.worker_threads());
    std::printf("machine: %s\n", describe_machine().c_str());
    std::fflush(stdout);

    ecs::World world;
    world.set_resource<DensityGrid>();
    world.set_resource<Stats>();
    {
        ecs::CommandBuffer cb(world);
        for (int i = 0; i < opt.agents; ++i) spawn_agent(cb, std::uint32_t(i));
        cb.apply();
    }
    ecs::Schedule schedule(jobs);
    add_systems(schedule);

    std::int64_t start = now_ns();
    for (int frame = 0; frame < opt.frames; ++frame) {
        profile::begin_frame();
        schedule.run(world);
        profile::end_frame();
        if (!opt.quiet && (frame + 1) % 50 == 0) {
            const auto& s = world.resource<Stats>();
            std::fprintf(stderr, "  frame %d/%d: %u agents, mean speed %.2f, %llu respawned\n", frame + 1,
                         opt.frames, s.agents, s.mean_speed, static_cast<unsigned long long>(s.respawned));
        }
    }
    double seconds = double(now_ns() - start) * 1e-9;
    std::printf("\n%s", profile::text_report().c_str());
    auto js = jobs.stats();
    std::printf("\njobs: %llu run, %llu stolen\n", (unsigned long long)js.jobs_run, (unsigned long long)js.steals);
    std::printf("%d frames in %.2f s (%.2f ms per frame)\n", opt.frames, seconds, seconds * 1e3 / opt.frames);

    std::filesystem::path trace(opt.trace);
    if (trace.has_parent_path()) {
        if (auto r = ensure_directory(trace.parent_path().string()); !r) {
            std::fprintf(stderr, "lantern-demo: %s\n", r.error().message.c_str());
            return 1;
        }
    }
    if (auto r = profile::write_chrome_trace(opt.trace, 60); !r) {
        std::fprintf(stderr, "lantern-demo: %s\n", r.error().message.c_str());
        return 1;
    }
    std::printf("Chrome trace of the last 60 frames: %s (open in https://ui.perfetto.dev or chrome://tracing)\n",
                opt.trace.c_str());
    return 0;
}
