// lantern-bench-jobs: job system overheads and scaling (issue 2), next to enkiTS and
// Taskflow figures measured on a similar machine (printed first; neither library is
// packaged in Debian, so they are not built here).
#include "bench_main.hpp"

#include "lantern/ecs/schedule.hpp"
#include "lantern/jobs/job_graph.hpp"
#include "lantern/jobs/job_system.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace {

using lantern::jobs::Counter;
using lantern::jobs::JobGraph;
using lantern::jobs::JobSystem;

lantern::bench::Reference reference{
    "Reference (2-core Xeon VM): enkiTS spawn-and-wait of one empty task 235 ns; 1M single-item tasks 211 ms;",
    "  Taskflow 1M-task prebuilt graph 145 ms; both reach 1.86x on 2 threads for a 64M-float sum.",
    "enkiTS 771a087 in one binary with Lantern (lantern-bench-peers, 2-core AMD EPYC VM, 2026-11-25), one worker:",
    "  spawn+wait quiet 67-107 ns (Lantern 25-27), one busy loop per core 114-140 ns (Lantern 37-61);",
    "  1M tasks quiet 58-102 ms (Lantern 14-82), busy 50-110 ms (Lantern 16-28).",
};

JobSystem& system_with(int workers) {
    // One system per worker count, kept for the whole run (a thread may be the main thread
    // of one JobSystem at a time, so they are created lazily and reused).
    static std::unique_ptr<JobSystem> current;
    static int current_workers = -2;
    if (current_workers != workers) {
        current.reset();
        JobSystem::Config c;
        c.worker_threads = workers;
        current = std::make_unique<JobSystem>(c);
        current_workers = workers;
    }
    return *current;
}

int default_workers() { return std::max(0, int(std::thread::hardware_concurrency()) - 1); }

void empty_job(void*, std::uint32_t) {}

void BM_SpawnAndWaitOne(benchmark::State& state) {
    JobSystem& jobs = system_with(int(state.range(0)));
    for (auto _ : state) {
        Counter c;
        jobs.spawn(&empty_job, nullptr, &c);
        jobs.wait(c);
    }
    state.SetItemsProcessed(state.iterations());
}

void BM_MillionSingleTasks(benchmark::State& state) {
    JobSystem& jobs = system_with(int(state.range(0)));
    for (auto _ : state) {
        Counter c;
        for (int i = 0; i < 1'000'000; ++i) jobs.spawn(&empty_job, nullptr, &c);
        jobs.wait(c);
    }
}

void BM_SpawnAndWaitOneContended(benchmark::State& state) {
    JobSystem& jobs = system_with(int(state.range(0)));
    lantern::bench::BusyCores busy;
    for (auto _ : state) {
        Counter c;
        jobs.spawn(&empty_job, nullptr, &c);
        jobs.wait(c);
    }
    state.SetItemsProcessed(state.iterations());
}

void BM_MillionSingleTasksContended(benchmark::State& state) {
    JobSystem& jobs = system_with(int(state.range(0)));
    lantern::bench::BusyCores busy;
    for (auto _ : state) {
        Counter c;
        for (int i = 0; i < 1'000'000; ++i) jobs.spawn(&empty_job, nullptr, &c);
        jobs.wait(c);
    }
}

void BM_MillionNodeGraph(benchmark::State& state) {
    JobSystem& jobs = system_with(int(state.range(0)));
    static JobGraph* graph = [] {
        auto* g = new JobGraph;
        for (int i = 0; i < 1'000'000; ++i) g->add("n", [](std::uint32_t) {});
        g->finalize();
        return g;
    }();
    for (auto _ : state) graph->run(jobs);
}

void BM_LayeredGraph1000x1000(benchmark::State& state) {
    JobSystem& jobs = system_with(int(state.range(0)));
    static JobGraph* graph = [] {
        auto* g = new JobGraph;
        for (int layer = 0; layer < 1000; ++layer)
            for (int i = 0; i < 1000; ++i) {
                auto id = g->add("n", [](std::uint32_t) {});
                if (layer > 0) g->precede(id - 1000, id);
                if (layer > 0 && i > 0) g->precede(id - 1001, id);
            }
        g->finalize();
        return g;
    }();
    for (auto _ : state) graph->run(jobs);
}

void BM_ParallelSum64M(benchmark::State& state) {
    static std::vector<float> data(64u << 20, 1.0f);
    JobSystem& jobs = system_with(int(state.range(0)));
    for (auto _ : state) {
        float s = jobs.parallel_reduce(
            "sum", 0, std::uint32_t(data.size()), 1u << 18, 0.0f,
            [](std::uint32_t b, std::uint32_t e) {
                float acc[8] = {};
                for (std::uint32_t i = b; i < e; i += 8)
                    for (int k = 0; k < 8; ++k) acc[k] += data[i + k];
                float t = 0;
                for (float a : acc) t += a;
                return t;
            },
            [](float a, float b) { return a + b; });
        benchmark::DoNotOptimize(s);
    }
    state.SetBytesProcessed(state.iterations() * std::int64_t(data.size() * sizeof(float)));
}

void BM_GraphFrameOverhead12Nodes(benchmark::State& state) {
    JobSystem& jobs = system_with(int(state.range(0)));
    JobGraph g;
    std::vector<JobGraph::NodeId> ids;
    for (int i = 0; i < 12; ++i) ids.push_back(g.add("system", [](std::uint32_t) {}));
    for (int i = 4; i < 12; ++i) g.precede(ids[i - 4], ids[i]); // three chains of four
    for (auto _ : state) g.run(jobs);
}

struct A {
    int v;
};
struct B {
    int v;
};
struct C {
    int v;
};

void BM_ScheduleFrameOverhead12Systems(benchmark::State& state) {
    JobSystem& jobs = system_with(int(state.range(0)));
    lantern::ecs::World world;
    lantern::ecs::Schedule s(jobs);
    const char* names[] = {"s0", "s1", "s2", "s3", "s4", "s5", "s6", "s7", "s8", "s9", "s10", "s11"};
    for (int i = 0; i < 12; ++i) {
        auto b = s.add(names[i], [](lantern::ecs::SystemContext&) {});
        if (i % 3 == 0) b.writes<A>();
        if (i % 3 == 1) b.writes<B>().reads<A>();
        if (i % 3 == 2) b.reads<C>();
    }
    for (auto _ : state) s.run(world);
}

} // namespace

const int W = default_workers();
BENCHMARK(BM_SpawnAndWaitOne)->Arg(0)->Arg(W)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_SpawnAndWaitOneContended)->Arg(0)->Arg(W)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_MillionSingleTasks)->Arg(0)->Arg(W)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_MillionSingleTasksContended)->Arg(0)->Arg(W)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_MillionNodeGraph)->Arg(0)->Arg(W)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_LayeredGraph1000x1000)->Arg(0)->Arg(W)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_ParallelSum64M)->DenseRange(0, W)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_GraphFrameOverhead12Nodes)->Arg(0)->Arg(W)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScheduleFrameOverhead12Systems)->Arg(0)->Arg(W)->Unit(benchmark::kMicrosecond);
