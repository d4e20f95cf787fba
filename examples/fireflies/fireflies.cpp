#include "fireflies.hpp"

#include <lantern/components/components.hpp>
#include <lantern/core/log.hpp>
#include <lantern/game/game_components.hpp>
#include <lantern/systems/streaming.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace fireflies {
namespace {

using lantern::ecs::Entity;
using lantern::ecs::SystemContext;
using lantern::ecs::World;
namespace reading = lantern::scene::reading;

constexpr float two_pi = 6.28318530718f;

std::uint64_t next(std::uint64_t& state) { // splitmix64
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
float uniform(std::uint64_t& state) { return float(next(state) >> 40) * (1.0f / 16777216.0f); } // [0, 1)

bool open_tile(const lantern::systems::Streaming& walls, glm::vec2 p) {
    return !walls.is_wall({int(std::floor(p.x)), int(std::floor(p.y))});
}

// Blinks, and fades in over its first second and out over its last.
float brightness(const Firefly& f) {
    const float fade = std::fmin(1.0f, std::fmin(f.age, f.lifetime - f.age));
    const float blink = 0.55f + 0.45f * std::sin(f.phase + 3.0f * f.age);
    return std::fmax(0.0f, fade) * blink;
}

void update(SystemContext& ctx) {
    World& w = ctx.world;
    FireflyRules& rules = w.resource<FireflyRules>();
    const float dt = w.resource<lantern::game::GameClock>().dt;
    const auto& walls = w.resource<lantern::systems::Streaming>();
    // Wander: steer a little at random, bounce off walls, age; gone at the end of life.
    int alive = 0;
    w.view<Firefly, lantern::EmissiveLight>().each([&](Entity e, Firefly& f, const lantern::EmissiveLight& light) {
        f.age += dt;
        if (f.age >= f.lifetime) {
            ctx.commands().destroy(e);
            return;
        }
        ++alive;
        const float turn = (uniform(rules.random) * 2.0f - 1.0f) * rules.turn * dt;
        const float c = std::cos(turn), s = std::sin(turn);
        f.velocity = {c * f.velocity.x - s * f.velocity.y, s * f.velocity.x + c * f.velocity.y};
        glm::vec2 to = light.position + f.velocity * dt;
        if (!open_tile(walls, to)) { // turn back rather than enter rock
            f.velocity = -f.velocity;
            to = light.position;
        }
        lantern::EmissiveLight& out = w.patch<lantern::EmissiveLight>(e);
        out.position = to;
        out.intensity = rules.intensity * brightness(f);
    });
    // The rule: at night, near the player, on open ground, up to max_alive.
    if (!is_night(w.resource<lantern::game::DayCycle>().time_of_day)) {
        rules.owed = 0.0f;
        return;
    }
    glm::vec2 player{0.0f};
    bool found = false;
    w.view<lantern::game::Player, lantern::Transform>().each(
        [&](const lantern::game::Player&, const lantern::Transform& t) {
            player = {t.position.x, t.position.z};
            found = true;
        });
    if (!found) return;
    rules.owed = std::fmin(rules.owed + rules.spawn_per_second * dt, 4.0f);
    for (; rules.owed >= 1.0f && alive < rules.max_alive; rules.owed -= 1.0f) {
        const float angle = uniform(rules.random) * two_pi;
        const float distance = rules.min_distance + uniform(rules.random) * (rules.max_distance - rules.min_distance);
        const glm::vec2 at = player + distance * glm::vec2(std::cos(angle), std::sin(angle));
        if (!open_tile(walls, at)) continue; // the rule: open ground only (this spawn is lost)
        const float heading = uniform(rules.random) * two_pi;
        Firefly f;
        f.velocity = rules.speed * glm::vec2(std::cos(heading), std::sin(heading));
        f.lifetime = rules.min_lifetime + uniform(rules.random) * (rules.max_lifetime - rules.min_lifetime);
        f.phase = uniform(rules.random) * two_pi;
        lantern::EmissiveLight light;
        light.position = at;
        light.color = rules.color;
        light.intensity = 0.0f; // fades in
        light.radius = rules.radius;
        const Entity e = ctx.commands().create();
        ctx.commands().emplace<Firefly>(e, f);
        ctx.commands().emplace<lantern::EmissiveLight>(e, light);
        ctx.commands().emplace<lantern::game::ExtensionOwned>(e);
        ++alive;
    }
}

void save(World& w, lantern::json::Writer& out) {
    const FireflyRules& rules = w.resource<FireflyRules>();
    char random[17];
    std::snprintf(random, sizeof(random), "%016llx", static_cast<unsigned long long>(rules.random));
    out.begin_object().field("random", random).field("owed", rules.owed);
    out.key("flies").begin_array();
    w.view<Firefly, lantern::EmissiveLight>().each([&](const Firefly& f, const lantern::EmissiveLight& light) {
        out.begin_object(lantern::json::Layout::one_line);
        out.key("position").begin_array().value(light.position.x).value(light.position.y).end();
        out.key("velocity").begin_array().value(f.velocity.x).value(f.velocity.y).end();
        out.field("age", f.age).field("lifetime", f.lifetime).field("phase", f.phase).end();
    });
    out.end().end();
}

void load(World& w, const lantern::json::Value& value, reading::Reader& r, const std::string& path) {
    FireflyRules rules = w.resource<FireflyRules>();
    reading::Fields top(r, value, path, {"random", "owed", "flies"});
    std::string random;
    top.required("random", random).optional("owed", rules.owed, reading::between(0.0, 4.0));
    if (r.ok()) {
        char* end = nullptr;
        rules.random = std::strtoull(random.c_str(), &end, 16);
        if (random.size() != 16 || *end != '\0' || random.find_first_of("+- ") != std::string::npos)
            top.fail("random", "expected 16 hexadecimal digits");
    }
    std::vector<std::pair<Firefly, glm::vec2>> flies;
    if (const lantern::json::Value* list = top.find_required("flies");
        list && r.expect(*list, path + ".flies", lantern::json::Type::array)) {
        const reading::Range speed{.min = -100.0, .max = 100.0, .note = "tiles per second"};
        for (std::size_t i = 0; i < list->as_array().size() && r.ok(); ++i) {
            const std::string at = reading::index_path(path + ".flies", i);
            Firefly f;
            glm::vec2 position{0.0f};
            reading::Fields fly(r, list->as_array()[i], at, {"position", "velocity", "age", "lifetime", "phase"});
            fly.required("position", position, reading::world_coordinate)
                .required("velocity", f.velocity, speed)
                .required("age", f.age, reading::at_least(0.0))
                .required("lifetime", f.lifetime, reading::between(0.001, 3600.0))
                .required("phase", f.phase, reading::between(-1000.0, 1000.0));
            if (r.ok() && f.age >= f.lifetime) fly.fail("age", "must be below the lifetime");
            flies.emplace_back(f, position);
        }
        if (r.ok() && flies.size() > 4096)
            r.fail(list->position(), path + ".flies", "at most 4096 fireflies");
    }
    if (!r.ok()) return; // nothing applied
    w.resource<FireflyRules>() = rules;
    for (const auto& [f, position] : flies) {
        const Entity e = w.create();
        lantern::EmissiveLight light;
        light.position = position;
        light.color = rules.color;
        light.intensity = rules.intensity * brightness(f);
        light.radius = rules.radius;
        w.emplace<Firefly>(e, f);
        w.emplace<lantern::EmissiveLight>(e, light);
        w.emplace<lantern::game::ExtensionOwned>(e);
    }
    LANTERN_LOG_INFO("fireflies: %zu loaded from the save", flies.size());
}

} // namespace

bool is_night(float time_of_day) { return time_of_day < 0.23f || time_of_day > 0.77f; }

lantern::game::GameExtension extension() {
    lantern::game::GameExtension e;
    e.name = "fireflies";
    e.setup = [](World& w) { w.set_resource<FireflyRules>(); };
    e.add_systems = [](lantern::ecs::Schedule& s) {
        s.add("fireflies", update)
            .reads<lantern::game::Player, lantern::Transform>()
            .writes<Firefly, lantern::EmissiveLight>()
            .reads_resource<lantern::game::GameClock, lantern::game::DayCycle, lantern::systems::Streaming>()
            .writes_resource<FireflyRules>();
    };
    e.save = save;
    e.load = load;
    return e;
}

} // namespace fireflies
