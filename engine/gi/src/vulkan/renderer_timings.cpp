// The renderer's timestamp query sets (renderer.hpp: begin_frame, completed_timings,
// wait_timings): three rotate, each read before its reuse, never waited for while a frame
// is in flight.
#include "vulkan/renderer_internal.hpp"

namespace lantern::gi::vk {

void Renderer::begin_frame(gpu::CommandList& cmd, std::uint64_t frame) {
    if (queries_.empty()) return;
    frame_slot_ = (frame_slot_ + 1) % int(queries_.size());
    QuerySet& set = queries_[std::size_t(frame_slot_)];
    if (set.pending) {
        // Three recordings old: its submission is normally done. Read it if so; a set whose
        // submission is still running is dropped rather than waited for.
        if (auto done = set.queries.try_resolve()) resolved_.push_back(collect_timings(set, *done));
        set.pending = false;
    }
    set.queries.reset(cmd);
    set.passes.clear();
    set.pending = true;
    set.frame = frame;
}

FrameTimings Renderer::collect_timings(const QuerySet& set, const gpu::TimestampResult& result) {
    FrameTimings out{set.frame, {}};
    for (std::size_t i = 0; i < result.regions.size() && i < set.passes.size(); ++i)
        out.passes.push_back(
            {set.passes[i].pass, double(result.regions[i].duration_ns) * 1e-6, result.regions[i], set.passes[i].part});
    return out;
}

std::vector<FrameTimings> Renderer::completed_timings() {
    std::vector<FrameTimings> out = std::move(resolved_);
    resolved_.clear();
    // Oldest first: walk the sets from the one after the newest.
    for (int k = 1; k <= int(queries_.size()); ++k) {
        QuerySet& set = queries_[std::size_t((frame_slot_ + k) % int(queries_.size()))];
        if (!set.pending) continue;
        if (auto done = set.queries.try_resolve()) {
            out.push_back(collect_timings(set, *done));
            set.pending = false;
        }
    }
    return out;
}

std::uint32_t Renderer::begin_part(gpu::CommandList& cmd, Pass pass, const char* part) {
    QuerySet* set = (!queries_.empty() && frame_slot_ >= 0) ? &queries_[std::size_t(frame_slot_)] : nullptr;
    // Parts are an extra: past the set's capacity they go untimed rather than fail.
    if (!set || set->queries.size() >= set->queries.capacity()) return no_part;
    const std::uint32_t region = set->queries.begin(cmd, part);
    set->passes.push_back({pass, part});
    return region;
}

void Renderer::end_part(gpu::CommandList& cmd, std::uint32_t region) {
    if (region == no_part) return;
    queries_[std::size_t(frame_slot_)].queries.end(cmd, region);
}

std::vector<PassTiming> Renderer::wait_timings() {
    if (queries_.empty() || frame_slot_ < 0) return {};
    QuerySet& set = queries_[std::size_t(frame_slot_)];
    if (!set.pending) return {};
    set.pending = false;
    return collect_timings(set, set.queries.resolve()).passes;
}

} // namespace lantern::gi::vk
