// The game's baked light (docs/baked.md, "In the game"): every resident chunk's static light
// (the caves' lava and crystal walls, decorative crystals, the mixed bounce of decorative
// torches) baked by engine/bake in the background, kept in cache files next to the saves, and
// composed into the frame's baked light (systems::BakedGi) and the probes that light the
// player (BakedChunks::probes_at).
//
// A chunk's inputs are the walls and materials within the bake's margin and the lights'
// reach around it, and the mixed and baked lights and shadow proxies there (a torch at its
// base intensity, not this frame's flicker). When they change (an edit, a light placed) the
// chunk is baked again in the background; until it arrives its previous bake stays on
// screen, and a cache file is used only when its key matches (bake::load_chunk).
//
// Threads: the frame's main thread calls update() and finish(); the bakes and the
// composition run on one background thread of the baker's own, at the lowest priority, so
// a bake never runs inside a frame's wait and never stalls it.
#pragma once

#include "lantern/bake/bake.hpp"
#include "lantern/ecs/schedule.hpp"
#include "lantern/ecs/world.hpp"

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>

namespace lantern::game {

struct BakerOptions {
    std::string cache_dir; // chunk cache files; empty: kept in memory only
    bake::BakeSettings settings{.resolution = 2, .margin = 8, .rays = 64, .face_rays = 32};
    int reach = 12; // tiles beyond the margin whose walls and lights a chunk's bake sees (the lights' radius)
    // While the game plays, the baker rests `pace` times as long as each bake took (0: never),
    // so a burst of new chunks spreads over frames instead of slowing the ones it overlaps.
    double pace = 3.0;
};

// The baked chunks the frame uses (a world resource the bake system writes).
struct BakedChunks {
    std::unordered_map<std::uint64_t, std::shared_ptr<const bake::ChunkBake>> chunks; // by chunk_id_key
    // The pulsing glow's factor this frame (seed 004's pulsing emission; scene::pulse_factor).
    float pulse = 1.0f;
    // The moving sun's keys this frame (baked with --bake-sun-keys: seed 004's precomputed GI
    // for the day cycle): the two around the sun's time and its colour; key -1: none.
    gi::BakedSun sun;
    // The baked light arriving at p (circular harmonics), interpolated between the probes
    // around it (bake::interpolate_probes), the pulsing part's scaled by `pulse`, the sun
    // keys' blended and scaled by the sun's colour; zero where no baked chunk has one.
    bake::CircularHarmonics probes_at(glm::vec2 p) const;
};
std::uint64_t chunk_id_key(bake::ChunkId c);

// What the HUD and the tests read (a world resource).
struct BakeStatus {
    bool enabled = false;
    std::string cache_dir;
    int chunks = 0;          // resident chunks with a bake
    int pending = 0;         // bakes queued or running
    std::uint64_t baked = 0, reused = 0; // so far (reused: read from the cache)
    std::uint64_t published = 0;         // composed baked lights handed to the frame
    double last_chunk_ms = 0.0;
    std::string last_warning; // an unusable cache file, named (re-baked)
};

class WorldBaker {
  public:
    explicit WorldBaker(BakerOptions options);
    ~WorldBaker(); // stops the thread (a bake in progress finishes first)
    WorldBaker(const WorldBaker&) = delete;
    WorldBaker& operator=(const WorldBaker&) = delete;

    // Once a frame, main thread (the `bake` system): takes finished bakes and compositions,
    // queues bakes for resident chunks whose inputs changed, and writes systems::BakedGi,
    // BakedChunks and BakeStatus.
    void update(ecs::World& world);
    // Bakes (or reads) everything the resident chunks need and waits for it (start-up).
    void finish(ecs::World& world);
    const BakerOptions& options() const { return options_; }

  private:
    struct Job;
    struct Result;
    void run();
    void queue(Job job);
    bool scan(ecs::World& world); // queues what changed; true when the resident set changed

    BakerOptions options_;
    std::mutex mutex_;
    std::condition_variable wake_, idle_;
    std::deque<std::unique_ptr<Job>> jobs_;
    std::vector<std::unique_ptr<Result>> results_;
    int running_ = 0;
    bool stop_ = false;
    bool hurry_ = false; // finish() waits: no pacing
    std::thread thread_;
    // Main thread only.
    std::unordered_map<std::uint64_t, std::uint64_t> requested_; // chunk -> inputs hash last queued
    std::uint64_t seen_version_ = 0, seen_lights_ = 0;
    std::vector<bake::ChunkId> resident_;
    bool compose_wanted_ = false;
};

// The `bake` system (main thread): runs `baker` each frame. Add before the GI systems.
void add_bake_system(ecs::Schedule& schedule, WorldBaker& baker);

} // namespace lantern::game
