#include "ecs_test_types.hpp"

#include "lantern/ecs/schedule.hpp"

#include <gtest/gtest.h>

#include <atomic>

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

// Regression (TSan, stop 36): two independent systems viewed components no entity had yet,
// so each created its pool from a worker thread while the other read the pool table. The
// schedule now makes every declared pool and resource slot before the systems start: a
// system sees them already there, and the table does not grow while systems run.
TEST(Schedule, DeclaredPoolsAndResourceSlotsExistBeforeAnySystemRuns) {
    struct Unused {
        int v = 0;
    };
    struct LaterResource {
        int v = 0;
    };
    lantern::jobs::JobSystem jobs(workers(2));
    World w;
    Schedule s(jobs);
    std::atomic<int> pools_seen{0};
    s.add("views_missing_pools", [&](SystemContext& ctx) {
         if (ctx.world.find_pool<Velocity>() && ctx.world.find_pool<Unused>()) ++pools_seen;
         ctx.world.view<Velocity, Unused>().each([](Velocity&, Unused&) {});
     }).reads<Velocity, Unused>();
    s.add("sets_a_resource", [&](SystemContext& ctx) {
         if (ctx.world.find_pool<Name>()) ++pools_seen;
         ctx.world.set_resource<LaterResource>(LaterResource{7});
     })
        .reads<Name>()
        .writes_resource<LaterResource>();
    // Independent systems: nothing orders them, so they may run at the same time.
    ASSERT_FALSE(s.ordered(0, 1));
    ASSERT_EQ(w.find_pool<Unused>(), nullptr);
    s.run(w);
    EXPECT_EQ(pools_seen.load(), 2);
    EXPECT_NE(w.find_pool<Unused>(), nullptr);
    ASSERT_NE(w.try_resource<LaterResource>(), nullptr);
    EXPECT_EQ(w.resource<LaterResource>().v, 7);
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

TEST(ScheduleInspection, EdgesCarryTheirReasonsAndTheReductionDropsImpliedOnes) {
    lantern::jobs::JobSystem jobs(workers(1));
    Schedule s(jobs);
    add_systems(s);
    const lantern::ecs::ScheduleInfo info = s.describe();
    ASSERT_EQ(info.systems.size(), 5u);
    EXPECT_EQ(info.systems[0].name, "apply_gravity");
    ASSERT_EQ(info.systems[0].reads.size(), 1u);
    EXPECT_EQ(info.systems[0].reads[0].type, "Gravity"); // namespaces stripped
    EXPECT_TRUE(info.systems[0].reads[0].resource);
    EXPECT_EQ(info.systems[0].writes[0].type, "Velocity");
    EXPECT_FALSE(info.systems[0].writes[0].resource);
    // Every edge of the job graph is described, with the type that orders it.
    std::size_t graph_edges = 0;
    for (std::uint32_t i = 0; i < s.size(); ++i) graph_edges += s.graph().successors(i).size();
    ASSERT_EQ(info.edges.size(), graph_edges);
    auto edge = [&](const char* a, const char* b) -> const lantern::ecs::ScheduleInfo::Edge* {
        for (const auto& e : info.edges)
            if (e.before == s.index_of(a) && e.after == s.index_of(b)) return &e;
        return nullptr;
    };
    const auto* gi = edge("apply_gravity", "integrate");
    ASSERT_NE(gi, nullptr);
    ASSERT_EQ(gi->conflicts.size(), 1u);
    EXPECT_EQ(gi->conflicts[0].type, "Velocity");
    EXPECT_FALSE(gi->declared);
    EXPECT_FALSE(gi->redundant);
    EXPECT_EQ(edge("apply_gravity", "rename"), nullptr);
    // No two systems write the same type: nothing is ambiguous.
    EXPECT_TRUE(info.ambiguities.empty());
    EXPECT_NE(lantern::ecs::ambiguity_report(info).find("no ambiguities"), std::string::npos);
}

TEST(ScheduleInspection, TwoWritersWithoutAfterAreAmbiguousUntilOneNamesTheOther) {
    lantern::jobs::JobSystem jobs(workers(1));
    for (bool ordered : {false, true}) {
        Schedule s(jobs);
        s.add("a", [](SystemContext&) {}).writes<Position>().writes_resource<Stats>();
        s.add("b", [](SystemContext&) {}).reads<Position>().writes<Velocity>();
        auto c = s.add("c", [](SystemContext&) {});
        c.writes<Position>().reads<Velocity>();
        if (ordered) c.after("b"); // a -> b (Position) -> c: after() chains through b only if declared
        s.add("d", [](SystemContext&) {}).writes_resource<Stats>().after("a");
        const lantern::ecs::ScheduleInfo info = s.describe();
        // a->c is implied by a->b->c in the graph: drawn without it.
        bool found = false;
        for (const auto& e : info.edges)
            if (e.before == 0 && e.after == 2) {
                found = true;
                EXPECT_TRUE(e.redundant);
                EXPECT_EQ(e.conflicts.size(), 1u);
            }
        EXPECT_TRUE(found);
        // a and d both write Stats, but d declares after(a): not ambiguous. a and c both
        // write Position; c's after(b) does not order it after a (b's own order is implied).
        ASSERT_EQ(info.ambiguities.size(), 1u) << ordered;
        EXPECT_EQ(info.ambiguities[0].first, 0u);
        EXPECT_EQ(info.ambiguities[0].second, 2u);
        ASSERT_EQ(info.ambiguities[0].types.size(), 1u);
        EXPECT_EQ(info.ambiguities[0].types[0].type, "Position");
        const std::string report = lantern::ecs::ambiguity_report(info);
        EXPECT_NE(report.find("a / c: both write Position"), std::string::npos) << report;
    }
    // Declaring the order removes the entry.
    Schedule s(jobs);
    s.add("a", [](SystemContext&) {}).writes<Position>();
    s.add("b", [](SystemContext&) {}).writes<Position>().after("a");
    EXPECT_TRUE(s.describe().ambiguities.empty());
}

TEST(ScheduleInspection, DotDrawsEverySystemTheReducedEdgesAndTheAmbiguities) {
    lantern::jobs::JobSystem jobs(workers(1));
    Schedule s(jobs);
    add_systems(s);
    s.add("main \"quoted\"", [](SystemContext&) {}).main_thread().writes<Name>().after("rename");
    s.add("late_writer", [](SystemContext&) {}).writes<Velocity>();
    const lantern::ecs::ScheduleInfo info = s.describe();
    const std::string dot = lantern::ecs::schedule_dot(info, "test schedule");
    EXPECT_EQ(dot.rfind("digraph schedule {", 0), 0u);
    EXPECT_EQ(dot.back(), '\n');
    for (std::size_t i = 0; i < info.systems.size(); ++i)
        EXPECT_NE(dot.find("  s" + std::to_string(i) + " [label="), std::string::npos) << i;
    EXPECT_NE(dot.find("main \\\"quoted\\\""), std::string::npos); // escaped
    EXPECT_NE(dot.find("peripheries=2"), std::string::npos);       // the main-thread system
    EXPECT_NE(dot.find("style=bold"), std::string::npos);          // its after()
    std::size_t drawn = 0, pos = 0;
    while ((pos = dot.find(" -> s", pos)) != std::string::npos) ++drawn, ++pos;
    std::size_t reduced = 0;
    for (const auto& e : info.edges) reduced += e.redundant && !e.declared ? 0 : 1;
    EXPECT_EQ(drawn, reduced + info.ambiguities.size());
    // apply_gravity and late_writer both write Velocity, ordered only by add order.
    ASSERT_EQ(info.ambiguities.size(), 1u);
    EXPECT_NE(dot.find("both write Velocity"), std::string::npos);
    // Balanced braces and quotes: one graph, no quote left open.
    std::size_t quotes = 0;
    for (std::size_t i = 0; i < dot.size(); ++i)
        if (dot[i] == '"' && (i == 0 || dot[i - 1] != '\\')) ++quotes;
    EXPECT_EQ(quotes % 2, 0u);
}
