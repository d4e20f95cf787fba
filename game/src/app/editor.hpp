// The scene editor (F3 in a scene world; docs/game.md, "Scene editor"): a designer selects,
// moves and recolours the scene file's lights, places and removes lights and shadow proxies in
// the running game, and writes the edits back to the file atomically. The file keeps everything
// the editor did not touch as it was written (scene::rewrite_scene_lists).
//
// The editor holds the edited lists; the game applies each EditResult to its world: an entry
// changed in place updates its entity, an entry added or removed rebuilds the world from
// scene(). Positions snap to quarter tiles.
// Threads: the main thread (draw() inside an ImGui frame).
#pragma once

#include "app/menu.hpp"
#include "lantern/core/result.hpp"
#include "lantern/scene/writer.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace lantern::game {

enum class EditKind : std::uint8_t { point_light, emissive_light, proxy };
inline constexpr const char* edit_kind_names[] = {"point", "emissive", "proxy"};

// One entry of the scene's lists ("point 2"), or nothing (index -1).
struct EditTarget {
    EditKind kind = EditKind::point_light;
    int index = -1;
    bool valid() const { return index >= 0; }
    friend bool operator==(const EditTarget&, const EditTarget&) = default;
};
std::string target_name(EditTarget t); // "point 2", "" for nothing

// What an edit asks of the running world.
struct EditResult {
    EditTarget changed;   // this entry changed in place (moved, recoloured): update its entity
    bool rebuild = false; // entries added or removed (or a change the bake must see): rebuild from scene()
    bool save = false;    // the panel's Save
    bool close = false;   // the panel's Close
};

inline constexpr float edit_snap = 0.25f;          // positions move in quarter tiles
inline constexpr float edit_pick_distance = 1.0f;  // a click selects the nearest entry this close

struct EditorColor {
    const char* name;
    glm::vec3 rgb;
};
// The panel's colour swatches (a ColorEdit beside them for any other colour).
inline constexpr EditorColor editor_colors[] = {
    {"warm", {1.0f, 0.6f, 0.25f}}, {"white", {1.0f, 1.0f, 1.0f}},  {"cold", {0.4f, 0.6f, 1.0f}},
    {"red", {1.0f, 0.15f, 0.1f}},  {"green", {0.3f, 1.0f, 0.35f}}, {"violet", {0.7f, 0.3f, 1.0f}},
};

class SceneEditor {
  public:
    // Reads the scene file at `path` and starts editing it; an error (positioned, as
    // load_scene's) leaves the editor as it was.
    Result<void> open(const std::string& path);
    // Hides the panel; the edits stay (reopen() shows them again, unsaved ones included).
    void close() { open_ = false; }
    void reopen() {
        open_ = !path_.empty();
        frames_open_ = 0;
    }
    bool is_open() const { return open_; }

    // The scene as edited: the file's, its lists replaced (a map's trees kept after the
    // file's own proxies). Valid once opened.
    scene::Scene scene() const;
    const scene::SceneLists& lists() const { return lists_; }
    const std::string& path() const { return path_; }
    EditTarget selected() const { return selected_; }
    std::optional<glm::vec2> position_of(EditTarget t) const;
    bool realtime(EditTarget t) const; // a realtime light: nothing baked depends on it
    bool unsaved() const { return unsaved_; }
    int saves() const { return saves_; }

    // The nearest entry within edit_pick_distance of `world` becomes the selection; none
    // there: nothing is selected.
    EditTarget select_near(glm::vec2 world);
    void select(EditTarget t) { selected_ = exists(t) ? t : EditTarget{}; }
    EditResult move_selected(glm::vec2 world); // to `world`, snapped
    EditResult recolor_selected(glm::vec3 color);
    EditResult add(EditKind kind, glm::vec2 world); // a default entry there, selected
    EditResult remove_selected();
    // Writes the edits into the file: refused (the file untouched) when the file changed on
    // disk since the editor read it.
    Result<void> save();

    // The panel; `player`: where Add places an entry.
    EditResult draw(glm::vec2 player, const std::string& message);
    // Its buttons once it has been drawn twice (layout settled), in window pixels.
    std::span<const MenuButton> settled_buttons() const {
        return frames_open_ >= 2 ? std::span<const MenuButton>(buttons_) : std::span<const MenuButton>();
    }

  private:
    bool exists(EditTarget t) const;
    int count(EditKind kind) const;
    EditResult changed(EditTarget t); // marks t edited, says how the world follows
    bool button(const char* label, float width = 0.0f);
    void draw_selection(EditResult& out);

    bool open_ = false;
    std::string path_, text_; // the file, and its text as last read or written
    scene::Scene base_;       // as last read or written
    std::size_t own_proxies_ = 0;
    scene::SceneLists lists_;
    EditTarget selected_;
    bool unsaved_ = false;
    int saves_ = 0;
    std::vector<MenuButton> buttons_;
    int frames_open_ = 0;
};

} // namespace lantern::game
