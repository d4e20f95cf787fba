// Component storage: one sparse set per component type.
//
// Layout: `dense_` lists the entity indices that have the component, packed; `data_` holds
// the components in the same order (contiguous, cache-friendly iteration); `ticks_` holds
// when each was added and last changed. The paged sparse array maps an entity index to its
// dense position and the generation it was added under, so `get` checks a handle and finds
// the component with two dependent loads. Removal swaps the last element into the hole.
// docs/ecs.md explains why Lantern uses sparse sets rather than archetype tables.
//
// Threads: concurrent reads are safe; any mutation needs exclusive access. The World
// enforces that structural changes do not happen while a view iterates this pool.
#pragma once

#include "lantern/core/assert.hpp"
#include "lantern/ecs/entity.hpp"
#include "lantern/ecs/pod_vector.hpp"

#include <atomic>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace lantern::ecs {

struct ComponentTicks {
    Tick added = 0;
    Tick changed = 0;
};

class PoolBase {
  public:
    static constexpr std::uint32_t page_bits = 12;
    static constexpr std::uint32_t page_size = 1u << page_bits;
    static constexpr std::uint32_t absent = ~0u;

    struct SparseEntry {
        std::uint32_t dense = absent;
        std::uint32_t generation = 0;
    };

    virtual ~PoolBase() = default;

    std::uint32_t size() const { return static_cast<std::uint32_t>(dense_.size()); }
    bool empty() const { return dense_.empty(); }
    const std::uint32_t* indices() const { return dense_.data(); }
    const ComponentTicks* ticks() const { return ticks_.data(); }

    // Dense position of `e`'s component, or `absent` (also for stale handles).
    std::uint32_t find(Entity e) const {
        const SparseEntry* entry = sparse_entry(e.index);
        return (entry && entry->dense != absent && entry->generation == e.generation) ? entry->dense : absent;
    }
    bool contains(Entity e) const { return find(e) != absent; }

    // Dense position by entity index alone (the caller knows the entity is alive).
    std::uint32_t find_index(std::uint32_t index) const {
        const SparseEntry* entry = sparse_entry(index);
        return entry ? entry->dense : absent;
    }
    // As find_index, trying `hint` first: pools filled in the same order line up, and the
    // check turns a random sparse lookup into a sequential compare.
    std::uint32_t find_index_hinted(std::uint32_t index, std::uint32_t hint) const {
        if (hint < dense_.size() && dense_[hint] == index) return hint;
        return find_index(index);
    }

    // Change tracking (see World::patch and View::each_changed).
    Tick last_added() const { return last_added_; }
    Tick last_changed() const { return last_changed_; }
    Tick last_removed() const { return last_removed_; }
    void mark_changed(std::uint32_t dense, Tick tick) {
        ticks_[dense].changed = tick;
        last_changed_ = tick;
    }
    // Element tick only (safe from parallel iterations over distinct elements); call
    // touch() once afterwards to update the pool-level tick.
    void mark_changed_at(std::uint32_t dense, Tick tick) { ticks_[dense].changed = tick; }
    void touch(Tick tick) {
        if (!dense_.empty()) last_changed_ = tick;
    }

    // Type-erased operations used by World::destroy and command buffers.
    virtual void erase_at(std::uint32_t dense, Tick tick) = 0;
    virtual void emplace_moved(Entity e, void* value, Tick tick) = 0; // add or replace
    virtual void clear(Tick tick) = 0;

    // Views lock the pools they iterate; structural changes assert the lock is free.
    std::atomic<std::int32_t>& iteration_lock() { return iterating_; }
    bool locked() const { return iterating_.load(std::memory_order_relaxed) != 0; }

