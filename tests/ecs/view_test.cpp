#include "ecs_test_types.hpp"

#include "lantern/ecs/view.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <random>

using namespace ecs_test;
using lantern::ecs::Entity;
using lantern::ecs::exclude;
using lantern::ecs::World;

namespace {
struct Health {
    int hp = 100;
};
} // namespace

TEST(View, OneTwoThreeComponentsAndExclusions) {
    World w;
    std::vector<Entity> all;
    for (int i = 0; i < 100; ++i) {
        Entity e = w.create();
        all.push_back(e);
        w.emplace<Position>(e, float(i), 0.0f);
        if (i % 2 == 0) w.emplace<Velocity>(e, 1.0f, 0.0f);
        if (i % 3 == 0) w.emplace<Health>(e);
        if (i % 5 == 0) w.emplace<Frozen>(e);
    }
    auto count = [](auto view) {
        int n = 0;
        view.each([&](auto&...) { ++n; });
        return n;
    };
    EXPECT_EQ(count(w.view<Position>()), 100);
    EXPECT_EQ(count(w.view<Position, Velocity>()), 50);
    EXPECT_EQ(count(w.view<Position, Velocity, Health>()), 17); // multiples of 6 in [0,100)
    EXPECT_EQ(count(w.view<Position, Velocity>(exclude<Frozen>)), 40);
    EXPECT_EQ(count(w.view<Position>(exclude<Velocity, Health>)), 33);
    // The argument order follows the type order, whichever pool leads.
    w.view<Health, Position>().each([](Entity, Health& h, Position& p) {
        EXPECT_EQ(h.hp, 100);
        EXPECT_EQ(int(p.x) % 3, 0);
    });
    EXPECT_TRUE((w.view<Position, Velocity>().contains(all[2])));
    EXPECT_FALSE((w.view<Position, Velocity>().contains(all[1])));
    EXPECT_FALSE((w.view<Position, Velocity>(exclude<Frozen>).contains(all[10])));
}

TEST(View, MisalignedPoolsStillMatch) {
    // Velocity added in reverse order: the same-position hint fails and the sparse path runs.
    World w;
    std::vector<Entity> es;
    for (int i = 0; i < 1000; ++i) {
        es.push_back(w.create());
        w.emplace<Position>(es.back(), float(i), 0.0f);
    }
    for (int i = 999; i >= 0; i -= 3) w.emplace<Velocity>(es[i], float(i), 0.0f);
    int n = 0;
    w.view<Position, Velocity>().each([&](Position& p, Velocity& v) {
        EXPECT_EQ(p.x, v.dx);
        ++n;
    });
    EXPECT_EQ(n, 334);
}

TEST(View, ParEachMatchesEach) {
    lantern::jobs::JobSystem::Config config;
    config.worker_threads = 2;
    lantern::jobs::JobSystem jobs(config);
    World w;
    std::mt19937 rng(3);
    for (int i = 0; i < 50000; ++i) {
        Entity e = w.create();
        w.emplace<Position>(e, float(i), 0.0f);
        if (rng() % 4) w.emplace<Velocity>(e, 2.0f, 1.0f);
    }
    w.view<Position, Velocity>().par_each(jobs, 1024, [](Position& p, const Velocity& v) {
        p.x += v.dx;
        p.y += v.dy;
    });
    int moved = 0;
    w.view<Position>().each([&](Entity e, Position& p) {
        bool has_v = w.contains<Velocity>(e);
        EXPECT_EQ(p.y, has_v ? 1.0f : 0.0f);
        moved += has_v;
    });
    EXPECT_EQ(moved, int(w.count<Velocity>()));
    std::atomic<int> seen{0};
    w.view<Position, Velocity>().par_each(jobs, 100, [&](Entity e, Position&, Velocity&) {
        EXPECT_TRUE(w.alive(e));
        seen.fetch_add(1);
    });
    EXPECT_EQ(seen.load(), moved);
}

TEST(View, EmptyAndMissingPools) {
    World w;
    int n = 0;
    w.view<Position, Velocity>().each([&](Position&, Velocity&) { ++n; });
    w.view<Position>(exclude<Name>).each([&](Position&) { ++n; });
    EXPECT_EQ(n, 0);
    EXPECT_EQ(w.view<Position>().size_hint(), 0u);
}

TEST(View, PatchEachMarksEveryVisitedComponent) {
    lantern::jobs::JobSystem::Config config;
    config.worker_threads = 1;
    lantern::jobs::JobSystem jobs(config);
    World w;
    for (int i = 0; i < 5000; ++i) {
        Entity e = w.create();
        w.emplace<Position>(e);
        if (i % 2) w.emplace<Velocity>(e);
    }
    auto t0 = w.tick();
    w.advance_tick();
    w.view<Position, Velocity>().patch_each<Position>([](Position& p, Velocity&) { p.x = 1; });
    int changed = 0;
    w.view<Position>().each_changed<Position>(t0, [&](Position& p) {
        EXPECT_EQ(p.x, 1.0f);
        ++changed;
    });
    EXPECT_EQ(changed, 2500);
    EXPECT_EQ(w.find_pool<Position>()->last_changed(), w.tick());
    auto t1 = w.tick();
    w.advance_tick();
    w.view<Velocity>().par_patch_each<Velocity>(jobs, 64, [](Velocity& v) { v.dx = 2; });
    int changed_v = 0;
    w.view<Velocity>().each_changed<Velocity>(t1, [&](Velocity&) { ++changed_v; });
    EXPECT_EQ(changed_v, 2500);
    int changed_p = 0;
    w.view<Position>().each_changed<Position>(t1, [&](Position&) { ++changed_p; });
    EXPECT_EQ(changed_p, 0);
}
