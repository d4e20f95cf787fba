#include "ecs_test_types.hpp"

#include "lantern/ecs/world.hpp"

#include <gtest/gtest.h>

using namespace ecs_test;
using lantern::ecs::Entity;
using lantern::ecs::World;

TEST(World, EmptyWorld) {
    World w;
    Expected m;
    expect_state(w, m);
    EXPECT_FALSE(w.alive(lantern::ecs::null_entity));
    EXPECT_FALSE(w.alive(Entity{0, 0}));
}

TEST(World, StateAfterEachMutation) {
    World w;
    Expected m;
    Entity a = w.create();
    m.entities[a] = {};
    expect_state(w, m);

    w.emplace<Position>(a, 1.0f, 2.0f);
    m.entities[a].first = Position{1, 2};
    expect_state(w, m);

    Entity b = w.create();
    m.entities[b] = {};
    w.emplace<Name>(b, "bee");
    m.entities[b].second = Name{"bee"};
    expect_state(w, m);

    w.emplace<Velocity>(a, 0.5f, 0.25f);
    m.velocity[a] = Velocity{0.5f, 0.25f};
    expect_state(w, m);

    w.emplace<Position>(b, 3.0f, 4.0f);
    m.entities[b].first = Position{3, 4};
    expect_state(w, m);

    w.get<Position>(a).x = 9.0f;
    m.entities[a].first->x = 9.0f;
    expect_state(w, m);

    w.remove<Position>(a);
    m.entities[a].first.reset();
    expect_state(w, m);

    EXPECT_FALSE(w.try_remove<Position>(a));
    EXPECT_TRUE(w.try_remove<Name>(b));
    m.entities[b].second.reset();
    expect_state(w, m);

    w.destroy(a);
    m.entities.erase(a);
    m.velocity.erase(a);
    expect_state(w, m);
    EXPECT_FALSE(w.alive(a));

    w.emplace_or_replace<Position>(b, 7.0f, 7.0f);
    m.entities[b].first = Position{7, 7};
    expect_state(w, m);

    w.clear<Position>();
    m.entities[b].first.reset();
    expect_state(w, m);
}

TEST(World, GenerationsDetectStaleHandles) {
    World w;
    Entity a = w.create();
    w.emplace<Position>(a);
    w.destroy(a);
    Entity b = w.create(); // reuses the slot
    EXPECT_EQ(b.index, a.index);
    EXPECT_NE(b.generation, a.generation);
    EXPECT_NE(a, b);
    EXPECT_FALSE(w.alive(a));
    EXPECT_TRUE(w.alive(b));
    w.emplace<Position>(b, 5.0f, 5.0f);
    EXPECT_FALSE(w.contains<Position>(a)); // the stale handle never sees b's component
    EXPECT_EQ(w.try_get<Position>(a), nullptr);
    EXPECT_TRUE(w.contains<Position>(b));
}

TEST(World, TagComponents) {
    World w;
    Entity a = w.create(), b = w.create();
    w.emplace<Frozen>(a);
    EXPECT_TRUE(w.contains<Frozen>(a));
    EXPECT_FALSE(w.contains<Frozen>(b));
    int n = 0;
    w.view<Frozen>().each([&](Entity e, Frozen&) {
        EXPECT_EQ(e, a);
        ++n;
    });
    EXPECT_EQ(n, 1);
    w.remove<Frozen>(a);
    EXPECT_EQ(w.count<Frozen>(), 0u);
}

TEST(World, ReservedEntitiesBecomeAliveAtFlush) {
    World w;
    Entity first = w.create();
    Entity r1 = w.reserve();
    Entity r2 = w.reserve();
    EXPECT_FALSE(w.alive(r1));
    EXPECT_NE(r1.index, r2.index);
    EXPECT_NE(r1.index, first.index);
    w.flush_reserved();
    EXPECT_TRUE(w.alive(r1));
    EXPECT_TRUE(w.alive(r2));
    EXPECT_EQ(w.alive_count(), 3u);
    Entity c = w.create();
    EXPECT_NE(c.index, r2.index);
    EXPECT_EQ(w.alive_count(), 4u);
}

