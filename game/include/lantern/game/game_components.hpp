// The sandbox game's components and resources (plain data; the engine's lights, proxies and
// camera are in components/). docs/game.md describes the game.
#pragma once

#include "lantern/components/components.hpp"

#include <glm/vec2.hpp>

#include <array>
#include <vector>
#include <cstdint>
#include <string>

namespace lantern::game {

// The player: a circle of `radius` tiles on the ground, at Transform.position (x, y, z).
struct Player {
    float speed = 5.0f;  // tiles per second
    float radius = 0.3f; // collision radius, tiles
    glm::vec2 facing{0.0f, 1.0f};
};

// A torch: a PointLight whose intensity flickers around `base_intensity`.
struct Torch {
    float base_intensity = 1.0f;
    float phase = 0.0f; // decorrelates torches
};

enum class PropKind : std::uint8_t { crystal, tree, lamp_post };

// A placed object (drawn by the renderer; its light or proxy is on the same entity).
struct Prop {
    PropKind kind = PropKind::crystal;
    glm::vec2 position{0.0f};
};

// Seed 004's per-object anchor override: the point where an object (a prop, the player)
// samples the baked light's probes, instead of its own position or each part's centre (an
// object half in shadow, a tall object whose base is not where its light is).
struct ProbeAnchor {
    glm::vec2 position{0.0f}; // world x, z
};

// The sun (with a DirectionalLight on the same entity).
struct Sun {};

// What the player asked for this frame, whatever produced it (window input or a script).
struct Controls {
    glm::vec2 move{0.0f};          // x, z in [-1, 1]
    bool has_cursor = false;
    glm::vec2 cursor_ndc{0.0f};    // [0, 1]^2 over the game view, y down
    bool mine = false;             // pressed this frame
    bool place_wall = false;
    bool place_torch = false;
    bool place_crystal = false;
    bool place_tree = false;
    bool place_lamp = false;
    bool toggle_day_cycle = false;
};

struct GameClock {
    double time = 0.0; // seconds since start
    float dt = 1.0f / 60.0f;
};

struct DayCycle {
    bool running = false;
    float time_of_day = 0.35f;   // 0 midnight, 0.25 sunrise, 0.5 noon, 0.75 sunset
    float day_length = 60.0f;    // seconds per day when running
    bool drives_sun = true;      // the Sun entities follow time_of_day (false: a scene's suns stay as authored)
};

// How the camera follows the player: a tilted top-down view (docs/game.md).
struct CameraRig {
    float height = 14.0f;
    float back = 9.0f;          // tiles behind the player along +z (the camera looks towards -z)
    float fov_deg = 40.0f;
    float aspect = 16.0f / 9.0f;
};

// What the player carries (issue 19: mining drops the block, or the torch or prop, as a
// DroppedItem the player collects; placing consumes). The hotbar shows it; saves keep it.
enum class Item : std::uint8_t { wall, torch, crystal, lamp_post, tree };
inline constexpr int item_count = 5;
inline constexpr const char* item_names[item_count] = {"wall", "torch", "crystal", "lamp post", "tree"};
struct Inventory {
    static constexpr int max_stack = 999;
    // A new game's: no blocks (mine some), a few lights and props to place.
    std::array<int, item_count> counts{0, 8, 4, 2, 4};
    int& operator[](Item i) { return counts[std::size_t(i)]; }
    int operator[](Item i) const { return counts[std::size_t(i)]; }
    friend bool operator==(const Inventory&, const Inventory&) = default;
};

// Something lying on the ground: what mining gave (a wall's block, a torch or prop picked up).
// The player collects it by walking near: within item_magnet_radius it glides to the player,
// within item_collect_radius it goes into the inventory (when the stack has room).
struct DroppedItem {
    Item item = Item::wall;
    int count = 1;             // 1 .. Inventory::max_stack
    glm::vec2 position{0.0f}; // world x, z
    float age = 0.0f;          // seconds on the ground (it hops out; collected after item_pickup_delay)
};
inline constexpr float item_pickup_delay = 0.3f;  // seconds before a dropped item can be collected
inline constexpr float item_magnet_radius = 1.75f; // tiles
inline constexpr float item_collect_radius = 0.4f; // tiles
inline constexpr float item_magnet_speed = 6.0f;   // tiles per second

// Edits the player made to the world (a wall mined or placed, a light or prop placed or picked
// up), counted by `interact`: the game compares the count with the one at the last save to
// know whether anything is unsaved.
struct WorldEdits {
    std::uint64_t count = 0;
};

// What the game's sound should play for this frame's edits (`interact` adds, the sound
// system plays and clears). The resource exists only while the game has sound.
enum class SoundCue : std::uint8_t { dig, place, pick_up };
struct SoundCues {
    struct Entry {
        SoundCue cue = SoundCue::dig;
        glm::vec2 at{0.0f};
    };
    std::vector<Entry> entries;
};

// Reach of the player's hands, tiles.
inline constexpr float interaction_range = 5.0f;

} // namespace lantern::game
