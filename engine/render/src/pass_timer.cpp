// PassTimer: a ring of timestamp query sets, one per frame.
#include "lantern/render/pass_timer.hpp"

#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/device.hpp"

#include <algorithm>

namespace lantern::render {

Result<PassTimer> PassTimer::create(gpu::Device& device, std::uint32_t max_passes) {
    PassTimer timer;
    for (std::uint32_t i = 0; i < ring_size; ++i) {
        auto queries = device.create_timestamp_queries(max_passes, "PassTimer");
        if (!queries) return queries.error();
        timer.sets_.push_back({std::move(queries).value(), 0, false});
    }
    timer.current_ = ring_size - 1; // begin_frame advances to set 0 first
    return timer;
}

void PassTimer::collect(Set& set, const gpu::TimestampResult& result) {
    done_.push_back({set.frame, result.regions});
    set.pending = false;
}

void PassTimer::begin_frame(gpu::CommandList& cmd, std::uint64_t frame) {
    LANTERN_ASSERT(!sets_.empty(), "render::PassTimer used before create");
    current_ = (current_ + 1) % ring_size;
    Set& set = sets_[current_];
    if (set.pending) {
        LANTERN_ASSERT(set.queries.serial() != 0,
                       "render::PassTimer: a frame's list was never submitted");
        collect(set,
                set.queries.resolve()); // blocks only with more than ring_size - 1 frames in flight
    }
    set.queries.reset(cmd);
    set.frame = frame;
    set.pending = true;
}

std::uint32_t PassTimer::begin(gpu::CommandList& cmd, const char* pass) {
    return sets_[current_].queries.begin(cmd, pass);
}

void PassTimer::end(gpu::CommandList& cmd, std::uint32_t pass) {
    sets_[current_].queries.end(cmd, pass);
}

std::vector<FrameTimings> PassTimer::take_completed() {
    for (Set& set : sets_) {
        if (!set.pending) continue;
        if (auto result = set.queries.try_resolve()) collect(set, *result);
    }
    std::vector<FrameTimings> out = std::move(done_);
    done_.clear();
    std::sort(out.begin(), out.end(),
              [](const FrameTimings& a, const FrameTimings& b) { return a.frame < b.frame; });
    return out;
}

} // namespace lantern::render
