// VK_CHECK: the second of Lantern's three error tiers (docs/architecture.md).
//
// Wrap every Vulkan call whose failure Lantern cannot recover from: out of memory, device
// lost, or a result that only a programmer error produces. On anything but VK_SUCCESS it
// aborts with the result's name, the call, file and line. Calls with legitimate non-success
// results (VK_NOT_READY, VK_TIMEOUT, VK_INCOMPLETE, VK_SUBOPTIMAL_KHR) and expected failures
// (instance creation, no device, missing features: these return lantern::Result) are
// handled explicitly instead.
#pragma once

#include <vulkan/vulkan.h>

namespace lantern::gpu {

// "VK_ERROR_DEVICE_LOST", ...; "VkResult(<n>)" for values this build does not know.
const char* vk_result_name(VkResult result);

namespace detail {
[[noreturn]] void vk_check_fail(VkResult result, const char* call, const char* file, int line);
}

} // namespace lantern::gpu

#define VK_CHECK(call)                                                                         \
    do {                                                                                       \
        const VkResult lantern_vk_check_result_ = (call);                                      \
        if (lantern_vk_check_result_ != VK_SUCCESS) [[unlikely]]                               \
            ::lantern::gpu::detail::vk_check_fail(lantern_vk_check_result_, #call, __FILE__,   \
                                                  __LINE__);                                   \
    } while (false)
