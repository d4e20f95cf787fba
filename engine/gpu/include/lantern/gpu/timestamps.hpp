// GPU timestamps around named regions of a CommandList, resolved to nanoseconds and mapped
// onto the CPU clock (lantern::now_ns) for the profiler's GPU lanes.
//
// Use, once per frame and query set (keep one set per frame in flight, e.g. 3):
//
//   if (auto done = queries.try_resolve())          // an earlier frame's set; never blocks
//       gpu::record_gpu_timestamps(lane, frame_of_that_set, *done);
//   queries.reset(cmd);                              // start of the new recording
//   auto pass = queries.begin(cmd, "direct");
//   ... dispatches ...
//   queries.end(cmd, pass);
//   device.submit(std::move(cmd));                   // stamps the set with the serial
//
// CPU-clock mapping (docs/gpu.md, "Timestamps"): with VK_EXT_calibrated_timestamps and a
// CLOCK_MONOTONIC time domain (the domain of now_ns() on Linux) each resolve calibrates
// the two clocks and maps exactly up to the reported deviation (result.calibrated = true).
// Otherwise the first region's begin is anchored on the CPU time of the vkQueueSubmit
// call: durations stay exact, absolute times are early by the queue latency.
//
// Reading never calls vkGetQueryPoolResults: Device::submit appends
// vkCmdCopyQueryPoolResults into a small host-visible buffer owned by the set, so a
// completed submission's results are a memcpy away on every driver (lavapipe's
// vkGetQueryPoolResults waits for the whole device to go idle, which would stall on the
// frames still in flight).
//
// Ownership: move-only, created by Device::create_timestamp_queries, destroyed deferred.
// Threads: recording (reset/begin/end) as CommandList; serial/ready/try_resolve/resolve
// poll or wait on the Device, so they belong to the submission thread.
#pragma once

#include "lantern/gpu/buffer.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace lantern::gpu {

class CommandList;
class Device;

namespace detail {
// One recording of a query set, shared with the CommandList it was recorded into. On
// submit the Device appends a copy of the queries into `results` and stamps the serial.
struct TimestampTicket {
    VkQueryPool pool = VK_NULL_HANDLE;
    VkBuffer results = VK_NULL_HANDLE;
    std::uint32_t query_count = 0;  // 2 per region begun
    std::uint32_t open_regions = 0; // begun and not ended (must be 0 at submit)
    std::uint64_t serial = 0;       // 0 until submitted
    std::int64_t submit_cpu_ns = 0;
};
} // namespace detail

struct TimestampRegion {
    const char* name = nullptr;      // as given to begin(); must outlive its uses
    std::uint64_t begin_ticks = 0;   // raw GPU clock (masked to timestampValidBits)
    std::uint64_t end_ticks = 0;
    std::int64_t duration_ns = 0;    // (end - begin) * timestampPeriod, >= 0
    std::int64_t cpu_begin_ns = 0;   // begin on the now_ns() clock
    std::int64_t cpu_end_ns = 0;     // cpu_begin_ns + duration_ns
};

struct TimestampResult {
    std::uint64_t serial = 0;   // the submission the regions ran in
    bool calibrated = false;    // CPU times from calibrated timestamps (else: submit anchor)
    std::vector<TimestampRegion> regions{}; // in begin() order
};

class TimestampQueries {
  public:
    TimestampQueries() = default;
    TimestampQueries(TimestampQueries&& other) noexcept;
    TimestampQueries& operator=(TimestampQueries&& other) noexcept;
    TimestampQueries(const TimestampQueries&) = delete;
    TimestampQueries& operator=(const TimestampQueries&) = delete;
    ~TimestampQueries() { reset_handle(); }

    explicit operator bool() const { return pool_ != VK_NULL_HANDLE; }
    std::uint32_t capacity() const { return capacity_; } // regions per recording
    std::uint32_t size() const { return static_cast<std::uint32_t>(names_.size()); }

    // Starts a new recording into `cmd`: records the query reset and forgets the previous
    // regions (read them first). Every begin/end until the next reset goes into this list,
    // and every region must be ended before the list is submitted.
    void reset(CommandList& cmd);
    // Opens region `name` (timestamp after all earlier commands of the queue completed) and
    // returns its index. At most capacity() regions per recording.
    std::uint32_t begin(CommandList& cmd, const char* name);
    void end(CommandList& cmd, std::uint32_t region);

    // The submission holding the current recording: 0 until that list is submitted.
    std::uint64_t serial() const;
    // Submitted and completed on the GPU: try_resolve() will succeed. Never blocks.
    bool ready() const;
    // The regions of the current recording if its submission completed, else nullopt.
    // Never blocks.
    std::optional<TimestampResult> try_resolve() const;
    // Waits for the submission, then resolves. The recording must have been submitted.
    TimestampResult resolve() const;

  private:
    friend class Device;
    void reset_handle();
    TimestampResult read() const;

    Device* device_ = nullptr;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    Buffer results_; // 2 * capacity 64-bit ticks, written by the submission
    std::uint32_t capacity_ = 0;
    std::vector<const char*> names_;
    std::vector<bool> ended_;
    VkCommandBuffer recording_ = VK_NULL_HANDLE; // the list reset() was given, for asserts
    std::shared_ptr<detail::TimestampTicket> ticket_;
};

// Feeds every region of `result` to the profiler's GPU lane `lane` as spans of frame
// `frame_index` (profile::record_gpu with the CPU-clock times).
void record_gpu_timestamps(std::uint32_t lane, std::uint64_t frame_index,
                           const TimestampResult& result);

} // namespace lantern::gpu
