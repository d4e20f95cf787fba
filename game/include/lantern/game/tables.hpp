// The game's tables (docs/game.md, "Game tables"): the caves' wall materials and the light of
// each thing the game places (torch, crystal, lamp post, the player's lantern), in a small JSON
// file a designer tunes (`--tables FILE`; the built-in defaults without it). With `--watch` the
// running game reloads the file when it changes and applies it to the world in place: the
// materials (their colours in the view, their bounce, the bake, which re-bakes what they reach)
// and the light of every torch, crystal, lamp post and the player (placed or saved ones too).
// A malformed edit is reported and the last good tables stay.
//
// parse_tables() rejects anything malformed with "<file>:<line>:<col>: <path>: <what>" (exit
// status 2); every key is optional. Threads: the functions are reentrant.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/scene/scene.hpp"

#include <glm/vec3.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace lantern::game {

inline constexpr int tables_format_version = 1;

// A light the game gives a kind of thing. `height` is above the ground (point lights; the
// crystal's emissive light has none). `ambient` is seed 001's ambient colour per light: what
// the per-texel lit models (props, the player) take from the light without shadows, falling
// off linearly to 0 at its radius (it flickers with a torch).
struct ItemLight {
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float radius = 4.0f;
    float height = 1.0f;
    glm::vec3 ambient{0.0f};
    friend bool operator==(const ItemLight&, const ItemLight&) = default;
};

struct GameTables {
    // The caves' materials, cell value 2 + k (scene::cave_lava, scene::cave_crystal): a file
    // tunes them by name, it cannot add or drop one (the caves' generator places them).
    std::vector<scene::Material> materials;
    ItemLight torch, crystal, lamp_post, player;
    friend bool operator==(const GameTables&, const GameTables&) = default;
};

// The built-in tables (scene::cave_materials(), the game's lights as they always were).
const GameTables& default_tables();

std::string format_tables(const GameTables& tables);
Result<GameTables> parse_tables(std::string_view text, const std::string& file_name);
Result<GameTables> read_tables(const std::string& path); // a missing file is an error (it was named)

} // namespace lantern::game
