// Writing a scene's lights and shadow proxies back into its file (the game's scene editor;
// docs/scenes.md, "Writing a scene back"). Only the three edited lists are rewritten, and in
// them only the entries that changed: an entry kept from the file is copied as it was written
// (a "temperature" stays a temperature), an edited or new one is written in full. Every other
// member of the file (world, view, gi, materials...) keeps its place and its values; only
// whitespace becomes the writer's. So parse_scene of the result equals the edited scene.
//
// Threads: every function is reentrant. Errors: Results, positioned like parse_scene's.
#pragma once

#include "lantern/core/json.hpp"
#include "lantern/core/result.hpp"
#include "lantern/scene/scene.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace lantern::scene {

// An entry in the scene file's form, every field written.
json::Value to_json(const PointLight& light);
json::Value to_json(const EmissiveLight& light);
json::Value to_json(const ShadowProxy& proxy);

// One entry of an edited list: `value`, and where it came from: `original` is its index in the
// file's own list while it is unedited (written as the file had it), -1 once edited or new.
template <typename T>
struct ListEntry {
    T value;
    int original = -1;
};

struct SceneLists {
    std::vector<ListEntry<PointLight>> point_lights;
    std::vector<ListEntry<EmissiveLight>> emissive_lights;
    // The file's own proxies; a "trees": "proxy" map's trees (read after them) are not here.
    std::vector<ListEntry<ShadowProxy>> shadow_proxies;
};

// The lists of `scene`, which parse_scene read from `text` (its file's text, `path` for
// messages), every entry unedited. An error when `text` is not that scene's (other counts).
Result<SceneLists> scene_lists(std::string_view text, const std::string& path, const Scene& scene);

// `text` with "point_lights", "emissive_lights" and "shadow_proxies" replaced by `lists`
// (a list that was absent and is empty stays absent; a new one goes at the end). An error
// when `text` is not a JSON object, or an `original` is not an index of the file's list.
Result<std::string> rewrite_scene_lists(std::string_view text, const std::string& path, const SceneLists& lists);

// The scene `lists` describe: `scene` with its lights and proxies replaced (the map's trees,
// after the file's own proxies, kept).
Scene with_lists(const Scene& scene, std::size_t own_proxies, const SceneLists& lists);

} // namespace lantern::scene
