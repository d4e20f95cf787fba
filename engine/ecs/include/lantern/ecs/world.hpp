// The ECS world: entities, component pools, resources (singletons) and change ticks.
//
// Threads. Reads (get, view iteration, contains) may run concurrently. Structural changes
// (create, destroy, emplace, remove, clear) need exclusive access and are rejected by
// assertion on a pool that a view is iterating; inside jobs and iterations record them in
// a CommandBuffer and apply it at a sync point. reserve() alone is thread-safe.
//
// Change tracking. The world has a tick, advanced by advance_tick() at sync points (the
// Schedule does it after each run). emplace records the element as added and changed at
// the current tick; patch() marks it changed. A system remembers the tick it last ran at
// and asks View::each_changed / each_added, or a pool's last_changed/last_removed, what
// happened since. get() never marks: write through patch() when others must see it.
//
// Errors. Using a stale or null handle, adding a component twice, or removing/getting one
// that is absent is a programmer error (LANTERN_ASSERT). try_get and contains answer
// instead of asserting.
#pragma once

#include "lantern/core/assert.hpp"
#include "lantern/ecs/entity.hpp"
#include "lantern/ecs/pool.hpp"

#include <atomic>
#include <cstdint>
#include <string>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace lantern::ecs {

template <typename... T>
struct Exclude {};
template <typename... T>
inline constexpr Exclude<T...> exclude{};

template <typename Include, typename ExcludeList>
class View;
template <typename... T>
struct Include {};

// Access key: component and resource types live in separate id spaces.
struct AccessKey {
    enum Kind : std::uint8_t { component, resource } kind;
    TypeId id;
    friend bool operator==(AccessKey, AccessKey) = default;
};

// What the system running on this thread declared (the Schedule sets it around each
// system). In builds with asserts on, every component and resource access through the
// World is checked against it: a system that touches a type it did not declare (or
// patches, emplaces or removes one it declared only as read) stops with its name and the
// type. Jobs a system spawns run unchecked.
struct SystemAccess {
    const char* name;
    const std::vector<AccessKey>* reads;
    const std::vector<AccessKey>* writes;
};

namespace detail {
#if defined(LANTERN_ENABLE_ASSERTS)
inline thread_local const SystemAccess* current_access = nullptr;
#endif
[[noreturn]] void undeclared_access(const SystemAccess& access, AccessKey key, bool write, const char* type_name);

inline bool declared(const SystemAccess& access, AccessKey key, bool write) {
    for (AccessKey k : *access.writes)
        if (k == key) return true;
    if (!write)
        for (AccessKey k : *access.reads)
            if (k == key) return true;
    return false;
}

template <typename T>
const char* type_name() {
    // "const char* ...type_name() [with T = lantern::Foo]" (GCC) or "...[T = lantern::Foo]" (Clang).
    static const std::string name = [](std::string f) {
        const auto at = f.find("T = ");
        if (at == std::string::npos) return f;
        f = f.substr(at + 4);
        return f.substr(0, f.find_first_of(";]"));
    }(__PRETTY_FUNCTION__);
    return name.c_str();
}
} // namespace detail

// Sets the thread's SystemAccess for its lifetime (the Schedule, around each system).
class AccessScope {
  public:
#if defined(LANTERN_ENABLE_ASSERTS)
    explicit AccessScope(const SystemAccess* access) : previous_(detail::current_access) {
        detail::current_access = access;
    }
    ~AccessScope() { detail::current_access = previous_; }
#else
    explicit AccessScope(const SystemAccess*) {}
#endif
    AccessScope(const AccessScope&) = delete;
    AccessScope& operator=(const AccessScope&) = delete;

  private:
#if defined(LANTERN_ENABLE_ASSERTS)
    const SystemAccess* previous_;
#endif
};

class World {
  public:
    World();
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    // ---- entities
    Entity create();
    void destroy(Entity e);
    bool alive(Entity e) const {
        return e.index < slots_.size() && slots_[e.index] == e.generation && !is_free(e.index);
    }
    // Thread-safe: a handle that becomes a live (empty) entity at the next flush_reserved(),
    // which apply(), create() and the Schedule's sync points call.
    Entity reserve();
    void flush_reserved();
    std::uint32_t alive_count() const { return alive_count_; }
    // Calls f(Entity) for every live entity, in index order.
    template <typename F>
    void each_entity(F&& f) const;

