#include "lantern/ecs/world.hpp"

#include <algorithm>
#include <string>

namespace lantern::ecs {

namespace detail {

void undeclared_access(const SystemAccess& access, AccessKey key, bool write, const char* type_name) {
    const bool component = key.kind == AccessKey::component;
    const std::string message = std::string("system '") + access.name + "' " + (write ? "writes " : "touches ") +
                                (component ? "component " : "resource ") + type_name +
                                " without declaring it: add ." + (write ? "writes" : "reads") +
                                (component ? "" : "_resource") + "<" + type_name + ">() where it is added";
    ::lantern::detail::assert_fail("declared access", message.c_str(), __FILE__, __LINE__);
}

} // namespace detail

World::World() = default;
World::~World() = default;

void World::set_free(std::uint32_t index, bool free) {
    std::uint64_t bit = std::uint64_t(1) << (index & 63);
    if (free)
        free_bits_[index >> 6] |= bit;
    else
        free_bits_[index >> 6] &= ~bit;
}

Entity World::create() {
    if (reserved_.load(std::memory_order_relaxed) != slots_.size()) [[unlikely]]
        flush_reserved();
    std::uint32_t index;
    if (!free_list_.empty()) {
        index = free_list_.back();
        free_list_.pop_back();
    } else {
        index = static_cast<std::uint32_t>(slots_.size());
        LANTERN_VERIFY(index != Entity::null_index, "entity index space exhausted");
        slots_.push_back(0);
        if ((index >> 6) >= free_bits_.size()) free_bits_.push_back(0);
        reserved_.store(index + 1, std::memory_order_relaxed);
    }
    set_free(index, false);
    ++alive_count_;
    return Entity{index, slots_[index]};
}

Entity World::reserve() {
    // Fresh indices only, so reservation never races with the free list.
    std::uint32_t index = reserved_.fetch_add(1, std::memory_order_relaxed);
    LANTERN_VERIFY(index != Entity::null_index, "entity index space exhausted");
    return Entity{index, 0};
}

void World::flush_reserved() {
    // Invariant: reserved_ >= slots_.size(); the difference is outstanding reservations.
    std::uint32_t end = reserved_.load(std::memory_order_relaxed);
    while (slots_.size() < end) {
        std::uint32_t index = static_cast<std::uint32_t>(slots_.size());
        slots_.push_back(0);
        if ((index >> 6) >= free_bits_.size()) free_bits_.push_back(0);
        set_free(index, false);
        ++alive_count_;
    }
}

void World::destroy(Entity e) {
    LANTERN_ASSERT(alive(e), "destroy of a dead or stale entity");
    for (auto& pool : pools_) {
        if (!pool) continue;
        std::uint32_t pos = pool->find_index(e.index);
        if (pos != PoolBase::absent) pool->erase_at(pos, tick_);
    }
    set_free(e.index, true);
    --alive_count_;
    // Retire a slot whose generation would wrap: its handles must never alias.
    if (++slots_[e.index] != ~0u) free_list_.push_back(e.index);
}

} // namespace lantern::ecs
