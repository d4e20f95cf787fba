// lantern-bench-frame: CPU cost of the frame's systems (issue 5): per frame with 1k, 10k and
// 100k light entities, static or all flickering; the cost of an unchanged frame (goal:
// under 50 us of CPU and zero GPU passes). The GPU work is excluded by a backend that only
// counts what it is asked to run; BM_UnchangedFrameVulkan checks the real backend submits
// nothing on an unchanged frame.
#include "bench_main.hpp"

#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/systems/gi_frame.hpp"

#include <benchmark/benchmark.h>

#include <random>

namespace {

using namespace lantern;

// Counts passes; does no GPU work (isolates the systems' CPU time).
class CountingBackend final : public gi::Backend {
  public:
    std::string name() const override { return "counting backend"; }
    Result<void> execute(std::uint64_t, const gi::FrameInputs&, const gi::PassPlan&, gi::PassSet run,
                         const gi::WallUpdate&) override {
        for (int p = 0; p < gi::registered_pass_count(); ++p) passes += run.has(gi::Pass(p));
        return {};
    }
    std::vector<gi::FrameTimes> completed_times() override { return {}; }
    std::optional<gi::Texture> read(const std::string&) override { return std::nullopt; }
    std::optional<gi::Image> read_lit() override { return std::nullopt; }
    std::vector<std::string> texture_names() const override { return {}; }
    void wait_idle() override {}
    std::uint64_t passes = 0;
};

struct World {
    jobs::JobSystem jobs;
    ecs::World world;
    std::vector<ecs::Entity> lights;
    CountingBackend* counter = nullptr;
    std::unique_ptr<systems::GiFrame> frame;

    World(int light_count, std::unique_ptr<gi::Backend> backend = nullptr) {
        ecs::Entity cam = world.create();
        world.emplace<Camera>(cam, Camera{scene::OrthoView{{1000.0f, 1000.0f}, {30.0f, 16.875f}}});
        world.emplace<GICache>(cam);
        std::mt19937 rng(1);
        // Spread over 2000 x 2000 tiles: a few dozen reach the window at 100k.
        for (int i = 0; i < light_count; ++i) {
            ecs::Entity e = world.create();
            world.emplace<PointLight>(e, PointLight{{float(rng() % 2000), float(rng() % 2000)}, 1.0f, {1, 0.7f, 0.4f}, 1.0f, 8.0f});
            lights.push_back(e);
        }
        if (!backend) {
            auto c = std::make_unique<CountingBackend>();
            counter = c.get();
            backend = std::move(c);
        }
        systems::GiConfig config;
        config.settings.resolution = 8;
        frame = std::make_unique<systems::GiFrame>(
            world, jobs, std::make_shared<systems::CaveSource>(scene::CaveParams{5, 0.52f}), std::move(backend), config);
        frame->warm_up();
        frame->step(); // first frame: everything runs
    }
};

void BM_StaticLightsFrame(benchmark::State& state) {
    World w(int(state.range(0)));
    const std::uint64_t before = w.counter->passes;
    for (auto _ : state) w.frame->step();
    state.counters["gpu_passes_per_frame"] = double(w.counter->passes - before) / double(state.iterations());
}

void BM_FlickeringLightsFrame(benchmark::State& state) {
    World w(int(state.range(0)));
    std::uint32_t k = 0;
    for (auto _ : state) {
        // Every light flickers: a changed component each, every frame.
        for (ecs::Entity e : w.lights) w.world.patch<PointLight>(e).intensity = 0.9f + 0.1f * float((k + e.index) % 7) / 7.0f;
        ++k;
        w.frame->step();
    }
}

void BM_UnchangedFrameVulkan(benchmark::State& state) {
    auto device = gpu::Device::create();
    if (!device) {
        state.SkipWithError(device.error().message.c_str());
        return;
    }
    auto renderer = gi::vk::Renderer::create(**device);
    {
        World w(1000, gi::make_vulkan_backend(**renderer));
        (*device)->wait_idle();
        const std::uint64_t submitted = (*device)->last_submitted_serial();
        for (auto _ : state) w.frame->step();
        state.counters["gpu_submissions"] = double((*device)->last_submitted_serial() - submitted);
    }
    renderer->reset();
}

} // namespace

BENCHMARK(BM_StaticLightsFrame)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FlickeringLightsFrame)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_UnchangedFrameVulkan)->Unit(benchmark::kMicrosecond);
