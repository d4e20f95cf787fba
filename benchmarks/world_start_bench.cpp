// lantern-bench-start: how long the game takes to make its world on big maps (docs/game.md,
// "Performance"). The spawn search alone in its worst case (every tile a wall but one in a
// ring inside the map's edge: it scans the whole map ring by ring), and create_world on a Moving AI map file of
// N x N cells (parse, trees as props with proxies, torches and crystals scattered, spawn),
// for N = 1024, 4096 and 8192. The search visits each ring's rim only, so its time grows with
// the area scanned (x16 from 1024 to 4096), not with the area times the radius.
#include "bench_main.hpp"

#include "lantern/core/file.hpp"
#include "lantern/ecs/world.hpp"
#include "lantern/game/world_setup.hpp"
#include "lantern/systems/world_source.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <random>
#include <string>

namespace {

using namespace lantern;

lantern::bench::Reference reference{
    "Before the rim-only search (same machine class, 2026-11-23): 48 s to start on an 8192^2 map."};

void BM_SpawnSearchWorstCase(benchmark::State& state) {
    const int n = int(state.range(0));
    scene::WallGrid grid;
    grid.width = grid.height = n;
    grid.cells.assign(std::size_t(n) * std::size_t(n), 1);
    // The only open tile on the map, on the last ring inside it (outside the map is air).
    const glm::ivec2 open(n - 1, n / 2 + 3);
    grid.cells[std::size_t(open.x) + std::size_t(open.y) * std::size_t(n)] = 0;
    const systems::GridSource source(std::move(grid));
    for (auto _ : state) {
        const glm::ivec2 t = game::find_open_tile(source, {n / 2, n / 2}, 0, n);
        benchmark::DoNotOptimize(t);
        if (t != open) state.SkipWithError("the search missed the open tile");
    }
    state.counters["tiles"] = double(n) * double(n);
    state.counters["ns_per_tile"] = benchmark::Counter(double(n) * double(n),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
}
BENCHMARK(BM_SpawnSearchWorstCase)->Arg(1024)->Arg(4096)->Arg(8192)->Unit(benchmark::kMillisecond);

// A map of n x n cells: 30 % walls, 2 % trees, seeded; written once per size.
std::string map_file(int n) {
    static std::map<int, std::string> files;
    if (auto it = files.find(n); it != files.end()) return it->second;
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("lantern-bench-start-" + std::to_string(n) + ".map");
    std::string text = "type octile\nheight " + std::to_string(n) + "\nwidth " + std::to_string(n) + "\nmap\n";
    text.reserve(text.size() + std::size_t(n + 1) * std::size_t(n));
    std::mt19937 rng{std::uint32_t(n)};
    for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c) {
            const std::uint32_t v = rng() % 100;
            text += v < 30 ? '@' : v < 32 ? 'T' : '.';
        }
        text += '\n';
    }
    if (auto ok = write_file_atomic(path.string(), text); !ok) return {};
    return files[n] = path.string();
}

void BM_CreateWorldFromMap(benchmark::State& state) {
    const int n = int(state.range(0));
    const std::string path = map_file(n);
    if (path.empty()) {
        state.SkipWithError("cannot write the map file");
        return;
    }
    std::size_t entities = 0;
    for (auto _ : state) {
        ecs::World world;
        auto w = game::create_world({game::WorldKind::map, path, 1}, world, {});
        if (!w) {
            state.SkipWithError(w.error().message.c_str());
            return;
        }
        entities = world.alive_count();
    }
    state.counters["entities"] = double(entities);
}
BENCHMARK(BM_CreateWorldFromMap)->Arg(1024)->Arg(4096)->Arg(8192)->Unit(benchmark::kMillisecond)->Iterations(1);

} // namespace
