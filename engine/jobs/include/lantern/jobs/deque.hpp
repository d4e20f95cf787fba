// Bounded Chase-Lev work-stealing deque of pointers (Le, Pop, Cohen, Zappa Nardelli 2013).
//
// Threads: push() and pop() only from the owning thread (LIFO end); steal() from any thread
// (FIFO end). push() fails when the deque holds `Capacity` items; the job system then runs
// the job inline, so memory stays bounded and nothing is ever lost.
//
// The usual fences are folded into seq_cst operations on top/bottom so that ThreadSanitizer,
// which does not model stand-alone fences, checks the real synchronisation.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace lantern::jobs {

template <typename T, std::uint32_t Capacity = 4096>
class WorkStealingDeque {
    static_assert((Capacity & (Capacity - 1)) == 0, "capacity must be a power of two");

  public:
    WorkStealingDeque() {
        for (auto& s : slots_) s.store(nullptr, std::memory_order_relaxed);
    }

    // The store of bottom is seq_cst: it doubles as the store half of the job system's
    // sleep/wake handshake (JobSystem::submit reads the sleeper count right after it).
    bool push(T* item) {
        std::int64_t b = bottom_.load(std::memory_order_relaxed);
        // top only grows, so a stale copy can only make the deque look fuller than it is:
        // re-read the shared top (a line thieves write) only when the copy says full.
        if (b - top_cache_ >= std::int64_t(Capacity)) {
            top_cache_ = top_.load(std::memory_order_acquire);
            if (b - top_cache_ >= std::int64_t(Capacity)) return false;
        }
        slots_[std::size_t(b) & (Capacity - 1)].store(item, std::memory_order_relaxed);
        bottom_.store(b + 1, std::memory_order_seq_cst);
        return true;
    }

    T* pop() {
        // Cheap exit when empty, without writing `bottom_` (a line thieves read): bottom is
        // exact for the owner and top only grows, so b <= an old top means empty now.
        if (bottom_.load(std::memory_order_relaxed) <= top_.load(std::memory_order_relaxed)) return nullptr;
        std::int64_t b = bottom_.load(std::memory_order_relaxed) - 1;
        bottom_.store(b, std::memory_order_seq_cst);
        std::int64_t t = top_.load(std::memory_order_seq_cst);
        if (t > b) { // empty
            bottom_.store(b + 1, std::memory_order_relaxed);
            return nullptr;
        }
        T* item = slots_[std::size_t(b) & (Capacity - 1)].load(std::memory_order_relaxed);
        if (t == b) { // last item: race the thieves for it
            if (!top_.compare_exchange_strong(t, t + 1, std::memory_order_seq_cst, std::memory_order_relaxed))
                item = nullptr;
            bottom_.store(b + 1, std::memory_order_relaxed);
        }
        return item;
    }

    T* steal() {
        std::int64_t t = top_.load(std::memory_order_seq_cst);
        std::int64_t b = bottom_.load(std::memory_order_seq_cst);
        if (t >= b) return nullptr;
        T* item = slots_[std::size_t(t) & (Capacity - 1)].load(std::memory_order_relaxed);
        if (!top_.compare_exchange_strong(t, t + 1, std::memory_order_seq_cst, std::memory_order_relaxed))
            return nullptr; // lost the race; the caller looks elsewhere
        return item;
    }

    // How many items a thief saw: a hint (it may change before the caller acts on it).
    std::int64_t size_hint() const {
        std::int64_t n = bottom_.load(std::memory_order_relaxed) - top_.load(std::memory_order_relaxed);
        return n > 0 ? n : 0;
    }

    static constexpr std::uint32_t capacity() { return Capacity; }

    // Whether the deque looked empty at some instant during the call. The loads are seq_cst
    // so that a thread about to sleep cannot miss a push it must see (JobSystem::idle_sleep).
    bool empty_hint() const {
        return bottom_.load(std::memory_order_seq_cst) <= top_.load(std::memory_order_seq_cst);
    }

  private:
    alignas(64) std::atomic<std::int64_t> top_{0};
    alignas(64) std::atomic<std::int64_t> bottom_{0};
    std::int64_t top_cache_ = 0; // owner's copy of top_
    alignas(64) std::array<std::atomic<T*>, Capacity> slots_;
};

} // namespace lantern::jobs
