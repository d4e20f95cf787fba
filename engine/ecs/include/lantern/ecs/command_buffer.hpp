// Deferred structural changes: record inside jobs and iterations, apply at a sync point.
//
// A CommandBuffer belongs to one thread at a time (keep one per worker; CommandQueues
// does that). Commands apply in recording order. Values passed to emplace() are moved into
// the buffer's arena at once and moved into the world at apply time.
//
// Deferred commands are lenient, because buffers recorded in parallel cannot know about
// each other: destroy of an entity that is no longer alive, emplace on a dead entity and
// remove of an absent component are skipped; emplace on an entity that already has the
// component replaces it (and marks it changed).
//
// Memory: the arena and the command list keep their capacity across clear(), so a buffer
// reused every frame stops allocating once warm.
#pragma once

#include "lantern/ecs/world.hpp"

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace lantern::ecs {

class CommandBuffer {
  public:
    explicit CommandBuffer(World& world) : world_(&world) {}
    ~CommandBuffer() { clear(); }
    CommandBuffer(CommandBuffer&& other) noexcept;
    CommandBuffer& operator=(CommandBuffer&&) = delete;
    CommandBuffer(const CommandBuffer&) = delete;

    // A new entity handle, usable in later commands at once; the entity is alive (and
    // empty) from the next sync point on, even if nothing is added to it.
    Entity create() { return world_->reserve(); }
    void destroy(Entity e) { commands_.push_back({Kind::destroy, e, nullptr, nullptr, nullptr}); }

    template <typename T, typename... Args>
    void emplace(Entity e, Args&&... args) {
        using U = std::decay_t<T>;
        void* slot = arena_allocate(sizeof(U), alignof(U));
        if constexpr (std::is_aggregate_v<U>)
            ::new (slot) U{std::forward<Args>(args)...};
        else
            ::new (slot) U(std::forward<Args>(args)...);
        commands_.push_back({Kind::emplace, e, slot, &emplace_thunk<U>, &destroy_thunk<U>});
    }
    template <typename T>
    void remove(Entity e) {
        commands_.push_back({Kind::remove, e, nullptr, &remove_thunk<T>, nullptr});
    }

    // Applies every command to the world, then clears. Call at a sync point, when no view
    // iterates and no other thread uses the world.
    void apply();
    // Drops every command without applying (reserved entities still become alive).
    void clear();

    std::size_t size() const { return commands_.size(); }
    bool empty() const { return commands_.empty(); }

  private:
    enum class Kind : std::uint8_t { destroy, emplace, remove };
    using Thunk = void (*)(World&, Entity, void*);
    struct Command {
        Kind kind;
        Entity entity;
        void* value;
        Thunk apply;
        void (*destroy_value)(void*);
    };
    struct Block {
        std::unique_ptr<std::byte[]> data;
        std::size_t size = 0;
        std::size_t used = 0;
    };

    template <typename U>
    static void emplace_thunk(World& w, Entity e, void* value) {
        if (w.alive(e)) w.assure<U>().emplace_moved(e, value, w.tick());
    }
    template <typename U>
    static void remove_thunk(World& w, Entity e, void*) {
        if (w.alive(e)) w.try_remove<U>(e);
    }
    template <typename U>
    static void destroy_thunk(void* value) {
        static_cast<U*>(value)->~U();
    }

    void* arena_allocate(std::size_t size, std::size_t align);

    World* world_;
    std::vector<Command> commands_;
    std::vector<Block> blocks_;
    std::size_t block_index_ = 0;
};

// One CommandBuffer per job-system thread, applied in thread order at a sync point.
class CommandQueues {
  public:
    CommandQueues(World& world, std::uint32_t threads);
    CommandBuffer& for_worker(std::uint32_t worker) { return buffers_[worker]; }
    void apply();
    std::size_t size() const;

  private:
    std::vector<CommandBuffer> buffers_;
};

} // namespace lantern::ecs
