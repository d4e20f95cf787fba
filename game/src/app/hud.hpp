// The timer HUD (Dear ImGui): frame-time graph and percentiles, every system job with its
// worker lane, every GPU pass, which GI passes ran or were left out and why, live GI and
// art settings, light and proxy counts. Drawn over the upscaled frame at window resolution.
#pragma once

#include "lantern/game/game_components.hpp"
#include "lantern/game/world_renderer.hpp"
#include "lantern/profile/profiler.hpp"
#include "lantern/systems/gi_frame.hpp"

#include <string>
#include <vector>

namespace lantern::game {

struct BakeStatus;

struct HudInputs {
    const systems::FrameReport* report = nullptr; // this frame's
    systems::GiConfig* config = nullptr;          // edited live
    ArtSettings* art = nullptr;                   // edited live
    BounceStyle* world_bounce = nullptr;          // edited live (seed 002's knobs)
    BounceStyle* character_bounce = nullptr;      // edited live
    GiDebugView* gi_view = nullptr;               // edited live
    GiDebugView gi_view_drawn = GiDebugView::lit; // what the last frame drew
    int converge_history = 0;                     // frames of history the method's converging pass has
    DayCycle* day = nullptr;
    const systems::GatheredLights* lights = nullptr;
    const systems::GatheredProxies* proxies = nullptr;
    systems::StreamingStats streaming;
    const BakeStatus* bake = nullptr; // the baked light's chunks (nullptr: --no-bake)
    const ecs::ScheduleInfo* schedule = nullptr; // the frame's schedule (its panel)
    std::uint32_t entities = 0;
    std::string world;        // one line
    std::string message;      // the last action's result ("saved to ...")
    const char* item = "";    // the selected item
    bool vsync = true;
    std::string device;
};

struct HudActions {
    bool export_trace = false;
    bool save = false;
    bool load = false;
    bool toggle_vsync = false;
};

class Hud {
  public:
    bool visible = true;
    int graph_frames = 240; // the frame-time graph's length (the trace exports as many)

    // Builds this frame's HUD windows (inside an ImGui frame).
    HudActions draw(const HudInputs& in);

  private:
    void refresh_stats();
    std::vector<profile::ScopeStats> stats_;
    profile::Percentiles frame_ms_;
    std::uint64_t stats_frame_ = 0;
    std::vector<float> graph_;
};

// The hotbar (drawn with the HUD hidden too, inside an ImGui frame): one slot per item at
// the bottom centre of the display with its key, name and count, the selected one
// highlighted, an empty one dimmed. Takes no input: keys 1-5 select.
void draw_hotbar(const Inventory& inventory, int selected);

} // namespace lantern::game
