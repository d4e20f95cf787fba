// lantern-bench-ecs: the ECS operations of issue 2, per 1M entities, for Lantern's sparse-set
// World next to an archetype-table prototype (archetype_prototype.hpp), to justify the
// storage choice (docs/ecs.md). EnTT figures are printed first for comparison (EnTT is not
// packaged in Debian, so it is not built here; lantern-bench-peers, benchmarks/peers/, puts
// Lantern and EnTT in one binary when a checkout is at hand).
#include "archetype_prototype.hpp"
#include "bench_main.hpp"

#include "lantern/ecs/world.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <vector>

namespace {

using lantern::ecs::Entity;
using lantern::ecs::World;
using lantern::bench::ArchetypeWorld;

struct Position {
    std::uint64_t x = 0, y = 0;
};
struct Velocity {
    std::uint64_t x = 0, y = 0;
};
struct Extra {
    std::uint64_t x = 0, y = 0;
};

constexpr std::uint32_t N = 1'000'000;

lantern::bench::Reference reference{
    "EnTT v3.16 reference (2-core Xeon 2.5 GHz VM, g++ 12 -O2), ms per 1M entities:",
    "  create with 2 components 108 | view<P> 2.6 | view<P,V> 7.9 (owning group 3.4) | view<P,V,E> 14.7",
    "  add then remove one component 55 | get by shuffled handle 114 | destroy 89",
    "EnTT 4.0.0 in one binary with Lantern (lantern-bench-peers, 2-core AMD EPYC VM, 2026-11-25), ms, medians:",
    "  create with 2 components 72-101 (Lantern 92-116, noisy) | registry.get shuffled 121-134 (Lantern",
    "  World::get 87) | storage.get shuffled 33-35 (Lantern pool.get 35-38) | view<P,V> 3.9 (Lantern 2.9)",
};

void make_world(World& w, std::vector<Entity>* out, bool third = false) {
    if (out) out->reserve(N);
    for (std::uint32_t i = 0; i < N; ++i) {
        Entity e = w.create();
        w.emplace<Position>(e);
        w.emplace<Velocity>(e);
        if (third) w.emplace<Extra>(e);
        if (out) out->push_back(e);
    }
}

// ---- Lantern (sparse sets)

void BM_Lantern_Create2(benchmark::State& state) {
    for (auto _ : state) {
        auto* w = new World;
        make_world(*w, nullptr);
        benchmark::DoNotOptimize(w);
        state.PauseTiming();
        delete w;
        state.ResumeTiming();
    }
}

void BM_Lantern_Iterate1(benchmark::State& state) {
    World w;
    make_world(w, nullptr, true);
    for (auto _ : state) w.view<Position>().each([](Position& p) { p.x = 0; });
}

void BM_Lantern_Iterate2(benchmark::State& state) {
    World w;
    make_world(w, nullptr, true);
    for (auto _ : state) w.view<Position, Velocity>().each([](Position& p, Velocity& v) { p.x = v.x = 0; });
}

void BM_Lantern_Iterate3(benchmark::State& state) {
    World w;
    make_world(w, nullptr, true);
    for (auto _ : state)
        w.view<Position, Velocity, Extra>().each([](Position& p, Velocity& v, Extra& e) { p.x = v.x = e.x = 0; });
}

void BM_Lantern_Iterate2WithEntity(benchmark::State& state) {
    World w;
    make_world(w, nullptr, true);
    std::uint64_t sink = 0;
    for (auto _ : state)
        w.view<Position, Velocity>().each([&](Entity e, Position& p, Velocity& v) {
            p.x = v.x = 0;
            sink += e.generation;
        });
    benchmark::DoNotOptimize(sink);
}

void BM_Lantern_AddRemove(benchmark::State& state) {
    World w;
    std::vector<Entity> es;
    make_world(w, &es);
    for (auto _ : state) {
        for (Entity e : es) w.emplace<Extra>(e);
        for (Entity e : es) w.remove<Extra>(e);
    }
}

void BM_Lantern_GetShuffled(benchmark::State& state) {
    World w;
    std::vector<Entity> es;
    make_world(w, &es);
    std::shuffle(es.begin(), es.end(), std::mt19937(42));
    for (auto _ : state) {
        std::uint64_t sum = 0;
        for (Entity e : es) sum += w.get<Position>(e).x;
        benchmark::DoNotOptimize(sum);
    }
}

// The hot-loop form: the pool fetched once (EnTT's registry.storage<T>()), then get by handle.
void BM_Lantern_GetShuffledPool(benchmark::State& state) {
    World w;
    std::vector<Entity> es;
    make_world(w, &es);
    std::shuffle(es.begin(), es.end(), std::mt19937(42));
    auto& pool = w.assure<Position>();
    for (auto _ : state) {
        std::uint64_t sum = 0;
        for (Entity e : es) sum += pool.get(e).x;
        benchmark::DoNotOptimize(sum);
    }
}

void BM_Lantern_Destroy(benchmark::State& state) {
    for (auto _ : state) {
        state.PauseTiming();
        auto* w = new World;
        std::vector<Entity> es;
        make_world(*w, &es);
        state.ResumeTiming();
        for (Entity e : es) w->destroy(e);
        state.PauseTiming();
        delete w;
        state.ResumeTiming();
    }
}

// ---- Archetype-table prototype (same operations)

ArchetypeWorld* make_archetype_world(std::vector<ArchetypeWorld::Entity>* out, bool third = false) {
    auto* w = new ArchetypeWorld;
    w->register_type<Position>();
    w->register_type<Velocity>();
    w->register_type<Extra>();
    for (std::uint32_t i = 0; i < N; ++i) {
        auto e = third ? w->create(Position{}, Velocity{}, Extra{}) : w->create(Position{}, Velocity{});
        if (out) out->push_back(e);
    }
    return w;
}

void BM_Archetype_Create2(benchmark::State& state) {
    for (auto _ : state) {
        auto* w = make_archetype_world(nullptr);
        state.PauseTiming();
        delete w;
        state.ResumeTiming();
    }
}

void BM_Archetype_Iterate1(benchmark::State& state) {
    std::unique_ptr<ArchetypeWorld> w(make_archetype_world(nullptr, true));
    for (auto _ : state) w->each<Position>([](Position& p) { p.x = 0; });
}

void BM_Archetype_Iterate2(benchmark::State& state) {
    std::unique_ptr<ArchetypeWorld> w(make_archetype_world(nullptr, true));
    for (auto _ : state) w->each<Position, Velocity>([](Position& p, Velocity& v) { p.x = v.x = 0; });
}

void BM_Archetype_Iterate3(benchmark::State& state) {
    std::unique_ptr<ArchetypeWorld> w(make_archetype_world(nullptr, true));
    for (auto _ : state)
        w->each<Position, Velocity, Extra>([](Position& p, Velocity& v, Extra& e) { p.x = v.x = e.x = 0; });
}

void BM_Archetype_AddRemove(benchmark::State& state) {
    std::vector<ArchetypeWorld::Entity> es;
    std::unique_ptr<ArchetypeWorld> w(make_archetype_world(&es));
    for (auto _ : state) {
        for (auto e : es) w->add(e, Extra{});
        for (auto e : es) w->remove<Extra>(e);
    }
}

void BM_Archetype_GetShuffled(benchmark::State& state) {
    std::vector<ArchetypeWorld::Entity> es;
    std::unique_ptr<ArchetypeWorld> w(make_archetype_world(&es));
    std::shuffle(es.begin(), es.end(), std::mt19937(42));
    for (auto _ : state) {
        std::uint64_t sum = 0;
        for (auto e : es) sum += w->get<Position>(e)->x;
        benchmark::DoNotOptimize(sum);
    }
}

void BM_Archetype_Destroy(benchmark::State& state) {
    for (auto _ : state) {
        state.PauseTiming();
        std::vector<ArchetypeWorld::Entity> es;
        auto* w = make_archetype_world(&es);
        state.ResumeTiming();
        for (auto e : es) w->destroy(e);
        state.PauseTiming();
        delete w;
        state.ResumeTiming();
    }
}

} // namespace