    // ---- components
    template <typename T, typename... Args>
    T& emplace(Entity e, Args&&... args) {
        LANTERN_ASSERT(alive(e), "emplace on a dead or stale entity");
        check<T>(AccessKey::component, true);
        return assure<T>().emplace(e, tick_, std::forward<Args>(args)...);
    }
    // Adds or replaces; replacing marks the component changed.
    template <typename T, typename... Args>
    T& emplace_or_replace(Entity e, Args&&... args);
    template <typename T>
    void remove(Entity e) {
        LANTERN_ASSERT(alive(e), "remove on a dead or stale entity");
        check<T>(AccessKey::component, true);
        Pool<T>* p = find_pool<T>();
        std::uint32_t pos = p ? p->find(e) : PoolBase::absent;
        LANTERN_ASSERT(pos != PoolBase::absent, "remove of a component the entity does not have");
        p->erase_at(pos, tick_);
    }
    // Removes if present; returns whether it was.
    template <typename T>
    bool try_remove(Entity e) {
        check<T>(AccessKey::component, true);
        Pool<T>* p = find_pool<T>();
        std::uint32_t pos = p ? p->find(e) : PoolBase::absent;
        if (pos == PoolBase::absent) return false;
        p->erase_at(pos, tick_);
        return true;
    }
    template <typename T>
    T& get(Entity e) {
        Pool<T>* p = find_pool<T>();
        LANTERN_ASSERT(p != nullptr, "get of a component type no entity has");
        return p->get(e);
    }
    template <typename T>
    const T& get(Entity e) const {
        return const_cast<World*>(this)->get<T>(e);
    }
    template <typename T>
    T* try_get(Entity e) {
        Pool<T>* p = find_pool<T>();
        return p ? p->try_get(e) : nullptr;
    }
    template <typename T>
    const T* try_get(Entity e) const {
        return const_cast<World*>(this)->try_get<T>(e);
    }
    template <typename T>
    bool contains(Entity e) const {
        const Pool<T>* p = find_pool<T>();
        return p && p->contains(e);
    }
    // Marks the component changed at the current tick and returns it for writing.
    template <typename T>
    T& patch(Entity e) {
        check<T>(AccessKey::component, true);
        Pool<T>* p = find_pool<T>();
        std::uint32_t pos = p ? p->find(e) : PoolBase::absent;
        LANTERN_ASSERT(pos != PoolBase::absent, "patch of a component the entity does not have");
        p->mark_changed(pos, tick_);
        return p->at(pos);
    }
    template <typename T>
    void clear() {
        check<T>(AccessKey::component, true);
        if (Pool<T>* p = find_pool<T>()) p->clear(tick_);
    }
    template <typename T>
    std::uint32_t count() const {
        const Pool<T>* p = find_pool<T>();
        return p ? p->size() : 0;
    }

    template <typename T>
    Pool<T>& assure() {
        check<T>(AccessKey::component, false); // views start here
        TypeId id = component_id<T>();
        if (id >= pools_.size()) pools_.resize(id + 1);
        if (!pools_[id]) pools_[id] = std::make_unique<Pool<T>>();
        return static_cast<Pool<T>&>(*pools_[id]);
    }
    template <typename T>
    Pool<T>* find_pool() {
        check<T>(AccessKey::component, false);
        TypeId id = component_id<T>();
        return id < pools_.size() ? static_cast<Pool<T>*>(pools_[id].get()) : nullptr;
    }
    template <typename T>
    const Pool<T>* find_pool() const {
        return const_cast<World*>(this)->find_pool<T>();
    }
    PoolBase* pool_by_id(TypeId id) { return id < pools_.size() ? pools_[id].get() : nullptr; }

    // ---- views
    template <typename... T, typename... X>
    View<Include<T...>, Exclude<X...>> view(Exclude<X...> = {});

