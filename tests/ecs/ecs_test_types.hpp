// Component types shared by the ECS tests.
#pragma once

#include "lantern/ecs/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ecs_test {

struct Position {
    float x = 0, y = 0;
    friend bool operator==(const Position&, const Position&) = default;
};
struct Velocity {
    float dx = 0, dy = 0;
    friend bool operator==(const Velocity&, const Velocity&) = default;
};
struct Name {
    std::string value;
    friend bool operator==(const Name&, const Name&) = default;
};
struct Frozen {}; // tag

inline std::vector<lantern::ecs::Entity> sorted(std::vector<lantern::ecs::Entity> v) {
    std::sort(v.begin(), v.end());
    return v;
}

// The whole observable state of a world holding Position, Velocity and Name, compared
// against an expected model after every mutation.
struct Expected {
    std::map<lantern::ecs::Entity, std::pair<std::optional<Position>, std::optional<Name>>> entities;
    std::map<lantern::ecs::Entity, Velocity> velocity;
};

inline void expect_state(lantern::ecs::World& w, const Expected& m) {
    using lantern::ecs::Entity;
    ASSERT_EQ(w.alive_count(), m.entities.size());
    std::vector<Entity> alive;
    w.each_entity([&](Entity e) { alive.push_back(e); });
    std::vector<Entity> expected_alive;
    std::size_t positions = 0, names = 0;
    for (const auto& [e, comps] : m.entities) {
        expected_alive.push_back(e);
        ASSERT_TRUE(w.alive(e));
        ASSERT_EQ(w.contains<Position>(e), comps.first.has_value());
        ASSERT_EQ(w.contains<Name>(e), comps.second.has_value());
        ASSERT_EQ(w.contains<Velocity>(e), m.velocity.count(e) == 1);
        if (comps.first) {
            ASSERT_EQ(w.get<Position>(e), *comps.first);
            ++positions;
        } else {
            ASSERT_EQ(w.try_get<Position>(e), nullptr);
        }
        if (comps.second) {
            ASSERT_EQ(w.get<Name>(e), *comps.second);
            ++names;
        }
        if (m.velocity.count(e)) {
            ASSERT_EQ(w.get<Velocity>(e), m.velocity.at(e));
        }
    }
    ASSERT_EQ(sorted(alive), expected_alive);
    ASSERT_EQ(w.count<Position>(), positions);
    ASSERT_EQ(w.count<Name>(), names);
    ASSERT_EQ(w.count<Velocity>(), m.velocity.size());
    // Views agree with the model.
    std::vector<Entity> pv;
    w.view<Position, Velocity>().each([&](Entity e, Position& p, Velocity& v) {
        ASSERT_EQ(p, *m.entities.at(e).first);
        ASSERT_EQ(v, m.velocity.at(e));
        pv.push_back(e);
    });
    std::vector<Entity> expected_pv;
    for (const auto& [e, v] : m.velocity)
        if (m.entities.at(e).first) expected_pv.push_back(e);
    ASSERT_EQ(sorted(pv), expected_pv);
    std::vector<Entity> p_not_n;
    w.view<Position>(lantern::ecs::exclude<Name>).each([&](Entity e, Position&) { p_not_n.push_back(e); });
    std::vector<Entity> expected_p_not_n;
    for (const auto& [e, comps] : m.entities)
        if (comps.first && !comps.second) expected_p_not_n.push_back(e);
    ASSERT_EQ(sorted(p_not_n), expected_p_not_n);
}

} // namespace ecs_test
