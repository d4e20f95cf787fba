// 100,000 random operations on a World, checked against a simple map-based model.
#include "ecs_test_types.hpp"

#include "lantern/ecs/command_buffer.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace ecs_test;
using lantern::ecs::Entity;
using lantern::ecs::World;

TEST(WorldRandomized, HundredThousandOperationsMatchModel) {
    World w;
    Expected m;
    std::vector<Entity> alive, dead;
    std::mt19937 rng(12345);
    auto pick = [&](std::vector<Entity>& v) { return v[rng() % v.size()]; };
    auto check_entity = [&](Entity e) {
        const auto& c = m.entities.at(e);
        ASSERT_TRUE(w.alive(e));
        ASSERT_EQ(w.contains<Position>(e), c.first.has_value());
        if (c.first) {
            ASSERT_EQ(w.get<Position>(e), *c.first);
        }
        ASSERT_EQ(w.contains<Name>(e), c.second.has_value());
        if (c.second) {
            ASSERT_EQ(w.get<Name>(e), *c.second);
        }
        ASSERT_EQ(w.contains<Velocity>(e), m.velocity.count(e) == 1);
    };
    constexpr int operations = 100000;
    for (int op = 0; op < operations; ++op) {
        int kind = int(rng() % 100);
        if (alive.empty() || kind < 20) {
            Entity e = w.create();
            alive.push_back(e);
            m.entities[e] = {};
            check_entity(e);
        } else if (kind < 30) {
            std::size_t i = rng() % alive.size();
            Entity e = alive[i];
            w.destroy(e);
            alive[i] = alive.back();
            alive.pop_back();
            m.entities.erase(e);
            m.velocity.erase(e);
            dead.push_back(e);
            ASSERT_FALSE(w.alive(e));
        } else if (kind < 45) {
            Entity e = pick(alive);
            Position p{float(rng() % 1000), float(op)};
            if (m.entities[e].first) w.get<Position>(e) = p;
            else w.emplace<Position>(e, p);
            m.entities[e].first = p;
            check_entity(e);
        } else if (kind < 55) {
            Entity e = pick(alive);
            bool had = m.entities[e].first.has_value();
            ASSERT_EQ(w.try_remove<Position>(e), had);
            m.entities[e].first.reset();
            check_entity(e);
        } else if (kind < 65) {
            Entity e = pick(alive);
            Name n{"name" + std::to_string(rng() % 50)};
            w.emplace_or_replace<Name>(e, n);
            m.entities[e].second = n;
            check_entity(e);
        } else if (kind < 70) {
            Entity e = pick(alive);
            if (m.entities[e].second) {
                w.remove<Name>(e);
                m.entities[e].second.reset();
            }
            check_entity(e);
        } else if (kind < 82) {
            Entity e = pick(alive);
            Velocity v{float(op % 13), 1.0f};
            w.emplace_or_replace<Velocity>(e, v);
            m.velocity[e] = v;
            check_entity(e);
        } else if (kind < 87) {
            Entity e = pick(alive);
            w.try_remove<Velocity>(e);
            m.velocity.erase(e);
            check_entity(e);
        } else if (kind < 92 && !dead.empty()) {
            // Stale handles are detected, never aliased to the slot's new entity.
            Entity e = pick(dead);
            ASSERT_FALSE(w.alive(e));
            ASSERT_FALSE(w.contains<Position>(e));
            ASSERT_FALSE(w.contains<Name>(e));
            ASSERT_EQ(w.try_get<Velocity>(e), nullptr);
        } else {
            // A deferred batch through a command buffer.
            lantern::ecs::CommandBuffer cb(w);
            Entity e = pick(alive);
            Entity fresh = cb.create();
            cb.emplace<Position>(fresh, 1.0f, float(op));
            cb.emplace<Velocity>(e, 2.0f, 2.0f);
            cb.apply();
            alive.push_back(fresh);
            m.entities[fresh] = {Position{1.0f, float(op)}, std::nullopt};
            m.velocity[e] = Velocity{2.0f, 2.0f};
            check_entity(fresh);
            check_entity(e);
        }
        if (op % 500 == 0 || op == operations - 1) {
            expect_state(w, m);
            if (HasFatalFailure()) FAIL() << "state mismatch after operation " << op;
        }
        if (HasFatalFailure()) FAIL() << "mismatch at operation " << op;
    }
}
