// Text report and Chrome trace-event export, built on the public history API.
#include "lantern/core/file.hpp"
#include "lantern/profile/profiler.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

namespace lantern::profile {
namespace {

void append_escaped(std::string& out, const char* s) {
    for (; s && *s; ++s) {
        char c = *s;
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof(buf), "\\u%04x", c);
            out += buf;
        } else {
            out += c;
        }
    }
}

void append_fmt(std::string& out, const char* fmt, double a, double b) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), fmt, a, b);
    out += buf;
}

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

    // pid 1: CPU lanes (tid = lane + 1, tid 0 = frame markers); pid 2: GPU lanes.
    std::string out = "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n";
    out += "{\"ph\":\"M\",\"pid\":1,\"name\":\"process_name\",\"args\":{\"name\":\"Lantern CPU\"}},\n";
    out += "{\"ph\":\"M\",\"pid\":2,\"name\":\"process_name\",\"args\":{\"name\":\"Lantern GPU\"}},\n";
    out += "{\"ph\":\"M\",\"pid\":1,\"tid\":0,\"name\":\"thread_name\",\"args\":{\"name\":\"frames\"}},\n";
    for (std::size_t i = 0; i < all_lanes.size(); ++i) {
        int pid = all_lanes[i].kind == LaneKind::gpu ? 2 : 1;
        out += "{\"ph\":\"M\",\"pid\":" + std::to_string(pid) + ",\"tid\":" + std::to_string(i + 1) +
               ",\"name\":\"thread_name\",\"args\":{\"name\":\"";
        append_escaped(out, all_lanes[i].name.c_str());
        out += "\"}},\n";
    }
    auto append_span = [&](const char* name, const char* cat, int pid, std::uint64_t tid, std::int64_t start,
                           std::int64_t end) {
        out += "{\"ph\":\"X\",\"name\":\"";
        append_escaped(out, name);
        out += "\",\"cat\":\"";
        out += cat;
        out += "\",\"pid\":" + std::to_string(pid) + ",\"tid\":" + std::to_string(tid);
        append_fmt(out, ",\"ts\":%.3f,\"dur\":%.3f},\n", double(start - origin) * 1e-3,
                   double(std::max<std::int64_t>(end - start, 0)) * 1e-3);
    };
    for (const Frame* f : frames) {
        std::string name = "frame " + std::to_string(f->index);
        append_span(name.c_str(), "frame", 1, 0, f->start_ns, f->end_ns);
        for (const Event& e : f->events) {
            const char* cat = e.kind == EventKind::job ? "job" : e.kind == EventKind::gpu ? "gpu" : "scope";
            int pid = e.kind == EventKind::gpu ? 2 : 1;
            append_span(e.name, cat, pid, e.lane + 1, e.start_ns, e.end_ns);
        }
    }
    // Close the array without a trailing comma.
    if (out.size() >= 2 && out[out.size() - 2] == ',') out.erase(out.size() - 2, 1);
    out += "]}\n";
    return out;
}

Result<void> write_chrome_trace(const std::string& path, std::uint32_t max_frames) {
    return write_file_atomic(path, chrome_trace_json(max_frames));
}

} // namespace lantern::profile