    // ---- resources (one value per type)
    template <typename T, typename... Args>
    T& set_resource(Args&&... args);
    template <typename T>
    T& resource() {
        T* r = try_resource<T>();
        LANTERN_ASSERT(r != nullptr, "resource not set");
        return *r;
    }
    template <typename T>
    T* try_resource() {
        check<T>(AccessKey::resource, false);
        TypeId id = resource_id<T>();
        if (id >= resources_.size() || !resources_[id]) return nullptr;
        return static_cast<T*>(resources_[id]->get());
    }
    // Grows the resource table to `count` slots (set_resource then never grows it for ids
    // below that; Schedule::run calls it before the systems start).
    void reserve_resource_slots(TypeId count) {
        if (count > resources_.size()) resources_.resize(count);
    }
    template <typename T>
    bool has_resource() const {
        TypeId id = resource_id<T>();
        return id < resources_.size() && resources_[id];
    }
    template <typename T>
    void remove_resource() {
        TypeId id = resource_id<T>();
        if (id < resources_.size()) resources_[id].reset();
    }

    // ---- ticks
    Tick tick() const { return tick_; }
    Tick advance_tick() { return ++tick_; }

    // Generation of the slot at `index` (views build handles from dense indices with it).
    std::uint32_t generation_at(std::uint32_t index) const { return slots_[index]; }

  private:
    template <typename T>
    static void check([[maybe_unused]] AccessKey::Kind kind, [[maybe_unused]] bool write) {
#if defined(LANTERN_ENABLE_ASSERTS)
        if (const SystemAccess* a = detail::current_access) {
            const AccessKey key{kind, kind == AccessKey::component ? component_id<T>() : resource_id<T>()};
            if (!detail::declared(*a, key, write)) [[unlikely]]
                detail::undeclared_access(*a, key, write, detail::type_name<T>());
        }
#endif
    }

    struct ResourceBase {
        virtual ~ResourceBase() = default;
        virtual void* get() = 0;
    };
    template <typename T>
    struct Resource final : ResourceBase {
        template <typename... Args>
        explicit Resource(Args&&... args) : value(std::forward<Args>(args)...) {}
        void* get() override { return &value; }
        T value;
    };

    bool is_free(std::uint32_t index) const { return (free_bits_[index >> 6] >> (index & 63)) & 1; }
    void set_free(std::uint32_t index, bool free);

    PodVector<std::uint32_t> slots_;     // generation per slot
    PodVector<std::uint64_t> free_bits_; // 1 = slot not alive
    PodVector<std::uint32_t> free_list_; // reusable slots, LIFO
    std::atomic<std::uint32_t> reserved_{0};
    std::uint32_t alive_count_ = 0;
    std::vector<std::unique_ptr<PoolBase>> pools_;
    std::vector<std::unique_ptr<ResourceBase>> resources_;
    Tick tick_ = 1;
};

template <typename T, typename... Args>
T& World::emplace_or_replace(Entity e, Args&&... args) {
    LANTERN_ASSERT(alive(e), "emplace_or_replace on a dead or stale entity");
    check<T>(AccessKey::component, true);
    Pool<T>& p = assure<T>();
    std::uint32_t pos = p.find(e);
    if (pos == PoolBase::absent) return p.emplace(e, tick_, std::forward<Args>(args)...);
    if constexpr (!Pool<T>::is_tag) {
        if constexpr (std::is_aggregate_v<T>)
            p.at(pos) = T{std::forward<Args>(args)...};
        else
            p.at(pos) = T(std::forward<Args>(args)...);
    }
    p.mark_changed(pos, tick_);
    return p.at(pos);
}

template <typename T, typename... Args>
T& World::set_resource(Args&&... args) {
    TypeId id = resource_id<T>();
    if (id >= resources_.size()) resources_.resize(id + 1);
    resources_[id] = std::make_unique<Resource<T>>(std::forward<Args>(args)...);
    return static_cast<Resource<T>&>(*resources_[id]).value;
}

template <typename F>
void World::each_entity(F&& f) const {
    for (std::uint32_t i = 0; i < slots_.size(); ++i)
        if (!is_free(i)) f(Entity{i, slots_[i]});
}

} // namespace lantern::ecs

#include "lantern/ecs/view.hpp"
