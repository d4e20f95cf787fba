#include "ecs_test_types.hpp"

#include "lantern/ecs/schedule.hpp"

#include <gtest/gtest.h>

using namespace ecs_test;
using lantern::ecs::Entity;
using lantern::ecs::Schedule;
using lantern::ecs::SystemContext;
using lantern::ecs::World;

namespace {
struct Gravity {
    float g = -1.0f;
};
struct Stats {
    int moved = 0;
    int changed_seen = 0;
};

lantern::jobs::JobSystem::Config workers(int n) {
    lantern::jobs::JobSystem::Config c;
    c.worker_threads = n;
    return c;
}

void add_systems(Schedule& s) {
    s.add("apply_gravity", [](SystemContext& ctx) {
         float g = ctx.world.resource<Gravity>().g;
         ctx.world.view<Velocity>().each([&](Velocity& v) { v.dy += g; });
     })
        .reads_resource<Gravity>()
        .writes<Velocity>();
    s.add("integrate", [](SystemContext& ctx) {
         ctx.world.view<Position, Velocity>().par_each(ctx.jobs, 512, [](Position& p, const Velocity& v) {
             p.x += v.dx;
             p.y += v.dy;
         });
     })
        .reads<Velocity>()
        .writes<Position>();
    s.add("rename", [](SystemContext& ctx) {
         ctx.world.view<Name>().patch_each<Name>([](Name& n) { n.value += "!"; });
     }).writes<Name>();
    s.add("spawn_and_reap", [](SystemContext& ctx) {
         ctx.world.view<Position>().each([&](Entity e, Position& p) {
             if (p.y < -5.0f) ctx.commands().destroy(e);
         });
         Entity child = ctx.commands().create();
         ctx.commands().emplace<Position>(child, 0.0f, 0.0f);
     }).reads<Position>();
    s.add("count_changes", [](SystemContext& ctx) {
         auto& stats = ctx.world.resource<Stats>();
         ctx.world.view<Name>().each_changed<Name>(ctx.last_run, [&](Name&) { ++stats.changed_seen; });
     })
        .reads<Name>()
        .writes_resource<Stats>();
}

std::vector<std::pair<float, float>> simulate(int worker_count) {
    lantern::jobs::JobSystem jobs(workers(worker_count));
    World w;
    w.set_resource<Gravity>();
    w.set_resource<Stats>();
    for (int i = 0; i < 3000; ++i) {
        Entity e = w.create();
        w.emplace<Position>(e, float(i), float(i % 7));
        if (i % 2) w.emplace<Velocity>(e, 0.5f, 0.0f);
        if (i % 100 == 0) w.emplace<Name>(e, "n");
    }
    Schedule s(jobs);
    add_systems(s);
    for (int frame = 0; frame < 10; ++frame) s.run(w);
    std::vector<std::pair<float, float>> out;
    w.view<Position>().each([&](Entity e, Position& p) { out.push_back({float(e.index), p.x + 1000 * p.y}); });
    std::sort(out.begin(), out.end());
    out.push_back({float(w.alive_count()), float(w.resource<Stats>().changed_seen)});
    return out;
}

} // namespace

TEST(Schedule, OrdersConflictingSystemsOnly) {
    lantern::jobs::JobSystem jobs(workers(1));
    Schedule s(jobs);
    add_systems(s);
    auto idx = [&](const char* n) { return s.index_of(n); };
    EXPECT_TRUE(s.ordered(idx("apply_gravity"), idx("integrate")));      // Velocity: write then read
    EXPECT_TRUE(s.ordered(idx("integrate"), idx("spawn_and_reap")));     // Position
    EXPECT_TRUE(s.ordered(idx("rename"), idx("count_changes")));         // Name
    EXPECT_FALSE(s.ordered(idx("apply_gravity"), idx("rename")));        // independent
    EXPECT_FALSE(s.ordered(idx("rename"), idx("integrate")));
    EXPECT_FALSE(s.ordered(idx("spawn_and_reap"), idx("count_changes")));
}

TEST(Schedule, SameResultForAnyWorkerCount) {
    auto serial = simulate(0);
    EXPECT_EQ(simulate(1), serial);
    EXPECT_EQ(simulate(2), serial);
    // 30 named entities renamed each frame, each change seen once per frame.
    EXPECT_EQ(serial.back().second, 30.0f * 10.0f);
}

TEST(Schedule, CommandsApplyAtTheSyncPointAndTickAdvances) {
    lantern::jobs::JobSystem jobs(workers(1));
    World w;
    Schedule s(jobs);
    std::uint32_t seen_during = 0;
    s.add("spawner", [&](SystemContext& ctx) {
        seen_during = ctx.world.alive_count();
        ctx.commands().emplace<Name>(ctx.commands().create(), "x");
    });
    auto t0 = w.tick();
    s.run(w);
    EXPECT_EQ(seen_during, 0u);
    EXPECT_EQ(w.alive_count(), 1u);
    EXPECT_EQ(w.tick(), t0 + 1);
    s.run(w);
    EXPECT_EQ(seen_during, 1u);
    EXPECT_EQ(w.count<Name>(), 2u);
}

#if defined(LANTERN_ENABLE_ASSERTS)
// Declared access is enforced: touching an undeclared component or resource, or writing
// one declared only as read, stops with the system's name and the type.
TEST(ScheduleDeathTest, UndeclaredAccessStopsWithTheSystemsName) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    auto run_one = [](auto declare, auto body) {
        lantern::jobs::JobSystem jobs(workers(0));
        World w;
        w.set_resource<Gravity>();
        const Entity e = w.create();
        w.emplace<Position>(e);
        Schedule s(jobs);
        declare(s.add("sneaky", [&, e](SystemContext& ctx) { body(ctx.world, e); }));
        s.run(w);
    };
    EXPECT_DEATH(run_one([](auto b) { b.template reads<Velocity>(); },
                         [](World& w, Entity) { w.view<Position>().each([](Position&) {}); }),
                 "system 'sneaky' touches component ecs_test::Position without declaring it");
    EXPECT_DEATH(run_one([](auto) {}, [](World& w, Entity) { (void)w.resource<Gravity>(); }),
                 "system 'sneaky' touches resource .*Gravity without declaring it: add .reads_resource");
    EXPECT_DEATH(run_one([](auto b) { b.template reads<Position>(); },
                         [](World& w, Entity e) { w.patch<Position>(e).x = 1.0f; }),
                 "system 'sneaky' writes component ecs_test::Position without declaring it: add .writes");
}

TEST(Schedule, DeclaredAccessPassesAndOutsideSystemsNothingIsChecked) {
    lantern::jobs::JobSystem jobs(workers(1));
    World w;
    w.set_resource<Gravity>();
    const Entity e = w.create();
    w.emplace<Position>(e);
    Schedule s(jobs);
    s.add("declared", [e](SystemContext& ctx) {
        ctx.world.patch<Position>(e).x += ctx.world.resource<Gravity>().g;
    }).writes<Position>().reads_resource<Gravity>();
    s.run(w);
    EXPECT_EQ(w.get<Position>(e).x, -1.0f); // and this access, outside any system, is not checked
}
#endif
