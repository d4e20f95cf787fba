// Timestamp query sets: recording, non-blocking resolve, GPU -> CPU clock mapping.
#include "device_internal.hpp"

#include "lantern/gpu/vk_check.hpp"
#include "lantern/profile/profiler.hpp"

#include <cmath>
#include <cstring>
#include <utility>

namespace lantern::gpu {

namespace {

std::uint64_t valid_mask(std::uint32_t bits) {
    return bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
}

// a - b on a clock of `bits` bits that may have wrapped, as a signed tick count.
std::int64_t tick_delta(std::uint64_t a, std::uint64_t b, std::uint32_t bits) {
    const std::uint64_t d = (a - b) & valid_mask(bits);
    if (bits >= 64) return static_cast<std::int64_t>(d);
    const std::uint64_t sign = std::uint64_t{1} << (bits - 1);
    return (d & sign) ? static_cast<std::int64_t>(d) - static_cast<std::int64_t>(sign << 1)
                      : static_cast<std::int64_t>(d);
}

std::int64_t ticks_to_ns(std::int64_t ticks, double period_ns) {
    return static_cast<std::int64_t>(std::llround(static_cast<double>(ticks) * period_ns));
}

} // namespace

Result<TimestampQueries> Device::create_timestamp_queries(std::uint32_t max_regions, const char* name) {
    LANTERN_ASSERT(max_regions > 0, "gpu: timestamp query set of 0 regions");
    if (!caps_.timestamps)
        return make_error("gpu: the queue of '" + name_ + "' does not support timestamps");
    TimestampQueries q;
    q.device_ = this;
    q.capacity_ = max_regions;
    auto info = vk_struct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * max_regions;
    VK_CHECK(vkCreateQueryPool(device_, &info, nullptr, &q.pool_));
    set_object_name(VK_OBJECT_TYPE_QUERY_POOL, reinterpret_cast<std::uint64_t>(q.pool_), name);
    {
        std::lock_guard lock(deletions_->mutex);
        ++deletions_->live_objects;
    }
    q.results_ = create_buffer({2 * max_regions * sizeof(std::uint64_t), 0, MemoryKind::readback,
                                name ? name : "timestamp results"});
    return q;
}

TimestampQueries::TimestampQueries(TimestampQueries&& other) noexcept { *this = std::move(other); }

TimestampQueries& TimestampQueries::operator=(TimestampQueries&& other) noexcept {
    if (this != &other) {
        reset_handle();
        device_ = std::exchange(other.device_, nullptr);
        pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
        results_ = std::move(other.results_);
        capacity_ = std::exchange(other.capacity_, 0);
        names_ = std::move(other.names_);
        ended_ = std::move(other.ended_);
        recording_ = std::exchange(other.recording_, VK_NULL_HANDLE);
        ticket_ = std::move(other.ticket_);
    }
    return *this;
}

void TimestampQueries::reset_handle() {
    if (!pool_) return;
    Device::Retired retired;
    retired.query_pool = std::exchange(pool_, VK_NULL_HANDLE);
    results_.reset();
    capacity_ = 0;
    names_.clear();
    ended_.clear();
    recording_ = VK_NULL_HANDLE;
    ticket_.reset();
    std::exchange(device_, nullptr)->retire(retired);
}

void TimestampQueries::reset(CommandList& cmd) {
    LANTERN_ASSERT(pool_ && cmd && cmd.device() == device_, "gpu: timestamp reset needs a recording list of the same device");
    if (ticket_ && ticket_->serial == 0) {
        // The previous recording was never submitted: its regions are forgotten, and its
        // list must not copy queries that this reset may leave unwritten (the copy waits
        // for availability and would never finish).
        ticket_->query_count = 0;
        ticket_->open_regions = 0;
    }
    vkCmdResetQueryPool(cmd.vk(), pool_, 0, 2 * capacity_);
    names_.clear();
    ended_.clear();
    recording_ = cmd.vk();
    ticket_ = std::make_shared<detail::TimestampTicket>();
    ticket_->pool = pool_;
    ticket_->results = results_.vk();
    cmd.tickets_.push_back(ticket_);
}

std::uint32_t TimestampQueries::begin(CommandList& cmd, const char* name) {
    LANTERN_ASSERT(ticket_ && ticket_->serial == 0 && cmd.vk() == recording_,
                   "gpu: timestamp begin outside the list given to reset()");
    LANTERN_ASSERT(names_.size() < capacity_, "gpu: more timestamp regions than capacity()");
    const auto region = static_cast<std::uint32_t>(names_.size());
    names_.push_back(name);
    ended_.push_back(false);
    ticket_->query_count = 2 * (region + 1);
    ++ticket_->open_regions;
    cmd.write_timestamp(pool_, 2 * region);
    // lavapipe bins a timestamp into its rasteriser's scene, written when the scene is next
    // flushed: once a rendering scope has set a framebuffer (the game draws the world before
    // its GI frame), a region's begin waited for the first barrier inside it, after its first
    // dispatch, whose time then showed as a gap before the region (the sun's pass read 0.1 ms
    // with 11 ms of its work in front of it). An empty execution dependency flushes here;
    // elsewhere it orders nothing and costs nothing. Not inside a rendering scope, where a
    // barrier needs a self-dependency.
    if (!cmd.rendering_)
        cmd.memory_barrier(VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0);
    return region;
}

void TimestampQueries::end(CommandList& cmd, std::uint32_t region) {
    LANTERN_ASSERT(ticket_ && ticket_->serial == 0 && cmd.vk() == recording_,
                   "gpu: timestamp end outside the list given to reset()");
    LANTERN_ASSERT(region < names_.size() && !ended_[region], "gpu: timestamp region ended twice or unknown");
    ended_[region] = true;
    --ticket_->open_regions;
    cmd.write_timestamp(pool_, 2 * region + 1);
}

std::uint64_t TimestampQueries::serial() const { return ticket_ ? ticket_->serial : 0; }

bool TimestampQueries::ready() const {
    const std::uint64_t s = serial();
    return s != 0 && device_->is_complete(s);
}

std::optional<TimestampResult> TimestampQueries::try_resolve() const {
    if (!ready()) return std::nullopt;
    return read();
}

TimestampResult TimestampQueries::resolve() const {
    LANTERN_ASSERT(serial() != 0, "gpu: resolve of timestamps that were never submitted");
    device_->wait(serial());
    return read();
}

TimestampResult TimestampQueries::read() const {
    TimestampResult result;
    result.serial = serial();
    const auto count = static_cast<std::uint32_t>(2 * names_.size());
    if (count == 0) return result;
    // The submission completed and ended with a barrier to the host: plain memory now.
    std::vector<std::uint64_t> ticks(count);
    std::memcpy(ticks.data(), results_.mapped(), count * sizeof(std::uint64_t));

    const Capabilities& caps = device_->capabilities();
    const std::uint32_t bits = caps.timestamp_valid_bits;
    const double period = caps.timestamp_period_ns;
    const auto calibration = device_->calibrate_clocks();
    result.calibrated = calibration.has_value();
    // Anchor: the calibration pair, or (approximation) first begin == vkQueueSubmit time.
    const std::uint64_t anchor_ticks = calibration ? calibration->gpu_ticks : ticks[0] & valid_mask(bits);
    const std::int64_t anchor_ns = calibration ? calibration->cpu_ns : ticket_->submit_cpu_ns;
    for (std::uint32_t r = 0; r < names_.size(); ++r) {
        TimestampRegion region;
        region.name = names_[r];
        region.begin_ticks = ticks[2 * r] & valid_mask(bits);
        region.end_ticks = ticks[2 * r + 1] & valid_mask(bits);
        const std::int64_t duration = tick_delta(region.end_ticks, region.begin_ticks, bits);
        region.duration_ns = duration > 0 ? ticks_to_ns(duration, period) : 0;
        region.cpu_begin_ns = anchor_ns + ticks_to_ns(tick_delta(region.begin_ticks, anchor_ticks, bits), period);
        region.cpu_end_ns = region.cpu_begin_ns + region.duration_ns;
        result.regions.push_back(region);
    }
    return result;
}

void record_gpu_timestamps(std::uint32_t lane, std::uint64_t frame_index, const TimestampResult& result) {
    for (const TimestampRegion& r : result.regions)
        profile::record_gpu(lane, frame_index, r.name, r.cpu_begin_ns, r.cpu_end_ns);
}

} // namespace lantern::gpu
