#include "lantern/systems/streaming.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/profile/profiler.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace lantern::systems {

constexpr int cells_per_chunk = chunk_size * chunk_size;

struct Streaming::PendingLoad {
    glm::ivec2 coord{0};
    std::array<std::uint8_t, cells_per_chunk> cells{};
    jobs::Counter done;
    const WorldSource* source = nullptr;
    bool edited = false; // the cells came from stored edits: they differ from the source
};

Streaming::Streaming(std::shared_ptr<const WorldSource> source, StreamingConfig config)
    : source_(std::move(source)), config_(config) {}

Streaming::~Streaming() {
    // Loads in flight write into their PendingLoad: let them finish first.
    for (auto* map : {&chunks_, &cancelled_})
        for (auto& [k, slot] : *map)
            if (slot.pending && jobs_) jobs_->wait(slot.pending->done);
}

std::uint64_t Streaming::key(glm::ivec2 c) {
    return (std::uint64_t(std::uint32_t(c.x)) << 32) | std::uint32_t(c.y);
}

std::size_t Streaming::mirror_index(int x, int z) const {
    return std::size_t(pmod(x, size_.x)) + std::size_t(pmod(z, size_.y)) * std::size_t(size_.x);
}

bool Streaming::in_rect(glm::ivec2 coord) const {
    const glm::ivec2 lo = rect_min_ / chunk_size, hi = (rect_min_ + size_) / chunk_size;
    return coord.x >= lo.x && coord.y >= lo.y && coord.x < hi.x && coord.y < hi.y;
}

gi::WallView Streaming::view() const {
    return gi::WallView{mirror_.data(), size_.x, size_.y, rect_min_,
                        glm::ivec2(pmod(rect_min_.x, std::max(size_.x, 1)), pmod(rect_min_.y, std::max(size_.y, 1)))};
}

void Streaming::clear_dirty() {
    dirty_.clear();
    resized_ = false;
}

StreamingStats Streaming::stats() const {
    StreamingStats s = stats_;
    s.resident_chunks = 0;
    s.loading_chunks = 0;
    for (const auto& [k, slot] : chunks_) (slot.pending ? s.loading_chunks : s.resident_chunks)++;
    s.edited_chunks_stored = edits_.size();
    s.mirror_bytes = mirror_.size();
    return s;
}

void Streaming::resize_mirror(glm::ivec2 size) {
    size_ = size;
    mirror_.assign(std::size_t(size.x) * std::size_t(size.y), 0);
    resized_ = true;
    dirty_.clear();
    ++version_;
}

// Copies a chunk's cells into the mirror (chunk rows are contiguous there: the mirror's
// width is a multiple of the chunk size and chunks start at multiples of it).
void Streaming::write_chunk(glm::ivec2 coord, const std::uint8_t* cells) {
    const int x0 = coord.x * chunk_size;
    for (int r = 0; r < chunk_size; ++r) {
        const std::size_t begin = mirror_index(x0, coord.y * chunk_size + r);
        if (cells)
            std::memcpy(&mirror_[begin], cells + r * chunk_size, chunk_size);
        else
            std::memset(&mirror_[begin], 0, chunk_size);
        dirty_.push_back({begin, begin + chunk_size});
    }
    ++version_;
}

std::vector<std::uint8_t> Streaming::read_chunk(glm::ivec2 coord) const {
    std::vector<std::uint8_t> cells(cells_per_chunk);
    const int x0 = coord.x * chunk_size;
    for (int r = 0; r < chunk_size; ++r)
        std::memcpy(cells.data() + r * chunk_size, &mirror_[mirror_index(x0, coord.y * chunk_size + r)], chunk_size);
    return cells;
}

void Streaming::start_load(ecs::CommandBuffer& commands, jobs::JobSystem& jobs, glm::ivec2 coord) {
    ChunkSlot slot;
    if (auto revived = cancelled_.find(key(coord)); revived != cancelled_.end()) {
        // Came back before its cancelled load finished: that load (and its edits) stands.
        slot = std::move(revived->second);
        cancelled_.erase(revived);
    } else {
        slot.pending = std::make_unique<PendingLoad>();
        slot.pending->coord = coord;
        if (auto stored = edits_.find(key(coord)); stored != edits_.end()) {
            // Edited before: the stored cells are the chunk (no generation needed).
            std::memcpy(slot.pending->cells.data(), stored->second.data(), cells_per_chunk);
            slot.pending->edited = true;
            edits_.erase(stored);
        } else {
            slot.pending->source = source_.get();
            PendingLoad* load = slot.pending.get();
            jobs.spawn(&load->done, jobs::JobOptions{"streaming.generate", jobs::Priority::normal, false},
                       [load] { load->source->generate(load->coord, load->cells); });
        }
    }
    slot.entity = commands.create();
    WallChunk chunk;
    chunk.coord = coord;
    chunk.state = ChunkState::loading;
    commands.emplace<WallChunk>(slot.entity, chunk);
    ++stats_.loads_started;
    chunks_.emplace(key(coord), std::move(slot));
}

