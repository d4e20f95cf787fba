// Monotonic time in nanoseconds, the one clock every profiler event and timing uses.
#pragma once

#include <chrono>
#include <cstdint>

namespace lantern {

inline std::int64_t now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

} // namespace lantern
