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
} // namespace detail

template <typename T>
TypeId component_id() {
    static const TypeId id = detail::next_component_id.fetch_add(1, std::memory_order_relaxed);
    return id;
}

template <typename T>
TypeId resource_id() {
    static const TypeId id = detail::next_resource_id.fetch_add(1, std::memory_order_relaxed);
    return id;
}

// Change ticks: the world's tick advances at sync points; "changed since t" means the
// element's tick is greater than t. 32 bits last 2 years at 60 ticks per second.
using Tick = std::uint32_t;

} // namespace lantern::ecs

template <>
struct std::hash<lantern::ecs::Entity> {
    std::size_t operator()(lantern::ecs::Entity e) const noexcept { return std::hash<std::uint64_t>{}(e.bits()); }
};