void Streaming::finish_loads(ecs::World& world, ecs::CommandBuffer& commands, bool wait, jobs::JobSystem& jobs) {
    for (auto& [k, slot] : chunks_) {
        if (!slot.pending) continue;
        if (wait) jobs.wait(slot.pending->done);
        if (!slot.pending->done.done()) continue;
        PendingLoad& load = *slot.pending;
        for (auto [cell, wall] : slot.pending_edits) load.cells[std::size_t(cell)] = wall ? 1 : 0;
        WallChunk chunk;
        chunk.coord = load.coord;
        chunk.state = ChunkState::resident;
        chunk.version = (load.edited || !slot.pending_edits.empty()) ? 1 : 0;
        if (world.alive(slot.entity))
            world.patch<WallChunk>(slot.entity) = chunk;
        else
            commands.emplace<WallChunk>(slot.entity, chunk); // created this frame: replaces at apply
        write_chunk(load.coord, load.cells.data());
        slot.pending.reset();
        slot.pending_edits.clear();
        ++stats_.loads_completed;
    }
}

void Streaming::unload(ecs::World& world, ecs::CommandBuffer& commands, glm::ivec2 coord, ChunkSlot& slot) {
    if (slot.pending) {
        // Still generating: park it (never wait in a frame); reaped when done.
        ++stats_.loads_cancelled;
        ChunkSlot parked;
        parked.pending = std::move(slot.pending);
        parked.pending_edits = std::move(slot.pending_edits);
        cancelled_[key(coord)] = std::move(parked);
    } else if (world.alive(slot.entity)) {
        const WallChunk& chunk = world.get<WallChunk>(slot.entity);
        if (chunk.version > 0) edits_[key(coord)] = read_chunk(coord); // the mirror holds its bytes
        write_chunk(coord, nullptr); // the slot reads as air until the next chunk arrives
    }
    commands.destroy(slot.entity);
    ++stats_.unloads;
}

void Streaming::reap_cancelled() {
    for (auto it = cancelled_.begin(); it != cancelled_.end();) {
        ChunkSlot& slot = it->second;
        if (!slot.pending->done.done()) {
            ++it;
            continue;
        }
        if (!slot.pending_edits.empty()) { // keep the edits made while it was loading
            std::vector<std::uint8_t> cells(slot.pending->cells.begin(), slot.pending->cells.end());
            for (auto [cell, wall] : slot.pending_edits) cells[std::size_t(cell)] = wall ? 1 : 0;
            edits_[it->first] = std::move(cells);
        }
        it = cancelled_.erase(it);
    }
}

void Streaming::update(ecs::World& world, ecs::CommandBuffer& commands, jobs::JobSystem& jobs,
                       const gi::CameraView& window) {
    LANTERN_PROFILE_SCOPE("streaming.update");
    jobs_ = &jobs;
    reap_cancelled();
    // Mirror size: the window plus the margin on both sides plus one chunk of alignment
    // slack, in whole chunks; stable while the window keeps its size.
    const glm::ivec2 span(int(std::ceil(window.width)) + 2 * config_.margin,
                          int(std::ceil(window.height)) + 2 * config_.margin);
    const glm::ivec2 size = (span / chunk_size + 2) * chunk_size;
    const glm::ivec2 rect_min(floor_div(int(std::floor(window.min_x)) - config_.margin, chunk_size) * chunk_size,
                              floor_div(int(std::floor(window.min_z)) - config_.margin, chunk_size) * chunk_size);
    if (size != size_) {
        // A new mirror: everything reloads (edits are kept).
        for (auto& [k, slot] : chunks_) unload(world, commands, glm::ivec2(std::int32_t(k >> 32), std::int32_t(k)), slot);
        chunks_.clear();
        resize_mirror(size);
    }
    rect_min_ = rect_min;
    has_rect_ = true;
    // Unload what left the rectangle, then load what entered it.
    for (auto it = chunks_.begin(); it != chunks_.end();) {
        const glm::ivec2 coord(std::int32_t(it->first >> 32), std::int32_t(it->first));
        if (in_rect(coord)) {
            ++it;
            continue;
        }
        unload(world, commands, coord, it->second);
        it = chunks_.erase(it);
    }
    const glm::ivec2 lo = rect_min_ / chunk_size, hi = (rect_min_ + size_) / chunk_size;
    for (int cz = lo.y; cz < hi.y; ++cz)
        for (int cx = lo.x; cx < hi.x; ++cx)
            if (!chunks_.count(key({cx, cz}))) start_load(commands, jobs, {cx, cz});
    finish_loads(world, commands, false, jobs);
}

