// Save files: the world a game was started from, the player, the time of day, every light,
// proxy, prop and dropped item (with their components), and every wall chunk the player edited.
//
// A save is a JSON text (docs/game.md has the format). write_save() replaces the file
// atomically (core/file.hpp): a game killed during a save leaves the previous save intact.
// read_save() rejects anything malformed with "<file>:<line>:<col>: <path>: <what>".
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/ecs/world.hpp"
#include "lantern/game/extension.hpp"
#include "lantern/game/game_components.hpp"
#include "lantern/game/world_setup.hpp"
#include "lantern/systems/streaming.hpp"

#include <optional>
#include <string>
#include <vector>

namespace lantern::game {

inline constexpr int save_format_version = 1;

// The game components of one entity (player and camera excluded).
struct SavedEntity {
    std::optional<PointLight> point_light;
    std::optional<EmissiveLight> emissive_light;
    std::optional<DirectionalLight> directional_light;
    std::optional<ShadowProxy> shadow_proxy;
    std::optional<Torch> torch;
    std::optional<Prop> prop;
    std::optional<DroppedItem> item; // its age is not saved (read back: resting)
    std::optional<ProbeAnchor> probe_anchor;
    bool sun = false;
};

struct SaveState {
    WorldSpec world;
    glm::vec2 player{0.0f};
    DayCycle day;
    Inventory inventory; // a save without one: a new game's
    std::vector<SavedEntity> entities;
    std::vector<systems::Streaming::EditedChunk> edits; // sorted by chunk
    // The baked light's cache keys of the chunks baked when saved (docs/baked.md, "In the
    // game"), sorted by chunk: which cache files the save's light comes from.
    struct BakedKey {
        glm::ivec2 chunk{0};
        std::uint64_t key = 0;
        friend bool operator==(const BakedKey&, const BakedKey&) = default;
    };
    std::vector<BakedKey> baked;
    // Game extensions' data (extension.hpp), by extension name, in the save's order.
    ExtensionData extensions;
    std::string file; // the file it was read from (messages about extension data)
};

// What to save from a running game (entities with ExtensionOwned left out: their extension
// saves them; the caller adds capture_extensions()).
SaveState capture_save(ecs::World& world, const systems::Streaming& streaming, const WorldSpec& spec);

// The save as text, and back. Floats are written in the shortest text that reads back as
// the same float (json::Writer), so a state reads back exactly.
std::string format_save(const SaveState& state);
Result<SaveState> parse_save(std::string_view text, const std::string& file_name);

Result<void> write_save(const std::string& path, const SaveState& state);
Result<SaveState> read_save(const std::string& path);

// Replaces the entities of a freshly created world (create_world) with the saved ones and
// moves the player; the caller hands state.edits to Streaming::restore_edits before the
// first frame.
void apply_save(const SaveState& state, ecs::World& world, ecs::Entity player);

// Save slots (the pause menu): slot 1 is the --save-file itself (F5 and F9), slots 2 and 3
// sit beside it ("lantern-save-2.json"), and the autosaves rotate through three more
// ("lantern-save-autosave-1.json" ...).
inline constexpr int save_slot_count = 3;
inline constexpr int autosave_slot_count = 3;
std::string save_slot_path(const std::string& save_file, int slot);   // slot in [1, save_slot_count]
std::string autosave_slot_path(const std::string& save_file, int slot); // slot in [1, autosave_slot_count]
// The autosave slot to write next: the first that does not exist, else the one written
// longest ago (the lowest slot among equals).
int next_autosave_slot(const std::string& save_file);

} // namespace lantern::game
