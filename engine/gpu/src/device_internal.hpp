// Implementation state of lantern::gpu::Device shared by the files of engine/gpu/src.
#pragma once

#include "lantern/gpu/device.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <mutex>
#include <set>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace lantern::gpu {

// A zeroed Vulkan info struct with its sType set (brace-initialising only sType would
// trip -Wmissing-field-initializers).
template <typename T>
T vk_struct(VkStructureType type) {
    T value{};
    value.sType = type;
    return value;
}

// Extension entry points, loaded once per device (nullptr when the extension is absent).
struct Device::Dispatch {
    PFN_vkCmdPushDescriptorSetKHR cmd_push_descriptor_set = nullptr;
    PFN_vkGetCalibratedTimestampsEXT get_calibrated_timestamps = nullptr;
    PFN_vkSetDebugUtilsObjectNameEXT set_object_name = nullptr;
    PFN_vkCmdBeginDebugUtilsLabelEXT cmd_begin_label = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT cmd_end_label = nullptr;
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger = nullptr;
    PFN_vkCmdBeginRenderingKHR cmd_begin_rendering = nullptr; // DeviceOptions::graphics
    PFN_vkCmdEndRenderingKHR cmd_end_rendering = nullptr;
};

// Messages of the debug-utils messenger. The callback runs on whatever thread the layer or
// driver reports from, hence the mutex.
struct Device::Validation {
    // Texts kept beyond this are dropped (still counted), so a runaway loop cannot eat memory.
    static constexpr std::size_t max_kept = 1000;

    mutable std::mutex mutex;
    std::vector<std::string> messages;
    std::uint64_t count = 0;
    bool log = true;
    bool abort_on_error = false;

    static VKAPI_ATTR VkBool32 VKAPI_CALL callback(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
};

// The Vulkan objects of one destroyed resource (unused fields stay VK_NULL_HANDLE).
struct Device::Retired {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkBufferView view = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkQueryPool query_pool = VK_NULL_HANDLE;
    VkImage image = VK_NULL_HANDLE;
    VkImageView image_view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
};

// Deferred destruction. An entry is "sealed" with the serial after which it may be freed.
// Destroyed while no CommandList is open: sealed at once with the last submitted serial.
// Destroyed while lists are open: those lists may still record uses, so the entry is
// sealed when the last of them (ids <= newest_open_list) is submitted or discarded, with
// the serial submitted last at that moment.
struct Device::Deletions {
    struct Entry {
        Retired objects;
        std::uint64_t serial = 0;
        std::uint64_t newest_open_list = 0;
        bool sealed = false;
    };

    mutable std::mutex mutex;
    std::vector<Entry> entries;
    std::set<std::uint64_t> open_lists; // ids of CommandLists being recorded
    std::uint64_t last_submitted = 0;   // mirror of Device::last_submitted_ for retire()
    std::size_t live_objects = 0;       // created and not yet destroyed
    std::unordered_map<VkDeviceMemory, VkDeviceSize> memory_sizes; // allocated and not yet freed
    std::uint64_t memory_bytes = 0;                                 // their sum
};

// One submission's command pool, command buffer and fence. Recycled when the fence signals.
struct Device::Context {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    std::uint64_t serial = 0;
};

// Helpers shared by the files of engine/gpu/src.
namespace detail {
// The layout a pipeline gets: what its shaders declare (gpu::reflect_spirv), checked against
// the description's bindings and push-constant size where it gives them (empty / 0: take
// the shader's; a given size may exceed the block, as a padded C++ struct does). A mismatch or an unreadable layout stops with a message naming `name`:
// shaders are built with the engine, so it is a programming error, not bad input.
struct PipelineLayoutInfo {
    std::vector<BindingType> bindings;
    std::uint32_t push_constant_size = 0;
};
PipelineLayoutInfo resolve_layout(std::span<const std::span<const std::uint32_t>> stages,
                                  std::span<const BindingType> declared, std::uint32_t declared_push_size,
                                  const char* name);
VkDescriptorSetLayout create_set_layout(VkDevice device, std::span<const BindingType> bindings,
                                        VkShaderStageFlags stages);
VkPipelineLayout create_pipeline_layout(VkDevice device, VkDescriptorSetLayout set_layout,
                                        std::uint32_t push_constant_size,
                                        VkShaderStageFlags stages);
VkShaderModule create_shader_module(VkDevice device, std::span<const std::uint32_t> spirv);
// The memory type for `kind` among `type_bits` (buffer.cpp), or UINT32_MAX.
std::uint32_t choose_memory_type(const VkPhysicalDeviceMemoryProperties& props,
                                 std::uint32_t type_bits, MemoryKind kind);

// VkSpecializationInfo over a list of SpecConstants (the info points into this object).
class Specialization {
  public:
    explicit Specialization(std::span<const SpecConstant> constants);
    Specialization(const Specialization&) = delete;
    Specialization& operator=(const Specialization&) = delete;
    // nullptr when there are no constants.
    const VkSpecializationInfo* info() const { return entries_.empty() ? nullptr : &info_; }

  private:
    std::vector<VkSpecializationMapEntry> entries_;
    std::vector<std::uint32_t> values_;
    VkSpecializationInfo info_{};
};
} // namespace detail

} // namespace lantern::gpu
