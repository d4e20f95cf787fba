// lantern-bench-peers: Lantern's job system and ECS beside enkiTS and EnTT in one binary,
// built only when LANTERN_PEERS_DIR names a folder holding checkouts of both (they are not
// packaged in Debian and their code stays out of the tree; see benchmarks/peers/README.md).
// Same machine, same run, same compiler flags: compare the rows' ratios, not the figures.
#include "../bench_main.hpp"

#include "lantern/ecs/world.hpp"
#include "lantern/jobs/job_system.hpp"

#include <TaskScheduler.h>
#include <benchmark/benchmark.h>
#include <entt/entt.hpp>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

namespace {

using lantern::bench::BusyCores;

// ---- jobs: one worker thread beside the calling thread in both systems

lantern::jobs::JobSystem& lantern_jobs() {
    static lantern::jobs::JobSystem jobs{lantern::jobs::JobSystem::Config{1, 2000}};
    return jobs;
}

enki::TaskScheduler& enki_jobs() {
    static enki::TaskScheduler* scheduler = [] {
        auto* s = new enki::TaskScheduler;
        enki::TaskSchedulerConfig config;
        config.numTaskThreadsToCreate = 1;
        s->Initialize(config);
        return s;
    }();
    return *scheduler;
}

void empty_job(void*, std::uint32_t) {}
struct EmptyTask : enki::ITaskSet {
    void ExecuteRange(enki::TaskSetPartition, std::uint32_t) override {}
};

std::unique_ptr<BusyCores> contention(const benchmark::State& state) {
    return state.range(0) ? std::make_unique<BusyCores>() : nullptr;
}

void BM_Lantern_SpawnAndWaitOne(benchmark::State& state) {
    auto& jobs = lantern_jobs();
    auto busy = contention(state);
    for (auto _ : state) {
        lantern::jobs::Counter c;
        jobs.spawn(&empty_job, nullptr, &c);
        jobs.wait(c);
    }
}

void BM_EnkiTS_SpawnAndWaitOne(benchmark::State& state) {
    auto& jobs = enki_jobs();
    auto busy = contention(state);
    EmptyTask task;
    for (auto _ : state) {
        jobs.AddTaskSetToPipe(&task);
        jobs.WaitforTask(&task);
    }
}

void BM_Lantern_MillionTasks(benchmark::State& state) {
    auto& jobs = lantern_jobs();
    auto busy = contention(state);
    for (auto _ : state) {
        lantern::jobs::Counter c;
        for (int i = 0; i < 1'000'000; ++i) jobs.spawn(&empty_job, nullptr, &c);
        jobs.wait(c);
    }
}

void BM_EnkiTS_MillionTasks(benchmark::State& state) {
    auto& jobs = enki_jobs();
    auto busy = contention(state);
    std::vector<EmptyTask> tasks(1'000'000);
    for (auto _ : state) {
        for (auto& t : tasks) jobs.AddTaskSetToPipe(&t);
        jobs.WaitforAll();
    }
}

// ---- ECS: 1M entities with two 16-byte components

struct Position {
    std::uint64_t x = 0, y = 0;
};
struct Velocity {
    std::uint64_t x = 0, y = 0;
};
constexpr std::uint32_t N = 1'000'000;

template <typename E>
std::vector<E> shuffled(std::vector<E> v) {
    std::shuffle(v.begin(), v.end(), std::mt19937(42));
    return v;
}

std::vector<lantern::ecs::Entity> fill(lantern::ecs::World& w) {
    std::vector<lantern::ecs::Entity> es;
    es.reserve(N);
    for (std::uint32_t i = 0; i < N; ++i) {
        auto e = w.create();
        w.emplace<Position>(e);
        w.emplace<Velocity>(e);
        es.push_back(e);
    }
    return es;
}

std::vector<entt::entity> fill(entt::registry& r) {
    std::vector<entt::entity> es;
    es.reserve(N);
    for (std::uint32_t i = 0; i < N; ++i) {
        auto e = r.create();
        r.emplace<Position>(e);
        r.emplace<Velocity>(e);
        es.push_back(e);
    }
    return es;
}

template <typename Registry>
void BM_Create2(benchmark::State& state) {
    for (auto _ : state) {
        auto* r = new Registry;
        fill(*r);
        benchmark::DoNotOptimize(r);
        state.PauseTiming();
        delete r;
        state.ResumeTiming();
    }
}

// World::get and registry.get: the same call in both libraries.
template <typename Registry>
void BM_GetShuffled(benchmark::State& state) {
    Registry r;
    const auto es = shuffled(fill(r));
    for (auto _ : state) {
        std::uint64_t sum = 0;
        for (auto e : es) sum += r.template get<Position>(e).x;
        benchmark::DoNotOptimize(sum);
    }
}

void BM_Lantern_PoolGetShuffled(benchmark::State& state) {
    lantern::ecs::World w;
    const auto es = shuffled(fill(w));
    auto& pool = w.assure<Position>();
    for (auto _ : state) {
        std::uint64_t sum = 0;
        for (auto e : es) sum += pool.get(e).x;
        benchmark::DoNotOptimize(sum);
    }
}

void BM_EnTT_StorageGetShuffled(benchmark::State& state) {
    entt::registry r;
    const auto es = shuffled(fill(r));
    auto& storage = r.storage<Position>();
    for (auto _ : state) {
        std::uint64_t sum = 0;
        for (auto e : es) sum += storage.get(e).x;
        benchmark::DoNotOptimize(sum);
    }
}

template <typename Registry>
void BM_View2(benchmark::State& state) {
    Registry r;
    fill(r);
    for (auto _ : state) r.template view<Position, Velocity>().each([](Position& p, Velocity& v) { p.x = v.x = 0; });
}

lantern::bench::Reference peers{"peers: EnTT " ENTT_VERSION ", enkiTS " LANTERN_ENKITS_COMMIT
                                "; Arg 0 = quiet, 1 = one busy loop per core"};

} // namespace

BENCHMARK(BM_Lantern_SpawnAndWaitOne)->Arg(0)->Arg(1);
BENCHMARK(BM_EnkiTS_SpawnAndWaitOne)->Arg(0)->Arg(1);
BENCHMARK(BM_Lantern_MillionTasks)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EnkiTS_MillionTasks)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Create2<lantern::ecs::World>)->Name("BM_Lantern_Create2")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Create2<entt::registry>)->Name("BM_EnTT_Create2")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GetShuffled<lantern::ecs::World>)->Name("BM_Lantern_GetShuffled")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GetShuffled<entt::registry>)->Name("BM_EnTT_GetShuffled")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Lantern_PoolGetShuffled)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EnTT_StorageGetShuffled)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_View2<lantern::ecs::World>)->Name("BM_Lantern_View2")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_View2<entt::registry>)->Name("BM_EnTT_View2")->Unit(benchmark::kMillisecond);
