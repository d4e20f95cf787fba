// Entity handles: an index into the world's slots and the generation of that slot.
//
// A handle stays valid until its entity is destroyed; afterwards every use of it is
// detected (generations differ), and the slot's next entity never compares equal to it.
// A slot whose 32-bit generation is exhausted is retired, never reused, so handles are
// never aliased even after 2^32 reuses of one slot.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

namespace lantern::ecs {

struct Entity {
    static constexpr std::uint32_t null_index = ~0u;
    std::uint32_t index = null_index;
    std::uint32_t generation = 0;

    constexpr bool is_null() const { return index == null_index; }
    constexpr std::uint64_t bits() const { return (std::uint64_t(generation) << 32) | index; }
    friend constexpr bool operator==(Entity, Entity) = default;
    friend constexpr bool operator<(Entity a, Entity b) { return a.bits() < b.bits(); }
};

inline constexpr Entity null_entity{};

// Dense per-process ids for component and resource types, assigned on first use.
using TypeId = std::uint32_t;

namespace detail {
inline std::atomic<TypeId> next_component_id{0};
inline std::atomic<TypeId> next_resource_id{0};
inline constexpr TypeId unassigned_id = ~0u;

// A type's id lives in a constant-initialised atomic (no guard variable, no order of
// initialisation to respect): reading it is one relaxed load and a predictable branch, which
// matters in World::get's hot loops. The first use assigns it; racing first uses agree
// through the compare-exchange, and the losers' numbers are simply never used.
template <typename T, bool Resource>
struct TypeSlot {
    static inline std::atomic<TypeId> id{unassigned_id};
};

template <typename T, bool Resource>
[[gnu::noinline]] TypeId assign_id() {
    std::atomic<TypeId>& counter = Resource ? next_resource_id : next_component_id;
    TypeId expected = unassigned_id;
    TypeId fresh = counter.fetch_add(1, std::memory_order_relaxed);
    TypeSlot<T, Resource>::id.compare_exchange_strong(expected, fresh, std::memory_order_relaxed);
    return TypeSlot<T, Resource>::id.load(std::memory_order_relaxed);
}
} // namespace detail

template <typename T>
inline TypeId component_id() {
    TypeId id = detail::TypeSlot<T, false>::id.load(std::memory_order_relaxed);
    return id != detail::unassigned_id ? id : detail::assign_id<T, false>();
}

template <typename T>
inline TypeId resource_id() {
    TypeId id = detail::TypeSlot<T, true>::id.load(std::memory_order_relaxed);
    return id != detail::unassigned_id ? id : detail::assign_id<T, true>();
}

// Change ticks: the world's tick advances at sync points; "changed since t" means the
// element's tick is greater than t. 32 bits last 2 years at 60 ticks per second.
using Tick = std::uint32_t;

} // namespace lantern::ecs

template <>
struct std::hash<lantern::ecs::Entity> {
    std::size_t operator()(lantern::ecs::Entity e) const noexcept { return std::hash<std::uint64_t>{}(e.bits()); }
};
