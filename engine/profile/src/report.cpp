// Text report and Chrome trace-event export, built on the public history API.
#include "lantern/core/file.hpp"
#include "lantern/core/json_writer.hpp"
#include "lantern/profile/profiler.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>

namespace lantern::profile {
namespace {

std::vector<const Frame*> last_frames(std::uint32_t max_frames) {
    auto frames = history();
    if (max_frames != 0 && frames.size() > max_frames)
        frames.erase(frames.begin(), frames.end() - max_frames);
    return frames;
}

} // namespace

std::string text_report() {
    std::string out;
    char line[256];
    Percentiles ft = frame_time_ms();
    std::snprintf(line, sizeof(line),
                  "Lantern profile: %u frames in history, frame time ms: last %.3f mean %.3f p50 %.3f "
                  "p95 %.3f p99 %.3f max %.3f\n",
                  ft.count, ft.last, ft.mean, ft.p50, ft.p95, ft.p99, ft.max);
    out += line;
    std::snprintf(line, sizeof(line), "%-4s %-32s %7s %8s %8s %8s %8s %8s %8s %8s\n", "lane", "scope",
                  "frames", "calls/f", "last", "mean", "p50", "p95", "p99", "max");
    out += line;
    for (const ScopeStats& s : stats()) {
        std::snprintf(line, sizeof(line), "%-4s %-32.32s %7u %8.1f %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f\n",
                      s.kind == LaneKind::gpu ? "gpu" : "cpu", s.name, s.frames_seen, s.calls_per_frame,
                      s.last_ms, s.mean_ms, s.p50_ms, s.p95_ms, s.p99_ms, s.max_ms);
        out += line;
    }
    out += "(times in ms per frame: the sum of all spans of a name within a frame)\n";
    if (std::uint64_t dropped = dropped_events()) {
        std::snprintf(line, sizeof(line), "warning: %llu events dropped (ring full or frame too old)\n",
                      static_cast<unsigned long long>(dropped));
        out += line;
    }
    return out;
}

std::string chrome_trace_json(std::uint32_t max_frames) {
    auto frames = last_frames(max_frames);
    auto all_lanes = lanes();
    std::int64_t origin = frames.empty() ? 0 : frames.front()->start_ns;
    for (const Frame* f : frames)
        for (const Event& e : f->events) origin = std::min(origin, e.start_ns);

    // pid 1: CPU lanes (tid = lane + 1, tid 0 = frame markers); pid 2: GPU lanes. One event a line.
    json::Writer w;
    w.begin_object().field("displayTimeUnit", "ms").key("traceEvents").begin_array();
    auto metadata = [&](const char* what, int pid, std::optional<std::size_t> tid, std::string_view name) {
        w.begin_object(json::Layout::one_line).field("ph", "M").field("pid", pid);
        if (tid) w.field("tid", *tid);
        w.field("name", what).key("args").begin_object().field("name", name).end().end();
    };
    metadata("process_name", 1, std::nullopt, "Lantern CPU");
    metadata("process_name", 2, std::nullopt, "Lantern GPU");
    metadata("thread_name", 1, 0, "frames");
    for (std::size_t i = 0; i < all_lanes.size(); ++i)
        metadata("thread_name", all_lanes[i].kind == LaneKind::gpu ? 2 : 1, i + 1, all_lanes[i].name);
    auto span = [&](std::string_view name, const char* cat, int pid, std::uint64_t tid, std::int64_t start,
                    std::int64_t end) {
        w.begin_object(json::Layout::one_line).field("ph", "X").field("name", name).field("cat", cat);
        w.field("pid", pid).field("tid", tid).field("ts", double(start - origin) * 1e-3, 3);
        w.field("dur", double(std::max<std::int64_t>(end - start, 0)) * 1e-3, 3).end();
    };
    for (const Frame* f : frames) {
        span("frame " + std::to_string(f->index), "frame", 1, 0, f->start_ns, f->end_ns);
        for (const Event& e : f->events) {
            const char* cat = e.kind == EventKind::job ? "job" : e.kind == EventKind::gpu ? "gpu" : "scope";
            span(e.name, cat, e.kind == EventKind::gpu ? 2 : 1, e.lane + 1, e.start_ns, e.end_ns);
        }
    }
    return w.end().end().take();
}

Result<void> write_chrome_trace(const std::string& path, std::uint32_t max_frames) {
    return write_file_atomic(path, chrome_trace_json(max_frames));
}

} // namespace lantern::profile