#define LANTERN_ECS_BENCH(fn) BENCHMARK(fn)->Unit(benchmark::kMillisecond)->MinTime(0.5)
LANTERN_ECS_BENCH(BM_Lantern_Create2);
LANTERN_ECS_BENCH(BM_Archetype_Create2);
LANTERN_ECS_BENCH(BM_Lantern_Iterate1);
LANTERN_ECS_BENCH(BM_Archetype_Iterate1);
LANTERN_ECS_BENCH(BM_Lantern_Iterate2);
LANTERN_ECS_BENCH(BM_Lantern_Iterate2WithEntity);
LANTERN_ECS_BENCH(BM_Archetype_Iterate2);
LANTERN_ECS_BENCH(BM_Lantern_Iterate3);
LANTERN_ECS_BENCH(BM_Archetype_Iterate3);
LANTERN_ECS_BENCH(BM_Lantern_AddRemove);
LANTERN_ECS_BENCH(BM_Archetype_AddRemove);
LANTERN_ECS_BENCH(BM_Lantern_GetShuffled);
LANTERN_ECS_BENCH(BM_Lantern_GetShuffledPool);
LANTERN_ECS_BENCH(BM_Archetype_GetShuffled);
LANTERN_ECS_BENCH(BM_Lantern_Destroy);
LANTERN_ECS_BENCH(BM_Archetype_Destroy);