  protected:
    const SparseEntry* sparse_entry(std::uint32_t index) const {
        std::uint32_t page = index >> page_bits;
        if (page >= pages_.size() || !pages_[page]) return nullptr;
        return &pages_[page][index & (page_size - 1)];
    }
    SparseEntry& assure_entry(std::uint32_t index) {
        std::uint32_t page = index >> page_bits;
        if (page >= pages_.size()) pages_.resize(page + 1);
        if (!pages_[page]) pages_[page].reset(new SparseEntry[page_size]);
        return pages_[page][index & (page_size - 1)];
    }
    // Appends `e` to the sparse and dense arrays; returns its dense position.
    std::uint32_t push_index(Entity e, Tick tick) {
        SparseEntry& entry = assure_entry(e.index);
        LANTERN_ASSERT(entry.dense == absent, "entity already has this component");
        entry.dense = static_cast<std::uint32_t>(dense_.size());
        entry.generation = e.generation;
        dense_.push_back(e.index);
        ticks_.push_back({tick, tick});
        last_added_ = last_changed_ = tick;
        return entry.dense;
    }
    // Swap-removes the index at `dense`; returns the position that moved into it (or absent).
    std::uint32_t pop_index(std::uint32_t dense, Tick tick) {
        std::uint32_t last = static_cast<std::uint32_t>(dense_.size() - 1);
        std::uint32_t removed = dense_[dense];
        assure_entry(removed).dense = absent;
        if (dense != last) {
            std::uint32_t moved = dense_[last];
            dense_[dense] = moved;
            ticks_[dense] = ticks_[last];
            assure_entry(moved).dense = dense;
        }
        dense_.pop_back();
        ticks_.pop_back();
        last_removed_ = tick;
        return dense != last ? dense : absent;
    }
    void assert_unlocked() const {
        LANTERN_ASSERT(!locked(), "structural change to a component pool while a view iterates it "
                                  "(use a CommandBuffer inside iterations)");
    }

    std::vector<std::unique_ptr<SparseEntry[]>> pages_;
    PodVector<std::uint32_t> dense_;
    PodVector<ComponentTicks> ticks_;
    Tick last_added_ = 0, last_changed_ = 0, last_removed_ = 0;
    std::atomic<std::int32_t> iterating_{0};
};

template <typename T>
class Pool final : public PoolBase {
  public:
    static constexpr bool is_tag = std::is_empty_v<T>;

    template <typename... Args>
    T& emplace(Entity e, Tick tick, Args&&... args) {
        assert_unlocked();
        std::uint32_t pos = push_index(e, tick);
        if constexpr (is_tag) {
            (void)pos;
            return tag_;
        } else {
            if constexpr (std::is_aggregate_v<T>)
                data_.push_back(T{std::forward<Args>(args)...});
            else
                data_.emplace_back(std::forward<Args>(args)...);
            return data_.back();
        }
    }

    void erase_at(std::uint32_t dense, Tick tick) override {
        assert_unlocked();
        std::uint32_t last = size() - 1;
        pop_index(dense, tick);
        if constexpr (!is_tag) {
            if (dense != last) data_[dense] = std::move(data_[last]);
            data_.pop_back();
        }
    }

    void emplace_moved(Entity e, void* value, Tick tick) override {
        std::uint32_t pos = find(e);
        if (pos != absent) {
            if constexpr (!is_tag) data_[pos] = std::move(*static_cast<T*>(value));
            mark_changed(pos, tick);
        } else if constexpr (is_tag) {
            emplace(e, tick);
        } else {
            emplace(e, tick, std::move(*static_cast<T*>(value)));
        }
    }

    void clear(Tick tick) override {
        assert_unlocked();
        for (std::uint32_t index : dense_) assure_entry(index).dense = absent;
        dense_.clear();
        ticks_.clear();
        if constexpr (!is_tag) data_.clear();
        if (tick) last_removed_ = tick;
    }

    // Component at a dense position (views) or of a live entity (asserts when absent).
    T& at(std::uint32_t dense) {
        if constexpr (is_tag) {
            (void)dense;
            return tag_;
        } else {
            return data_[dense];
        }
    }
    T& get(Entity e) {
        std::uint32_t pos = find(e);
        LANTERN_ASSERT(pos != absent, "entity does not have this component (or the handle is stale)");
        return at(pos);
    }
    T* try_get(Entity e) {
        std::uint32_t pos = find(e);
        return pos == absent ? nullptr : &at(pos);
    }
    T* data() {
        if constexpr (is_tag)
            return nullptr;
        else
            return data_.data();
    }
    void reserve(std::uint32_t n) {
        dense_.reserve(n);
        ticks_.reserve(n);
        if constexpr (!is_tag) data_.reserve(n);
    }

  private:
    // Trivially copyable components grow without copies (see PodVector).
    std::conditional_t<pod_vector_compatible<T> && !is_tag, PodVector<T>, std::vector<T>> data_;
    struct NoTag {};
    [[no_unique_address]] std::conditional_t<is_tag, T, NoTag> tag_{};
};

} // namespace lantern::ecs
