// Streaming: keeps the wall chunks around the GI window resident, loads new ones in
// background jobs, unloads far ones keeping their edits, and maintains the CPU mirror of
// the GPU wall buffer with the byte ranges that changed.
//
// The resident area is a rectangle of whole chunks covering the GI window plus a margin.
// Its mirror is stored toroidally (tile (x, z) at cells[pmod(x, W) + pmod(z, H) * W]), so a
// chunk keeps its place in the buffer while the rectangle moves, and loading or unloading a
// chunk changes only that chunk's bytes: the GPU buffer is updated by those ranges, never
// re-uploaded whole (except when the window's size changes the mirror's size).
//
// Loads never stall a frame: update() starts jobs and collects the ones that finished.
// With zero job-system workers they run inside the frame's waits, so they finish within
// the frame that started them. Edits survive unloading and reloading.
//
// Threads: update(), set_wall() and the accessors belong to the frame's main thread (the
// streaming system is a main-thread system); generation runs on job threads.
#pragma once

#include "lantern/components/components.hpp"
#include "lantern/ecs/schedule.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/systems/world_source.hpp"

#include <memory>
#include <unordered_map>
#include <vector>

namespace lantern::systems {

struct StreamingConfig {
    int margin = 16; // tiles of resident wall grid kept beyond the GI window on every side
};

struct StreamingStats {
    std::uint32_t resident_chunks = 0; // loaded and in the mirror
    std::uint32_t loading_chunks = 0;  // jobs in flight
    std::uint64_t loads_started = 0, loads_completed = 0, unloads = 0;
    std::uint64_t loads_cancelled = 0; // the chunk left the resident area before it arrived
    std::uint64_t edited_chunks_stored = 0; // chunks whose edits are kept while unloaded
    std::size_t mirror_bytes = 0;
};

class Streaming {
  public:
    explicit Streaming(std::shared_ptr<const WorldSource> source, StreamingConfig config = {});
    ~Streaming();
    Streaming(const Streaming&) = delete;
    Streaming& operator=(const Streaming&) = delete;

    // One frame: moves the resident rectangle to cover `window`, starts loads for chunks
    // that entered it, finishes loads that completed, unloads chunks that left it.
    // Chunk entities are created and destroyed through `commands`.
    void update(ecs::World& world, ecs::CommandBuffer& commands, jobs::JobSystem& jobs, const gi::CameraView& window);
    // As update(), then waits until every chunk of the resident area is loaded (start-up,
    // tools, tests). Applies the commands itself.
    void load_all(ecs::World& world, jobs::JobSystem& jobs, const gi::CameraView& window);

    // Sets or clears the wall at `tile`, resident or not (a chunk still loading gets the
    // edit when it arrives). Main thread, outside iterations over WallChunk.
    void set_wall(ecs::World& world, glm::ivec2 tile, bool wall);
    // The world's wall at `tile`: the mirror where resident, else edits or the source.
    bool is_wall(glm::ivec2 tile) const { return cell(tile) != 0; }
    // Its cell value (0 air, 1 rock, 2 + k material k; a placed wall is 1), from the same places.
    std::uint8_t cell(glm::ivec2 tile) const;

    // The resident walls as the GI passes read them (valid until the next update/edit).
    gi::WallView view() const;
    const std::vector<gi::WallRange>& dirty() const { return dirty_; }
    // True when the mirror was reallocated (a new size): the GPU buffer needs a whole upload.
    bool resized() const { return resized_; }
    void clear_dirty();
    // Bumped whenever the resident walls change (loads, unloads, edits).
    std::uint64_t version() const { return version_; }
    StreamingStats stats() const;

    // Every chunk that differs from the source (resident or stored), for save files.
    struct EditedChunk {
        glm::ivec2 coord;
        std::vector<std::uint8_t> cells; // chunk_size^2, row-major
    };
    std::vector<EditedChunk> edited_chunks(const ecs::World& world) const;
    // Replaces the stored edits with `chunks` (a loaded save). Call before the first update.
    void restore_edits(std::vector<EditedChunk> chunks);
    const WorldSource& source() const { return *source_; }
    glm::ivec2 resident_min() const { return rect_min_; }
    glm::ivec2 resident_size() const { return size_; }

  private:
    struct PendingLoad;
    struct ChunkSlot {
        ecs::Entity entity;
        std::unique_ptr<PendingLoad> pending; // while loading
        std::vector<std::pair<int, bool>> pending_edits; // (cell index, wall) for a loading chunk
    };
    static std::uint64_t key(glm::ivec2 coord);

    void resize_mirror(glm::ivec2 size);
    void start_load(ecs::CommandBuffer& commands, jobs::JobSystem& jobs, glm::ivec2 coord);
    void finish_loads(ecs::World& world, ecs::CommandBuffer& commands, bool wait, jobs::JobSystem& jobs);
    void unload(ecs::World& world, ecs::CommandBuffer& commands, glm::ivec2 coord, ChunkSlot& slot);
    void write_chunk(glm::ivec2 coord, const std::uint8_t* cells);
    std::vector<std::uint8_t> read_chunk(glm::ivec2 coord) const; // a resident chunk's bytes, from the mirror
    void reap_cancelled();
    bool in_rect(glm::ivec2 coord) const;
    std::size_t mirror_index(int x, int z) const;

    std::shared_ptr<const WorldSource> source_;
    StreamingConfig config_;
    std::vector<std::uint8_t> mirror_;
    glm::ivec2 size_{0};     // mirror size in tiles (multiples of chunk_size)
    glm::ivec2 rect_min_{0}; // resident rectangle origin (a multiple of chunk_size)
    bool has_rect_ = false;
    bool resized_ = false;
    std::vector<gi::WallRange> dirty_;
    std::uint64_t version_ = 1;
    std::unordered_map<std::uint64_t, ChunkSlot> chunks_; // resident or loading
    std::unordered_map<std::uint64_t, std::vector<std::uint8_t>> edits_; // unloaded edited chunks
    // Loads whose chunk left the area before they finished: never waited for; reaped once
    // done, or revived if the chunk comes back first.
    std::unordered_map<std::uint64_t, ChunkSlot> cancelled_;
    StreamingStats stats_;
    jobs::JobSystem* jobs_ = nullptr; // for waiting on loads at destruction
};

// Floor division and the non-negative modulo, for tiles and chunks.
constexpr int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
constexpr int pmod(int a, int b) {
    const int m = a % b;
    return m < 0 ? m + b : m;
}

} // namespace lantern::systems
