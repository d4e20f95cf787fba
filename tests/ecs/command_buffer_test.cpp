#include "ecs_test_types.hpp"

#include "lantern/ecs/command_buffer.hpp"

#include <gtest/gtest.h>

#include <memory>

using namespace ecs_test;
using lantern::ecs::CommandBuffer;
using lantern::ecs::CommandQueues;
using lantern::ecs::Entity;
using lantern::ecs::World;

namespace {
struct Tracked {
    static inline int live = 0;
    std::unique_ptr<int> value;
    explicit Tracked(int v) : value(std::make_unique<int>(v)) { ++live; }
    Tracked(Tracked&& o) noexcept : value(std::move(o.value)) { ++live; }
    Tracked& operator=(Tracked&& o) noexcept {
        value = std::move(o.value);
        return *this;
    }
    ~Tracked() { --live; }
};
} // namespace

TEST(CommandBuffer, DeferredUntilApply) {
    World w;
    Expected m;
    Entity a = w.create();
    m.entities[a] = {};
    CommandBuffer cb(w);
    Entity b = cb.create();
    cb.emplace<Position>(b, 1.0f, 2.0f);
    cb.emplace<Name>(b, "deferred");
    cb.emplace<Position>(a, 5.0f, 5.0f);
    cb.emplace<Velocity>(a, 1.0f, 1.0f);
    expect_state(w, m); // nothing visible yet
    EXPECT_EQ(cb.size(), 4u);
    cb.apply();
    m.entities[b] = {Position{1, 2}, Name{"deferred"}};
    m.entities[a].first = Position{5, 5};
    m.velocity[a] = Velocity{1, 1};
    expect_state(w, m);
    EXPECT_TRUE(cb.empty());

    cb.remove<Velocity>(a);
    cb.destroy(b);
    expect_state(w, m);
    cb.apply();
    m.velocity.erase(a);
    m.entities.erase(b);
    expect_state(w, m);
}

TEST(CommandBuffer, LenientAboutWhatOtherBuffersDid) {
    World w;
    Entity a = w.create();
    w.emplace<Position>(a, 1.0f, 1.0f);
    CommandBuffer first(w), second(w);
    first.destroy(a);
    second.destroy(a);                  // already destroyed by `first`: skipped
    second.emplace<Name>(a, "too late"); // on a dead entity: skipped
    second.remove<Velocity>(a);         // absent: skipped
    first.apply();
    second.apply();
    EXPECT_FALSE(w.alive(a));
    EXPECT_EQ(w.alive_count(), 0u);
    EXPECT_EQ(w.count<Name>(), 0u);

    Entity b = w.create();
    w.emplace<Position>(b, 1.0f, 1.0f);
    lantern::ecs::Tick before = w.tick();
    w.advance_tick();
    CommandBuffer cb(w);
    cb.emplace<Position>(b, 9.0f, 9.0f); // replaces, and counts as a change
    cb.apply();
    EXPECT_EQ(w.get<Position>(b), (Position{9, 9}));
    int changed = 0;
    w.view<Position>().each_changed<Position>(before, [&](Position&) { ++changed; });
    EXPECT_EQ(changed, 1);
}

TEST(CommandBuffer, OwnsAndDestroysNonTrivialValues) {
    World w;
    Entity e = w.create();
    {
        CommandBuffer cb(w);
        for (int i = 0; i < 3000; ++i) cb.emplace<Tracked>(e, i); // spans several arena blocks
        EXPECT_EQ(Tracked::live, 3000);
        cb.clear(); // dropped without applying
        EXPECT_EQ(Tracked::live, 0);
        cb.emplace<Tracked>(e, 42);
        cb.apply();
    }
    EXPECT_EQ(Tracked::live, 1); // only the one in the world
    EXPECT_EQ(*w.get<Tracked>(e).value, 42);
    w.destroy(e);
    EXPECT_EQ(Tracked::live, 0);
}

TEST(CommandBuffer, IterationWithDeferredChanges) {
    World w;
    for (int i = 0; i < 100; ++i) w.emplace<Position>(w.create(), float(i), 0.0f);
    CommandBuffer cb(w);
    w.view<Position>().each([&](Entity e, Position& p) {
        if (int(p.x) % 2) cb.destroy(e);
        else cb.emplace<Velocity>(e, p.x, 0.0f);
    });
    cb.apply();
    EXPECT_EQ(w.count<Position>(), 50u);
    EXPECT_EQ(w.count<Velocity>(), 50u);
    w.view<Position, Velocity>().each([](Position& p, Velocity& v) { EXPECT_EQ(p.x, v.dx); });
}

TEST(CommandQueues, PerWorkerBuffersInParallelIteration) {
    lantern::jobs::JobSystem::Config config;
    config.worker_threads = 2;
    lantern::jobs::JobSystem jobs(config);
    World w;
    for (int i = 0; i < 20000; ++i) w.emplace<Position>(w.create(), float(i), 0.0f);
    CommandQueues queues(w, jobs.thread_count());
    w.view<Position>().par_each(jobs, 256, [&](Entity e, Position& p) {
        auto& cb = queues.for_worker(jobs.current_worker());
        if (int(p.x) % 4 == 0) {
            Entity child = cb.create();
            cb.emplace<Name>(child, "child");
            cb.emplace<Position>(child, -p.x, 0.0f);
        } else if (int(p.x) % 4 == 1) {
            cb.destroy(e);
        }
    });
    EXPECT_EQ(w.alive_count(), 20000u);
    queues.apply();
    EXPECT_EQ(w.alive_count(), 20000u - 5000u + 5000u);
    EXPECT_EQ(w.count<Name>(), 5000u);
    EXPECT_EQ(w.count<Position>(), 20000u);
}
