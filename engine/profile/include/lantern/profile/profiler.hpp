// Frame profiler: CPU scopes on any thread, job spans, GPU pass timestamps, frame markers.
//
// Threads: record() and Scope may be used from any thread at any time. Each thread writes
// into its own fixed-size ring (no locks, no allocation on the hot path); the thread that
// calls end_frame() (normally the main thread) drains every ring into the frame history.
// begin_frame(), end_frame(), stats(), the reports and the exports must be called from that
// one thread. When a ring is full, new events are dropped and counted (dropped_events()).
//
// Names: every name is a `const char*` that must outlive the profiler. String literals are
// fine; build dynamic names once with intern() (which locks, so not per event).
//
// Lanes: each recording thread is one CPU lane ("main", "worker 1", ...; see
// set_thread_name). GPU queues are lanes too (add_gpu_lane), fed with timestamps that
// arrive frames later (record_gpu names the frame they belong to).
//
// Cost: with profiling disabled (the default) a Scope costs one relaxed atomic load. When
// enabled, two clock reads and a 32-byte store.
#pragma once

#include "lantern/core/result.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::profile {

enum class LaneKind : std::uint8_t { cpu, gpu };
enum class EventKind : std::uint8_t { scope, job, gpu };

struct Event {
    const char* name = nullptr;
    std::int64_t start_ns = 0;
    std::int64_t end_ns = 0;
    std::uint32_t lane = 0;
    EventKind kind = EventKind::scope;
};
static_assert(sizeof(Event) == 32, "Event is one half cache line");

struct Lane {
    std::string name;
    LaneKind kind = LaneKind::cpu;
};

struct Frame {
    std::uint64_t index = 0;
    std::int64_t start_ns = 0;
    std::int64_t end_ns = 0;
    std::vector<Event> events; // CPU events drained this frame plus GPU events of this frame
};

// Statistics of one name over the frame history. A frame's value is the sum of the
// durations of all events of that name in that frame; frames without the name are not
// counted (see frames_seen).
struct ScopeStats {
    const char* name = nullptr;
    LaneKind kind = LaneKind::cpu;
    std::uint32_t frames_seen = 0;
    double calls_per_frame = 0.0;
    double last_ms = 0.0, mean_ms = 0.0, p50_ms = 0.0, p95_ms = 0.0, p99_ms = 0.0, max_ms = 0.0;
};

struct Percentiles {
    double last = 0.0, mean = 0.0, p50 = 0.0, p95 = 0.0, p99 = 0.0, max = 0.0;
    std::uint32_t count = 0;
};

// Nearest-rank percentiles of `values` (copied and sorted). `last` is values.back().
Percentiles percentiles(std::vector<double> values);

void set_enabled(bool enabled);
bool enabled();

// Keeps the last `frames` frames (default 300). Clears the history.
void set_history_size(std::uint32_t frames);

// Names the calling thread's lane. The first thread to record is "main" unless named.
void set_thread_name(const char* name);

// Returns a stable copy of `name` that lives as long as the process.
const char* intern(std::string_view name);

// Records a finished span on the calling thread's lane (used by the job system).
void record(const char* name, std::int64_t start_ns, std::int64_t end_ns, EventKind kind = EventKind::scope);

std::uint32_t add_gpu_lane(const char* name);
// A GPU span of frame `frame_index`, in the CPU clock's nanoseconds (convert timestamps first).
void record_gpu(std::uint32_t lane, std::uint64_t frame_index, const char* name, std::int64_t start_ns,
                std::int64_t end_ns);

void begin_frame();
void end_frame();
// Drains the thread rings into the current frame without ending it.
void flush();
std::uint64_t frame_index(); // index of the frame begun last (0 before the first)

std::uint64_t dropped_events();
std::vector<Lane> lanes();
// Frames in the history, oldest first.
std::vector<const Frame*> history();
std::vector<ScopeStats> stats();
Percentiles frame_time_ms();

// Plain-text table of every scope, GPU pass and the frame time.
std::string text_report();
// Chrome trace-event JSON of the last `max_frames` frames (0 = the whole history): one
// lane per thread, GPU lanes in their own process, frame markers. Written atomically.
Result<void> write_chrome_trace(const std::string& path, std::uint32_t max_frames = 0);
std::string chrome_trace_json(std::uint32_t max_frames = 0);

// Clears history, lanes' events and counters (for tests; no thread may be recording).
void reset();

class Scope {
  public:
    explicit Scope(const char* name) : name_(enabled() ? name : nullptr) {
        if (name_) start_ = now();
    }
    ~Scope() {
        if (name_) record(name_, start_, now());
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

  private:
    static std::int64_t now();
    const char* name_;
    std::int64_t start_ = 0;
};

} // namespace lantern::profile

#define LANTERN_PROFILE_CONCAT_(a, b) a##b
#define LANTERN_PROFILE_CONCAT(a, b) LANTERN_PROFILE_CONCAT_(a, b)
#define LANTERN_PROFILE_SCOPE(name)                                                            \
    ::lantern::profile::Scope LANTERN_PROFILE_CONCAT(lantern_profile_scope_, __LINE__)(name)