TEST(World, ChangeTicks) {
    World w;
    Entity a = w.create(), b = w.create();
    w.emplace<Position>(a);
    w.emplace<Position>(b);
    lantern::ecs::Tick t0 = w.tick();
    w.advance_tick();
    w.patch<Position>(b).x = 3.0f;
    std::vector<Entity> changed, added;
    w.view<Position>().each_changed<Position>(t0, [&](Entity e, Position&) { changed.push_back(e); });
    w.view<Position>().each_added<Position>(t0, [&](Entity e, Position&) { added.push_back(e); });
    EXPECT_EQ(changed, std::vector<Entity>{b});
    EXPECT_TRUE(added.empty());
    EXPECT_GT(w.find_pool<Position>()->last_changed(), t0);
    lantern::ecs::Tick t1 = w.tick();
    w.advance_tick();
    Entity c = w.create();
    w.emplace<Position>(c);
    added.clear();
    w.view<Position>().each_added<Position>(t1, [&](Entity e, Position&) { added.push_back(e); });
    EXPECT_EQ(added, std::vector<Entity>{c});
    EXPECT_EQ(w.find_pool<Position>()->last_removed(), 0u);
    w.destroy(a);
    EXPECT_EQ(w.find_pool<Position>()->last_removed(), w.tick());
}

TEST(World, Resources) {
    World w;
    struct Settings {
        int rounds = 20;
    };
    EXPECT_FALSE(w.has_resource<Settings>());
    EXPECT_EQ(w.try_resource<Settings>(), nullptr);
    w.set_resource<Settings>();
    EXPECT_EQ(w.resource<Settings>().rounds, 20);
    w.resource<Settings>().rounds = 5;
    EXPECT_EQ(w.resource<Settings>().rounds, 5);
    w.set_resource<Settings>(Settings{9});
    EXPECT_EQ(w.resource<Settings>().rounds, 9);
    w.remove_resource<Settings>();
    EXPECT_FALSE(w.has_resource<Settings>());
}

class WorldDeathTest : public ::testing::Test {
  protected:
    void SetUp() override { GTEST_FLAG_SET(death_test_style, "threadsafe"); }
};

TEST_F(WorldDeathTest, GetWithStaleHandle) {
    World w;
    Entity a = w.create();
    w.emplace<Position>(a);
    w.destroy(a);
    w.emplace<Position>(w.create());
    EXPECT_DEATH(w.get<Position>(a), "handle is stale");
}

TEST_F(WorldDeathTest, EmplaceTwice) {
    World w;
    Entity a = w.create();
    w.emplace<Position>(a);
    EXPECT_DEATH(w.emplace<Position>(a), "already has this component");
}

TEST_F(WorldDeathTest, RemoveAbsent) {
    World w;
    Entity a = w.create();
    EXPECT_DEATH(w.remove<Position>(a), "does not have");
}

TEST_F(WorldDeathTest, DestroyTwice) {
    World w;
    Entity a = w.create();
    w.destroy(a);
    EXPECT_DEATH(w.destroy(a), "dead or stale");
}

TEST_F(WorldDeathTest, EmplaceOnDeadEntity) {
    World w;
    Entity a = w.create();
    w.destroy(a);
    EXPECT_DEATH(w.emplace<Position>(a), "dead or stale");
}

TEST_F(WorldDeathTest, StructuralChangeDuringIteration) {
    World w;
    for (int i = 0; i < 4; ++i) w.emplace<Position>(w.create());
    EXPECT_DEATH(w.view<Position>().each([&](Entity e, Position&) { w.remove<Position>(e); }),
                 "while a view iterates");
    EXPECT_DEATH(w.view<Position>().each([&](Entity e, Position&) { w.destroy(e); }), "while a view iterates");
    EXPECT_DEATH(w.view<Position>().each([&](Position&) { w.emplace<Position>(w.create()); }),
                 "while a view iterates");
}

TEST_F(WorldDeathTest, MissingResource) {
    World w;
    struct Missing {};
    EXPECT_DEATH(w.resource<Missing>(), "resource not set");
}
