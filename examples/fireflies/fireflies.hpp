// Fireflies: a game extension built outside Lantern's tree (docs/extending.md). Wandering
// emissive lights with a lifetime, spawned at night on open ground near the player by a
// rule, saved and loaded with the world: a component (Firefly), a resource (FireflyRules),
// a system in the game's schedule ("fireflies") and the save hooks, handed to
// lantern::game::run_game as one GameExtension. Nothing in the engine was edited for it.
#pragma once

#include <lantern/game/extension.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace fireflies {

// On an entity with an EmissiveLight (the light the GI sees) and lantern::game::ExtensionOwned.
struct Firefly {
    glm::vec2 velocity{0.0f}; // tiles per second
    float age = 0.0f;         // seconds
    float lifetime = 8.0f;    // seconds; the firefly is gone when age reaches it
    float phase = 0.0f;       // of its blinking, radians
};

// The spawn rule and the state it keeps (the random stream, the fraction of a spawn owed).
struct FireflyRules {
    int max_alive = 24;
    float spawn_per_second = 4.0f;
    float min_distance = 2.0f, max_distance = 9.0f; // from the player, tiles
    float speed = 1.5f;                             // tiles per second
    float turn = 2.5f;                              // radians per second of random steering, at most
    float min_lifetime = 6.0f, max_lifetime = 14.0f;
    glm::vec3 color{0.7f, 1.0f, 0.3f};
    float intensity = 1.6f, radius = 4.0f;
    std::uint64_t random = 0x9E3779B97F4A7C15ull; // splitmix64 state
    float owed = 0.0f;                            // spawns owed, carried between frames
};

// Night: fireflies are out when the sun is down (time of day outside [0.23, 0.77]).
bool is_night(float time_of_day);

// The extension: setup (FireflyRules), the "fireflies" system, save and load.
lantern::game::GameExtension extension();

} // namespace fireflies
