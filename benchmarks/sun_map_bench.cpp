// The sun's grid shadows, by the DDA and by the shadow map (gi.sun_shadow_method), on the C++
// reference: every start point the directional pass asks (ground texel centres, points just
// outside wall faces) of a GI window over a walled world, for a low, a middle and a high
// sun. Also what building the map costs (once per directional pass). docs/gi.md, "The sun's
// shadow map", quotes these; compare the two methods within one run.
#include "bench_main.hpp"

#include "lantern/gi/reference.hpp"
#include "lantern/gi/sun_map.hpp"

#include <benchmark/benchmark.h>

#include <glm/geometric.hpp>

#include <cstdint>
#include <random>
#include <vector>

namespace {

using namespace lantern;

// A cave world 256 x 256 (45 % walls, smoothed), a 672 x 384 texel window at giRes 8 in the
// middle, one sun whose height is the benchmark's argument (tenths of its slope).
struct SunFixture {
    scene::Scene scene;
    gi::FrameInputs in;
    std::vector<glm::vec2> starts;

    explicit SunFixture(int slope_tenths) {
        const int n = 256;
        scene.walls.width = scene.walls.height = n;
        scene.walls.cells.assign(std::size_t(n) * n, 0);
        std::mt19937 rng(7);
        for (auto& c : scene.walls.cells) c = rng() % 100 < 45 ? 1 : 0;
        for (int pass = 0; pass < 4; ++pass) {
            std::vector<std::uint8_t> next(scene.walls.cells);
            for (int z = 1; z < n - 1; ++z)
                for (int x = 1; x < n - 1; ++x) {
                    int walls = 0;
                    for (int dz = -1; dz <= 1; ++dz)
                        for (int dx = -1; dx <= 1; ++dx) walls += scene.walls.cells[std::size_t((z + dz) * n + x + dx)];
                    next[std::size_t(z * n + x)] = walls >= 5 ? 1 : 0;
                }
            scene.walls.cells = next;
        }
        scene.wall_height = 2.0f;
        scene.view = scene::OrthoView{{128.0f, 128.0f}, {60.0f, 33.75f}};
        scene::DirectionalLight sun;
        sun.direction = glm::normalize(glm::vec3(0.8f, -0.1f * float(slope_tenths), 0.45f));
        scene.directional_lights.push_back(sun);
        auto window = gi::compute_window(scene.view, scene.gi);
        in = gi::gather_frame_inputs(scene, *window);
        const gi::GiWindow& w = in.window;
        for (int y = 0; y < w.height; ++y)
            for (int x = 0; x < w.width; ++x) {
                const glm::vec2 p = w.texel_center(x, y);
                if (!in.walls.is_wall(int(std::floor(p.x)), int(std::floor(p.y)))) starts.push_back(p);
            }
    }
};

void BM_SunShadowDda(benchmark::State& state) {
    const SunFixture f(int(state.range(0)));
    const gi::GpuDirectionalLight& sun = f.in.directional_lights[0];
    const float max_distance = sun.direction_base.w * sun.color_multiplier.w;
    for (auto _ : state) {
        float lit = 0.0f;
        for (glm::vec2 p : f.starts)
            lit += gi::directional_shadow_dda(f.in.walls, p, glm::vec3(sun.direction_base), max_distance, f.in.wall_height);
        benchmark::DoNotOptimize(lit);
    }
    state.counters["per_texel"] = benchmark::Counter(double(f.starts.size()), benchmark::Counter::kIsIterationInvariantRate |
                                                                                    benchmark::Counter::kInvert);
}

void BM_SunShadowMap(benchmark::State& state) {
    const SunFixture f(int(state.range(0)));
    const gi::GpuDirectionalLight& sun = f.in.directional_lights[0];
    const std::vector<gi::SunMap> maps = gi::build_sun_maps(f.in);
    for (auto _ : state) {
        float lit = 0.0f;
        for (glm::vec2 p : f.starts) lit += gi::sun_map_visibility(maps[0], f.in.walls, sun, p, f.in.wall_height);
        benchmark::DoNotOptimize(lit);
    }
    state.counters["per_texel"] = benchmark::Counter(double(f.starts.size()), benchmark::Counter::kIsIterationInvariantRate |
                                                                                    benchmark::Counter::kInvert);
    state.counters["map_tiles"] = double(maps[0].entries.size());
}

void BM_SunMapBuild(benchmark::State& state) {
    const SunFixture f(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(gi::build_sun_maps(f.in));
}

} // namespace

// Slopes 0.1 (a sun 6 degrees above the horizon: long shadows), 0.5 and 2.0 (high).
BENCHMARK(BM_SunShadowDda)->Arg(1)->Arg(5)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SunShadowMap)->Arg(1)->Arg(5)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SunMapBuild)->Arg(1)->Arg(5)->Arg(20)->Unit(benchmark::kMillisecond);
