// The frame: ECS systems on the job graph feeding a GI backend (docs/frame.md).
//
//   camera_view ──► streaming ─┐
//        │   └────► light_gather ├──► cache_keys ──► gpu_submit (main thread)
//        └────────► proxy_gather ┘
//
// Each system is a job with declared reads and writes; the Schedule runs independent ones
// in parallel. The cache keys are per pass, so an unchanged frame submits no GI work and a
// change reruns exactly the passes that depend on it. Game systems come in through
// GiFrameOptions::add_game_systems (they run before the GI systems they conflict with).
//
// Threads: construct and step() on the job system's main thread.
#pragma once

#include "lantern/components/components.hpp"
#include "lantern/ecs/schedule.hpp"
#include "lantern/gi/backend.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/wall_distance.hpp"
#include "lantern/systems/streaming.hpp"

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lantern::systems {

// ---- resources

// Stepping the converging rows by hand (the HUD's bounce stepper: the radiosity method adds a
// bounce a frame). Counters, so that the frame systems only read them: each increment of
// `steps` lets a held row run one more frame, each increment of `restarts` starts the rows
// afresh next frame (bounce 1 again).
struct ConvergeControl {
    bool hold = false;        // converging rows stay where they are (a still scene shows one bounce)
    std::uint64_t steps = 0;    // while held: one more frame per increment (one a frame)
    std::uint64_t restarts = 0; // start afresh next frame
};

struct GiConfig {
    scene::GiSettings settings;
    ConvergeControl converge;
    float wall_height = 2.0f;
    bool lit_image = false; // run the lit-image pass (tools); the game shades in its raster pass
    float light_hysteresis = 2.0f; // world units of priority bonus for lights kept last frame
    // Shadow proxies beyond gi.max_shadow_proxies: the last kept fade out over this many world
    // units of distance before the cut instead of popping (gi::gather_offers_faded). 0 (the
    // default): the hard cut, as the scene path (gi::gather_frame_inputs) gathers; the game
    // fades over 6.
    float proxy_fade = 0.0f;
    // The wall materials: cell value 2 + k is materials[k] (docs/scenes.md, "Materials").
    std::vector<scene::Material> materials;
};

// The bake's light the frame adds (docs/baked.md, "At run time"): set by whoever loads or
// bakes it (lantern-render --bake, the game's bake system); nullptr: none. The lights and
// materials in the world must then leave out what it holds (bake::live_scene).
struct BakedGi {
    std::shared_ptr<const gi::BakedLight> light;
    float pulse = 1.0f; // the pulsing glow's factor this frame (gi::FrameInputs::baked_pulse)
};

struct GiView {
    std::optional<gi::GiWindow> window; // nullopt: no GI this frame
    std::string bail_reason;
};

struct GatheredLights {
    std::vector<gi::GpuPointLight> points, emissives;
    std::vector<gi::GpuPointLight> mixed_points, mixed_emissives; // with a bake (BakedGi): direct light only
    std::vector<gi::GpuDirectionalLight> suns;
    std::vector<ecs::Entity> point_entities; // kept this frame, in GPU order
    std::uint64_t hash = 0;                  // of the point lights and emissives
    std::uint64_t suns_hash = 0;             // of the directional lights
    std::uint32_t point_candidates = 0;      // reaching the window, before the cap
};

struct GatheredProxies {
    std::vector<gi::GpuShadowProxy> proxies;
    std::uint64_t hash = 0;
};

// What this frame runs, from the cache keys.
struct FramePasses {
    gi::PassPlan plan;                           // what the scene needs
    gi::PassSet run;                             // what runs: needed and keys changed
    std::array<std::uint64_t, gi::pass_count> keys{};
    std::array<std::string, gi::pass_count> reason; // for passes that do not run
    gi::FrameInputs inputs;                      // the GPU-ready inputs of this frame
};

// The distance to the nearest wall over the GI window, for game code (AI, sound): seed 003's
// distance field on the CPU (gi::WallDistance, equal to the GPU's distance_field texture),
// rebuilt by the wall_distance system when the walls, the window or gi.radiosity.scale
// change, whatever the GI method. Read it in a system that declares
// reads_resource<WallDistanceField>().
struct WallDistanceField {
    gi::WallDistance field;
    std::uint64_t key = 0;    // the window, walls and grid it was built for
    std::uint64_t builds = 0; // how many times it was rebuilt
};

struct FrameReport {
    std::uint64_t frame = 0;
    gi::PassSet ran;
    std::array<std::string, gi::pass_count> reason;
    std::optional<gi::GiWindow> window;
    std::vector<gi::FrameTimes> completed; // GPU times of earlier frames that finished since
    // The backend refused this frame (the window does not fit the device, too many lights
    // for one pass): nothing ran, every pass reruns next frame. Tools fail on it; the game
    // logs it and goes on.
    std::optional<Error> error;
};

struct GiFrameOptions {
    StreamingConfig streaming;
    // Adds the game's systems to the schedule before the GI systems, so that (where their
    // access conflicts) they run first: a camera moved or a light changed this frame is
    // seen by this frame's GI.
    // They reach the walls through the world resource Streaming (declared as any resource).
    std::function<void(ecs::Schedule&)> add_game_systems;
    // Before the first frame's passes, records two frames not shown (gi::warm_up_inputs, with
    // its shadow proxies left out and then with them) so that the shader variants a sunrise,
    // a mixed light, a proxy or a sun with no proxy in view will need
    // have their code before play: llvmpipe generates it at a pipeline's
    // first dispatch, and on a machine whose shader cache has not seen it that took 400-900 ms
    // in the middle of a frame (docs/performance.md, "Hitches on a fresh machine"). The first
    // frame then computes everything afresh, as it would have.
    bool warm_up_shaders = false;
};

class GiFrame {
  public:
    // `source` gives the walls; `backend` runs the passes. Registers the resources and the
    // GI systems in the world and schedule.
    GiFrame(ecs::World& world, jobs::JobSystem& jobs, std::shared_ptr<const WorldSource> source,
            std::unique_ptr<gi::Backend> backend, GiConfig config, GiFrameOptions options = {});
    ~GiFrame();

    // Game systems go here (before the first step).
    ecs::Schedule& schedule() { return schedule_; }
    ecs::World& world() { return world_; }
    // The world resource Streaming (registered by the constructor, removed by the destructor).
    Streaming& streaming() { return world_.resource<Streaming>(); }
    gi::Backend& backend() { return *backend_; }
    GiConfig& config() { return world_.resource<GiConfig>(); }

    // Loads the walls the camera's first window needs and waits for them (start-up).
    void warm_up();
    // One frame: runs the schedule (every system, the GPU submission included).
    FrameReport step();
    std::uint64_t frame() const { return frame_; }
    // The camera entity whose view and GICache the frame uses (the first Camera).
    ecs::Entity camera() const;

  private:
    void add_systems();

    ecs::World& world_;
    jobs::JobSystem& jobs_;
    std::unique_ptr<gi::Backend> backend_;
    ecs::Schedule schedule_;
    std::uint64_t frame_ = 0;
    std::uint32_t gpu_lane_ = 0;
    FrameReport report_;
    gi::Convergence convergence_; // the camera's converging rows (cache_keys, gpu_submit)
    std::uint64_t steps_seen_ = 0, restarts_seen_ = 0; // GiConfig::converge acted on
    gi::PassSet held_; // ran while held: advanced by the next step or the release
    bool warm_up_shaders_ = false; // GiFrameOptions::warm_up_shaders, until the first frame ran
};

// Per-pass cache keys of a frame (exposed for tests and the HUD): gi::derive_keys over the
// frame's input versions. A pass's key hashes what its pass-table row lists and the keys of
// the passes it reads, so a change reruns exactly its dependents.
// With `convergence`, converging rows count their history (gi::derive_keys).
std::array<std::uint64_t, gi::pass_count> pass_keys(const gi::FrameInputs& in, gi::PassPlan& plan,
                                                     std::uint64_t wall_version, std::uint64_t lights_hash,
                                                     std::uint64_t suns_hash, std::uint64_t proxies_hash,
                                                     gi::Convergence* convergence = nullptr);

} // namespace lantern::systems
