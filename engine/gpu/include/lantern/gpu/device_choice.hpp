// The physical-device choice rule as a pure function, so it can be tested without GPUs and
// reused by tools that list devices. Device::create applies it to the enumerated devices.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gpu/device.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::gpu {

struct DeviceCandidate {
    std::uint32_t index = 0;           // enumeration order (what an index selector names)
    std::string name{};
    DeviceType type = DeviceType::other;
    std::vector<std::string> problems{}; // why it is unsuitable; empty = suitable
};

// Rank of a device type: lower is preferred (discrete 0 < integrated < virtual < cpu < other).
int device_type_rank(DeviceType type);

// Position in `candidates` of the device to use. `selector` empty: the best-ranked suitable
// device (the first listed among equals). Otherwise only devices it matches are considered:
// all digits = the device with that index, else a case-insensitive substring of the name.
// Errors ("no Vulkan device: ...") name `selector_source` and list the devices or problems.
Result<std::size_t> choose_device(std::span<const DeviceCandidate> candidates,
                                  std::string_view selector, std::string_view selector_source);

} // namespace lantern::gpu
