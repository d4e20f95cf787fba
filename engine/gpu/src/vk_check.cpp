#include "lantern/gpu/vk_check.hpp"

#include <cstdio>
#include <cstdlib>

namespace lantern::gpu {

const char* vk_result_name(VkResult result) {
    switch (result) {
#define LANTERN_VK_RESULT_CASE(name)                                                           \
    case name:                                                                                 \
        return #name;
        LANTERN_VK_RESULT_CASE(VK_SUCCESS)
        LANTERN_VK_RESULT_CASE(VK_NOT_READY)
        LANTERN_VK_RESULT_CASE(VK_TIMEOUT)
        LANTERN_VK_RESULT_CASE(VK_EVENT_SET)
        LANTERN_VK_RESULT_CASE(VK_EVENT_RESET)
        LANTERN_VK_RESULT_CASE(VK_INCOMPLETE)
        LANTERN_VK_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        LANTERN_VK_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        LANTERN_VK_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
        LANTERN_VK_RESULT_CASE(VK_ERROR_DEVICE_LOST)
        LANTERN_VK_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        LANTERN_VK_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        LANTERN_VK_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        LANTERN_VK_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        LANTERN_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        LANTERN_VK_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        LANTERN_VK_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        LANTERN_VK_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
        LANTERN_VK_RESULT_CASE(VK_ERROR_UNKNOWN)
        LANTERN_VK_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        LANTERN_VK_RESULT_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        LANTERN_VK_RESULT_CASE(VK_ERROR_FRAGMENTATION)
        LANTERN_VK_RESULT_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
        LANTERN_VK_RESULT_CASE(VK_PIPELINE_COMPILE_REQUIRED)
        LANTERN_VK_RESULT_CASE(VK_ERROR_SURFACE_LOST_KHR)
        LANTERN_VK_RESULT_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        LANTERN_VK_RESULT_CASE(VK_SUBOPTIMAL_KHR)
        LANTERN_VK_RESULT_CASE(VK_ERROR_OUT_OF_DATE_KHR)
        LANTERN_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR)
        LANTERN_VK_RESULT_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
        LANTERN_VK_RESULT_CASE(VK_ERROR_INVALID_SHADER_NV)
#undef LANTERN_VK_RESULT_CASE
    default:
        break;
    }
    thread_local char unknown[32];
    std::snprintf(unknown, sizeof unknown, "VkResult(%d)", static_cast<int>(result));
    return unknown;
}

namespace detail {

void vk_check_fail(VkResult result, const char* call, const char* file, int line) {
    std::fprintf(stderr, "%s:%d: Vulkan call failed with %s: %s\n", file, line,
                 vk_result_name(result), call);
    std::fflush(stderr);
    std::abort();
}

} // namespace detail
} // namespace lantern::gpu
