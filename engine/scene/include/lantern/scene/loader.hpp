// Scene files: reading, validating and importing them into lantern::scene::Scene, plus
// the Moving AI map importer and the `--set gi.KEY=VALUE` overrides of the render CLI.
// The format is ../shared/SCENES.md with Lantern's extensions, all in docs/scenes.md.
//
// Errors. Every function here returns a Result; nothing throws, and a failed call leaves
// its output untouched (no half-applied scene or override). A message is one line,
//     <file>:<line>:<col>: <json path>: <what is wrong>
// e.g. "level.json:14:22: gi.ao.radius: must be in (0, 8], got 12", where the position is
// that of the offending value (of the enclosing object for a missing key, of the key for
// an unknown key). Problems inside a map file name the map file, line and column instead.
// Error::exit_code is always 2 (bad input).
//
// Strictness. Unknown keys are errors (to catch typos such as "resoluton"), as are wrong
// types, non-integral integers, values out of range and numbers that do not fit a float.
//
// Trust boundary: safe for untrusted scene and map files. Malformed input of any kind comes
// back as an Error; grids above max_grid_cells, map sides above max_grid_side and GI
// windows above max_gi_texels_per_side are rejected before anything that large is
// allocated, so memory stays proportional to the file sizes. Map paths are followed as
// given (relative to the scene's folder); the loader does not sandbox them.
//
// Threads: all functions are reentrant; they share no state.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/scene/scene.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

namespace lantern::scene {

// Limits that keep hostile or mistaken inputs from exhausting memory.
inline constexpr int max_grid_side = 65536;                           // cells per grid side
inline constexpr std::int64_t max_grid_cells = std::int64_t(1) << 28; // 256 MiB of cells
// Trees a map may turn into shadow proxies ("trees": "proxy"; the game's --map does): each
// becomes a proxy in the scene, and in the game an entity with a prop, about 130 bytes of
// memory together, so this bounds them near 520 MiB whatever the map's size.
inline constexpr std::int64_t max_map_tree_proxies = std::int64_t(1) << 22;
inline constexpr double max_gi_texels_per_side = 65536.0;             // padded window * resolution

// Reads the scene file at `path` and parses it with parse_scene, with its folder as the
// base of relative map paths. Scene::source is `path`.
Result<Scene> load_scene(const std::string& path);

// Parses and validates scene JSON, imports its map (a relative "map" path is taken from
// `base_dir`; "" means the working directory), appends the tree proxies of
// "trees": "proxy" after the scene's own shadow proxies, and normalises directional light
// directions. `file_name_for_messages` prefixes every error and becomes Scene::source.
Result<Scene> parse_scene(std::string_view json_text, const std::string& file_name_for_messages,
                          const std::string& base_dir);

// Applies one `--set` assignment "gi.KEY=VALUE" to scene.gi, where KEY is a gi key of the
// scene format, nested keys joined by dots ("ao.radius"), and VALUE is a JSON scalar
// (16, 1.5, true, "aces") or a bare word taken as a string (aces). The value is checked
// exactly as in a file, and for a top-down view so is the size of the GI window. Errors
// read "--set gi.KEY: <what is wrong>"; on error `scene` is unchanged.
Result<void> apply_override(Scene& scene, std::string_view assignment);

// Checks every field of `gi` against the ranges of the scene format (the file loader
// and apply_override already do this), for settings built in code. Errors read
// "gi.<key>: <what is wrong>".
Result<void> validate_gi_settings(const GiSettings& gi);

// Every gi key of the scene format, nested keys joined by dots ("ao.radius"), in the order
// of the one table that files, `--set` and validation read (docs/scenes.md).
std::vector<std::string> gi_setting_keys();
// The value of one gi key as a number (bools 0 or 1, enums their value), the form the
// pass table hashes into cache keys; nullopt for a key that is not a gi key.
std::optional<double> gi_setting_value(const GiSettings& gi, std::string_view key);
// Every key's value at once, in the order of gi_setting_keys() (one pass over the table).
std::vector<double> gi_setting_values(const GiSettings& gi);

// What a Moving AI 'T' (tree) cell becomes.
enum class TreeMode : std::uint8_t {
    wall,  // a wall cell, like '@'
    proxy, // a floor cell; the scene loader adds a circle shadow proxy of radius 0.4 at its
           // centre (max_length 3, other ShadowProxy fields default)
};

struct MapImportOptions {
    TreeMode trees = TreeMode::wall;
    // Characters outside the Moving AI format to read as floor, e.g. "st" for the start
    // and target marks some published maps carry. Printable ASCII, none of ".GSW@OT".
    std::string extra_floor_chars;
};

struct ImportedMap {
    WallGrid walls;                // origin (0, 0): the caller places the grid
    std::vector<glm::ivec2> trees; // TreeMode::proxy: (col, row) of every 'T' cell in row-major
                                   // order, at most max_map_tree_proxies; TreeMode::wall: empty
};

// Reads a Moving AI grid map: four header lines ("type octile", "height H", "width W",
// "map"), then H rows of W characters; '\n' or "\r\n" line ends. '.' 'G' 'S' 'W' are
// floor, '@' 'O' wall, 'T' as options.trees says, options.extra_floor_chars floor; any
// other character is an error "<path>:<line>:<col>: unknown map character 'x' ...". Row i,
// column j becomes grid cell (j, i).
Result<ImportedMap> import_moving_ai_map(const std::string& path,
                                         const MapImportOptions& options = {});

// import_moving_ai_map on text already in memory; `file_name` is used in messages only.
Result<ImportedMap> parse_moving_ai_map(std::string_view text, const std::string& file_name,
                                        const MapImportOptions& options = {});

} // namespace lantern::scene