void Streaming::load_all(ecs::World& world, jobs::JobSystem& jobs, const gi::CameraView& window) {
    ecs::CommandBuffer commands(world);
    update(world, commands, jobs, window);
    finish_loads(world, commands, true, jobs);
    commands.apply();
}

void Streaming::set_wall(ecs::World& world, glm::ivec2 tile, bool wall) {
    const glm::ivec2 coord(floor_div(tile.x, chunk_size), floor_div(tile.y, chunk_size));
    const int cell = pmod(tile.y, chunk_size) * chunk_size + pmod(tile.x, chunk_size);
    auto it = chunks_.find(key(coord));
    if (it != chunks_.end()) {
        ChunkSlot& slot = it->second;
        if (slot.pending) {
            slot.pending_edits.push_back({cell, wall});
            return;
        }
        ++world.patch<WallChunk>(slot.entity).version; // the bytes live in the mirror only
        const std::size_t index = mirror_index(tile.x, tile.y);
        mirror_[index] = wall ? 1 : 0;
        dirty_.push_back({index, index + 1});
        ++version_;
        return;
    }
    if (auto parked = cancelled_.find(key(coord)); parked != cancelled_.end()) {
        parked->second.pending_edits.push_back({cell, wall}); // applied when it is reaped or revived
        return;
    }
    // Not resident: edit the stored copy (generated now if there is none).
    auto& cells = edits_[key(coord)];
    if (cells.empty()) {
        cells.resize(cells_per_chunk);
        source_->generate(coord, cells);
    }
    cells[std::size_t(cell)] = wall ? 1 : 0;
}

std::vector<Streaming::EditedChunk> Streaming::edited_chunks(const ecs::World& world) const {
    std::vector<EditedChunk> out;
    for (const auto& [k, cells] : edits_)
        out.push_back({glm::ivec2(std::int32_t(k >> 32), std::int32_t(k)), cells});
    for (const auto& [k, slot] : chunks_) {
        if (slot.pending || !world.alive(slot.entity)) continue;
        const WallChunk& chunk = world.get<WallChunk>(slot.entity);
        if (chunk.version > 0) out.push_back({chunk.coord, read_chunk(chunk.coord)});
    }
    std::sort(out.begin(), out.end(), [](const EditedChunk& a, const EditedChunk& b) {
        return a.coord.y != b.coord.y ? a.coord.y < b.coord.y : a.coord.x < b.coord.x;
    });
    return out;
}

void Streaming::restore_edits(std::vector<EditedChunk> chunks) {
    LANTERN_ASSERT(chunks_.empty(), "restore_edits after chunks were loaded");
    edits_.clear();
    for (EditedChunk& c : chunks) {
        LANTERN_ASSERT(c.cells.size() == std::size_t(cells_per_chunk), "edited chunk of the wrong size");
        edits_[key(c.coord)] = std::move(c.cells);
    }
}

std::uint8_t Streaming::cell(glm::ivec2 tile) const {
    const glm::ivec2 coord(floor_div(tile.x, chunk_size), floor_div(tile.y, chunk_size));
    const int cell = pmod(tile.y, chunk_size) * chunk_size + pmod(tile.x, chunk_size);
    auto it = chunks_.find(key(coord));
    if (it != chunks_.end() && !it->second.pending) return mirror_[mirror_index(tile.x, tile.y)];
    auto e = edits_.find(key(coord));
    if (e != edits_.end()) return e->second[std::size_t(cell)];
    if (auto parked = cancelled_.find(key(coord)); parked != cancelled_.end())
        for (auto edit = parked->second.pending_edits.rbegin(); edit != parked->second.pending_edits.rend(); ++edit)
            if (edit->first == cell) return edit->second ? scene::default_wall_cell : 0;
    return source_->cell(tile);
}

} // namespace lantern::systems
