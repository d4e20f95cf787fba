#include "lantern/profile/profiler.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/clock.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>

namespace lantern::profile {
namespace {

// Single-producer (the owning thread) / single-consumer (the frame thread) ring.
struct ThreadBuffer {
    static constexpr std::uint64_t capacity = 1u << 15; // 32768 events, 1 MiB
    std::unique_ptr<Event[]> ring{new Event[capacity]};
    std::atomic<std::uint64_t> head{0};
    std::atomic<std::uint64_t> tail{0};
    std::atomic<bool> in_use{true};
    std::uint32_t lane = 0;
};

struct State {
    std::atomic<bool> enabled{false};
    std::atomic<std::uint64_t> dropped{0};
    std::mutex mutex; // registration, lanes, interned names
    std::vector<std::unique_ptr<ThreadBuffer>> buffers;
    std::vector<Lane> lanes;
    std::set<std::string, std::less<>> interned;

    // Frame history (frame thread only).
    std::vector<Frame> frames = std::vector<Frame>(300);
    std::size_t next = 0;  // slot the next frame goes to
    std::size_t count = 0; // committed frames in the ring
    Frame* open = nullptr;
    std::uint64_t frame_counter = 0;
    std::vector<Event> pending; // drained while no frame was open
};

State& state() {
    static State* s = new State; // leaked on purpose: thread_local destructors may outlive statics
    return *s;
}

struct ThreadHandle {
    ThreadBuffer* buffer = nullptr;
    ~ThreadHandle() {
        if (buffer) buffer->in_use.store(false, std::memory_order_release);
    }
};
thread_local ThreadHandle tls_handle;

ThreadBuffer& acquire_buffer(const char* name) {
    State& s = state();
    std::lock_guard lock(s.mutex);
    ThreadBuffer* found = nullptr;
    for (auto& b : s.buffers) {
        bool drained = b->head.load(std::memory_order_acquire) == b->tail.load(std::memory_order_acquire);
        if (!b->in_use.load(std::memory_order_acquire) && drained) {
            found = b.get();
            found->in_use.store(true, std::memory_order_relaxed);
            break;
        }
    }
    if (!found) {
        s.buffers.push_back(std::make_unique<ThreadBuffer>());
        found = s.buffers.back().get();
        found->lane = static_cast<std::uint32_t>(s.lanes.size());
        s.lanes.push_back({});
    }
    s.lanes[found->lane] = Lane{name ? std::string(name) : "thread " + std::to_string(found->lane), LaneKind::cpu};
    return *found;
}

ThreadBuffer& thread_buffer() {
    if (!tls_handle.buffer) tls_handle.buffer = &acquire_buffer(nullptr);
    return *tls_handle.buffer;
}

void drain_into(std::vector<Event>& out) {
    State& s = state();
    std::lock_guard lock(s.mutex);
    for (auto& b : s.buffers) {
        std::uint64_t tail = b->tail.load(std::memory_order_relaxed);
        std::uint64_t head = b->head.load(std::memory_order_acquire);
        for (std::uint64_t i = tail; i < head; ++i) {
            Event e = b->ring[i & (ThreadBuffer::capacity - 1)];
            e.lane = b->lane;
            out.push_back(e);
        }
        b->tail.store(head, std::memory_order_release);
    }
}

} // namespace

std::int64_t Scope::now() { return now_ns(); }

void set_enabled(bool on) { state().enabled.store(on, std::memory_order_relaxed); }
bool enabled() { return state().enabled.load(std::memory_order_relaxed); }

void set_history_size(std::uint32_t frames) {
    State& s = state();
    LANTERN_ASSERT(frames > 0, "history must hold at least one frame");
    LANTERN_ASSERT(s.open == nullptr, "set_history_size inside a frame");
    s.frames = std::vector<Frame>(frames);
    s.next = 0;
    s.count = 0;
}

void set_thread_name(const char* name) {
    if (!tls_handle.buffer) {
        tls_handle.buffer = &acquire_buffer(name);
        return;
    }
    State& s = state();
    std::lock_guard lock(s.mutex);
    s.lanes[tls_handle.buffer->lane].name = name;
}

const char* intern(std::string_view name) {
    State& s = state();
    std::lock_guard lock(s.mutex);
    auto it = s.interned.find(name);
    if (it == s.interned.end()) it = s.interned.emplace(name).first;
    return it->c_str();
}

void record(const char* name, std::int64_t start_ns, std::int64_t end_ns, EventKind kind) {
    ThreadBuffer& b = thread_buffer();
    std::uint64_t head = b.head.load(std::memory_order_relaxed);
    std::uint64_t tail = b.tail.load(std::memory_order_acquire);
    if (head - tail >= ThreadBuffer::capacity) {
        state().dropped.fetch_add(1, std::memory_order_relaxed);
        return;
    }
    Event& e = b.ring[head & (ThreadBuffer::capacity - 1)];
    e.name = name;
    e.start_ns = start_ns;
    e.end_ns = end_ns;
    e.lane = b.lane;
    e.kind = kind;
    b.head.store(head + 1, std::memory_order_release);
}

std::uint32_t add_gpu_lane(const char* name) {
    State& s = state();
    std::lock_guard lock(s.mutex);
    s.lanes.push_back(Lane{name, LaneKind::gpu});
    return static_cast<std::uint32_t>(s.lanes.size() - 1);
}

void record_gpu(std::uint32_t lane, std::uint64_t frame_index, const char* name, std::int64_t start_ns,
                std::int64_t end_ns) {
    State& s = state();
    Event e{name, start_ns, end_ns, lane, EventKind::gpu};
    if (s.open && s.open->index == frame_index) {
        s.open->events.push_back(e);
        return;
    }
    for (auto& f : s.frames) {
        if (f.index == frame_index && f.index != 0) {
            f.events.push_back(e);
            return;
        }
    }
    s.dropped.fetch_add(1, std::memory_order_relaxed); // frame already left the history
}

void begin_frame() {
    State& s = state();
    LANTERN_ASSERT(s.open == nullptr, "begin_frame() twice without end_frame()");
    Frame& f = s.frames[s.next];
    f.index = ++s.frame_counter;
    f.events.clear();
    f.events.swap(s.pending);
    f.start_ns = now_ns();
    f.end_ns = f.start_ns;
    s.open = &f;
}

void end_frame() {
    State& s = state();
    LANTERN_ASSERT(s.open != nullptr, "end_frame() without begin_frame()");
    drain_into(s.open->events);
    s.open->end_ns = now_ns();
    s.open = nullptr;
    s.next = (s.next + 1) % s.frames.size();
    s.count = std::min(s.count + 1, s.frames.size());
}

void flush() {
    State& s = state();
    drain_into(s.open ? s.open->events : s.pending);
}

std::uint64_t frame_index() { return state().frame_counter; }
std::uint64_t dropped_events() { return state().dropped.load(std::memory_order_relaxed); }

std::vector<Lane> lanes() {
    State& s = state();
    std::lock_guard lock(s.mutex);
    return s.lanes;
}

std::vector<const Frame*> history() {
    State& s = state();
    std::vector<const Frame*> out;
    out.reserve(s.count);
    std::size_t n = s.frames.size();
    for (std::size_t i = 0; i < s.count; ++i) out.push_back(&s.frames[(s.next + n - s.count + i) % n]);
    return out;
}

Percentiles percentiles(std::vector<double> values) {
    Percentiles p;
    if (values.empty()) return p;
    p.count = static_cast<std::uint32_t>(values.size());
    p.last = values.back();
    double sum = 0.0;
    for (double v : values) sum += v;
    p.mean = sum / double(values.size());
    std::sort(values.begin(), values.end());
    auto rank = [&](double q) {
        std::size_t k = static_cast<std::size_t>(std::ceil(q * double(values.size())));
        return values[std::clamp<std::size_t>(k, 1, values.size()) - 1];
    };
    p.p50 = rank(0.50);
    p.p95 = rank(0.95);
    p.p99 = rank(0.99);
    p.max = values.back();
    return p;
}

std::vector<ScopeStats> stats() {
    struct Acc {
        const char* name = nullptr;
        std::vector<double> per_frame;
        std::uint64_t calls = 0;
        std::uint64_t last_frame = ~0ull;
    };
    std::map<std::pair<std::string_view, LaneKind>, Acc> acc;
    for (const Frame* f : history()) {
        for (const Event& e : f->events) {
            LaneKind kind = e.kind == EventKind::gpu ? LaneKind::gpu : LaneKind::cpu;
            Acc& a = acc[{std::string_view(e.name), kind}];
            a.name = e.name;
            if (a.last_frame != f->index) {
                a.per_frame.push_back(0.0);
                a.last_frame = f->index;
            }
            a.per_frame.back() += double(e.end_ns - e.start_ns) * 1e-6;
            ++a.calls;
        }
    }
    std::vector<ScopeStats> out;
    for (auto& [key, a] : acc) {
        Percentiles p = percentiles(a.per_frame);
        ScopeStats st;
        st.name = a.name;
        st.kind = key.second;
        st.frames_seen = p.count;
        st.calls_per_frame = double(a.calls) / double(p.count);
        st.last_ms = p.last;
        st.mean_ms = p.mean;
        st.p50_ms = p.p50;
        st.p95_ms = p.p95;
        st.p99_ms = p.p99;
        st.max_ms = p.max;
        out.push_back(st);
    }
    std::sort(out.begin(), out.end(), [](const ScopeStats& a, const ScopeStats& b) {
        if (a.kind != b.kind) return a.kind < b.kind;
        return a.mean_ms > b.mean_ms;
    });
    return out;
}

Percentiles frame_time_ms() {
    std::vector<double> values;
    for (const Frame* f : history()) values.push_back(double(f->end_ns - f->start_ns) * 1e-6);
    return percentiles(std::move(values));
}

void reset() {
    State& s = state();
    LANTERN_ASSERT(s.open == nullptr, "reset() inside a frame");
    std::vector<Event> discard;
    drain_into(discard);
    for (auto& f : s.frames) {
        f.events.clear();
        f.index = 0;
    }
    s.pending.clear();
    s.next = 0;
    s.count = 0;
    s.dropped.store(0, std::memory_order_relaxed);
}

} // namespace lantern::profile
