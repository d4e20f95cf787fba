// Device::create: instance and messenger, physical-device choice, logical device.
// Every failure here is an expected one (tier 3): it returns an Error, it never aborts.
#include "device_internal.hpp"

#include "lantern/gpu/device_choice.hpp"

#include "lantern/core/log.hpp"
#include "lantern/gpu/vk_check.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace lantern::gpu {

namespace {

constexpr const char* validation_layer = "VK_LAYER_KHRONOS_validation";
constexpr std::uint32_t min_api_version = VK_API_VERSION_1_2;

// Formats the GI backend reads through uniform texel buffers.
constexpr std::array<std::pair<VkFormat, const char*>, 3> required_texel_formats = {{
    {VK_FORMAT_R8_UNORM, "R8_UNORM"},
    {VK_FORMAT_R8G8_UNORM, "R8G8_UNORM"},
    {VK_FORMAT_R16G16B16A16_SFLOAT, "R16G16B16A16_SFLOAT"},
}};

Error no_device(const std::string& why) { return make_error("no Vulkan device: " + why); }

std::string env_string(const char* name) {
    const char* value = std::getenv(name);
    return value ? std::string(value) : std::string();
}

std::string version_string(std::uint32_t version) {
    return std::to_string(VK_API_VERSION_MAJOR(version)) + "." +
           std::to_string(VK_API_VERSION_MINOR(version)) + "." +
           std::to_string(VK_API_VERSION_PATCH(version));
}

bool has_extension(const std::vector<VkExtensionProperties>& available, const char* name) {
    return std::any_of(available.begin(), available.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

std::vector<VkExtensionProperties> instance_extensions(const char* layer) {
    std::uint32_t count = 0;
    if (vkEnumerateInstanceExtensionProperties(layer, &count, nullptr) != VK_SUCCESS) return {};
    std::vector<VkExtensionProperties> out(count);
    if (vkEnumerateInstanceExtensionProperties(layer, &count, out.data()) < 0) return {};
    out.resize(count);
    return out;
}

bool has_instance_layer(const char* name) {
    std::uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(count);
    if (vkEnumerateInstanceLayerProperties(&count, layers.data()) < 0) return false;
    layers.resize(count);
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

std::vector<VkExtensionProperties> device_extensions(VkPhysicalDevice physical) {
    std::uint32_t count = 0;
    VK_CHECK(vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> out(count);
    VK_CHECK(vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, out.data()));
    return out;
}

DeviceType device_type(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return DeviceType::discrete;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return DeviceType::integrated;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return DeviceType::virtual_gpu;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return DeviceType::cpu;
    default: return DeviceType::other;
    }
}

// What one physical device offers, and why it cannot be used (problems empty = suitable).
struct Candidate {
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    std::uint32_t index = 0;
    VkPhysicalDeviceProperties properties{};
    std::uint32_t queue_family = UINT32_MAX;
    std::uint32_t timestamp_valid_bits = 0;
    bool graphics = false;
    bool calibrated_timestamps = false;
    std::vector<std::string> problems;

    std::string name() const { return properties.deviceName; }
    DeviceType type() const { return device_type(properties.deviceType); }
    DeviceCandidate summary() const { return {index, name(), type(), problems}; }
};

// Prefers a family that writes timestamps, then one that also does graphics (a universal
// queue, so later rendering can share it), then the lowest index. `need_graphics` keeps
// only families that do graphics too.
void choose_queue_family(Candidate& c, bool need_graphics) {
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(c.physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(c.physical, &count, families.data());
    int best_score = -1;
    for (std::uint32_t i = 0; i < count; ++i) {
        const VkQueueFamilyProperties& f = families[i];
        if (!(f.queueFlags & VK_QUEUE_COMPUTE_BIT) || f.queueCount == 0) continue;
        const bool graphics = (f.queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0;
        if (need_graphics && !graphics) continue;
        const int score = (f.timestampValidBits > 0 ? 2 : 0) + (graphics ? 1 : 0);
        if (score > best_score) {
            best_score = score;
            c.queue_family = i;
            c.timestamp_valid_bits = f.timestampValidBits;
            c.graphics = graphics;
        }
    }
    if (c.queue_family == UINT32_MAX)
        c.problems.push_back(need_graphics ? "no queue family with compute and graphics"
                                           : "no queue family with compute");
}

// Why `physical` cannot do DeviceOptions::graphics (empty: it can).
std::vector<std::string> raster_problems(VkPhysicalDevice physical,
                                         const std::vector<VkExtensionProperties>& extensions) {
    if (!has_extension(extensions, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME))
        return {std::string("missing ") + VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME};
    auto dynamic_rendering = vk_struct<VkPhysicalDeviceDynamicRenderingFeaturesKHR>(
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES_KHR);
    auto v12 = vk_struct<VkPhysicalDeviceVulkan12Features>(
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    v12.pNext = &dynamic_rendering;
    auto features =
        vk_struct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    features.pNext = &v12;
    vkGetPhysicalDeviceFeatures2(physical, &features);
    std::vector<std::string> problems;
    if (!dynamic_rendering.dynamicRendering) problems.push_back("no dynamicRendering feature");
    if (!v12.imagelessFramebuffer) problems.push_back("no imagelessFramebuffer feature");
    return problems;
}

bool supports_calibration(VkInstance instance, VkPhysicalDevice physical) {
#if defined(__linux__)
    auto get_domains = reinterpret_cast<PFN_vkGetPhysicalDeviceCalibrateableTimeDomainsEXT>(
        vkGetInstanceProcAddr(instance, "vkGetPhysicalDeviceCalibrateableTimeDomainsEXT"));
    if (!get_domains) return false;
    std::uint32_t count = 0;
    if (get_domains(physical, &count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkTimeDomainEXT> domains(count);
    if (get_domains(physical, &count, domains.data()) != VK_SUCCESS) return false;
    auto has = [&](VkTimeDomainEXT d) {
        return std::find(domains.begin(), domains.end(), d) != domains.end();
    };
    // now_ns() is std::chrono::steady_clock, which is CLOCK_MONOTONIC on Linux.
    return has(VK_TIME_DOMAIN_DEVICE_EXT) && has(VK_TIME_DOMAIN_CLOCK_MONOTONIC_EXT);
#else
    (void)instance;
    (void)physical;
    return false;
#endif
}

Candidate evaluate(VkInstance instance, VkPhysicalDevice physical, std::uint32_t index,
                   const DeviceOptions& options) {
    Candidate c;
    c.physical = physical;
    c.index = index;
    vkGetPhysicalDeviceProperties(physical, &c.properties);
    if (c.properties.apiVersion < min_api_version)
        c.problems.push_back("Vulkan " + version_string(c.properties.apiVersion) + " < 1.2");
    choose_queue_family(c, options.graphics);

    const auto extensions = device_extensions(physical);
    if (options.graphics) {
        for (std::string& problem : raster_problems(physical, extensions))
            c.problems.push_back(std::move(problem));
    }
    std::vector<const char*> required = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    required.insert(required.end(), options.device_extensions.begin(),
                    options.device_extensions.end());
    for (const char* ext : required) {
        if (!has_extension(extensions, ext)) c.problems.push_back(std::string("missing ") + ext);
    }
    for (const auto& [format, format_name] : required_texel_formats) {
        VkFormatProperties props{};
        vkGetPhysicalDeviceFormatProperties(physical, format, &props);
        if (!(props.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT))
            c.problems.push_back(std::string(format_name) + " lacks UNIFORM_TEXEL_BUFFER");
    }
    c.calibrated_timestamps = has_extension(extensions, VK_EXT_CALIBRATED_TIMESTAMPS_EXTENSION_NAME) &&
                              supports_calibration(instance, physical);
    return c;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
    std::uint32_t count = 0;
    if (vkEnumeratePhysicalDevices(instance, &count, nullptr) != VK_SUCCESS) return {};
    std::vector<VkPhysicalDevice> out(count);
    if (vkEnumeratePhysicalDevices(instance, &count, out.data()) < 0) return {};
    out.resize(count);
    return out;
}

// Optional features, queried and then enabled where present.
struct FeatureChain {
    VkPhysicalDeviceFeatures2 core =
        vk_struct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    VkPhysicalDeviceVulkan11Features v11 =
        vk_struct<VkPhysicalDeviceVulkan11Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES);
    VkPhysicalDeviceVulkan12Features v12 =
        vk_struct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    FeatureChain() {
        core.pNext = &v11;
        v11.pNext = &v12;
    }
    FeatureChain(const FeatureChain&) = delete;
};

} // namespace

struct DeviceBuilder {
    static Result<void> create_instance(Device& d, const DeviceOptions& options);
    static Result<void> choose_physical(Device& d, const DeviceOptions& options);
    static Result<void> create_logical(Device& d, const DeviceOptions& options);
    static void fill_capabilities(Device& d, std::uint32_t timestamp_valid_bits);
    static void load_dispatch(Device& d);
};

Result<void> DeviceBuilder::create_instance(Device& d, const DeviceOptions& options) {
    std::uint32_t loader_version = VK_API_VERSION_1_0;
    if (vkEnumerateInstanceVersion(&loader_version) != VK_SUCCESS || loader_version < min_api_version)
        return no_device("the Vulkan loader supports " + version_string(loader_version) +
                         ", Lantern needs 1.2");

    const std::string env = env_string("LANTERN_VK_VALIDATION");
    const bool want_validation = options.validation || env == "1" || env == "sync";
    const bool want_sync = options.synchronization_validation || env == "sync";
    const bool validation = want_validation && has_instance_layer(validation_layer);
    if (want_validation && !validation)
        LANTERN_LOG_WARN("gpu: %s is not installed; running without validation", validation_layer);

    const auto available = instance_extensions(nullptr);
    std::vector<const char*> extensions;
    for (const char* ext : options.instance_extensions) {
        if (!has_extension(available, ext))
            return no_device(std::string("instance extension ") + ext + " is not available");
        extensions.push_back(ext);
    }
    const bool debug_utils = has_extension(available, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debug_utils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    const bool sync_validation =
        validation && want_sync &&
        has_extension(instance_extensions(validation_layer), VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    if (sync_validation) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);

    auto app = vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = options.application_name.c_str();
    app.pEngineName = "lantern";
    app.apiVersion = min_api_version;

    // Chained into the instance create info too, so messages of vkCreateInstance and
    // vkDestroyInstance are counted as well.
    auto messenger_info = vk_struct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger_info.pfnUserCallback = &Device::Validation::callback;

    const VkValidationFeatureEnableEXT sync_feature = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    auto features = vk_struct<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync_feature;

    auto info = vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pApplicationInfo = &app;
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    if (validation) {
        d.validation_ = std::make_unique<Device::Validation>();
        d.validation_->log = options.log_validation_messages;
        d.validation_->abort_on_error = options.abort_on_validation_error;
        messenger_info.pUserData = d.validation_.get();
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = &validation_layer;
        if (debug_utils) {
            messenger_info.pNext = sync_validation ? &features : nullptr;
            info.pNext = &messenger_info;
        } else if (sync_validation) {
            info.pNext = &features;
        }
    }
    const VkResult result = vkCreateInstance(&info, nullptr, &d.instance_);
    if (result != VK_SUCCESS) {
        d.instance_ = VK_NULL_HANDLE;
        return no_device(std::string("vkCreateInstance failed with ") + vk_result_name(result) +
                         (result == VK_ERROR_INCOMPATIBLE_DRIVER
                              ? " (no Vulkan driver found; install mesa-vulkan-drivers or a GPU driver)"
                              : ""));
    }
    d.caps_.debug_utils = debug_utils;
    if (validation && debug_utils) {
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(d.instance_, "vkCreateDebugUtilsMessengerEXT"));
        d.dispatch_->destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(d.instance_, "vkDestroyDebugUtilsMessengerEXT"));
        messenger_info.pNext = nullptr;
        if (create_messenger && d.dispatch_->destroy_messenger)
            VK_CHECK(create_messenger(d.instance_, &messenger_info, nullptr, &d.messenger_));
    }
    return {};
}

Result<void> DeviceBuilder::choose_physical(Device& d, const DeviceOptions& options) {
    const auto physicals = physical_devices(d.instance_);
    if (physicals.empty())
        return no_device("the Vulkan loader found no physical device (is a driver such as "
                         "mesa-vulkan-drivers installed?)");
    std::vector<Candidate> candidates;
    for (std::uint32_t i = 0; i < physicals.size(); ++i)
        candidates.push_back(evaluate(d.instance_, physicals[i], i, options));

    std::string selector = env_string("LANTERN_VK_DEVICE");
    const char* source = "LANTERN_VK_DEVICE";
    if (selector.empty()) {
        selector = options.device;
        source = "DeviceOptions::device";
    }
    std::vector<DeviceCandidate> summaries;
    for (const auto& c : candidates) summaries.push_back(c.summary());
    auto chosen = choose_device(summaries, selector, source);
    if (!chosen) return chosen.error();
    const Candidate& c = candidates[*chosen];
    d.physical_ = c.physical;
    d.physical_index_ = c.index;
    d.name_ = c.name();
    d.type_ = c.type();
    d.queue_family_ = c.queue_family;
    fill_capabilities(d, c.timestamp_valid_bits);
    d.caps_.calibrated_timestamps = c.calibrated_timestamps;
    return {};
}

Result<void> DeviceBuilder::create_logical(Device& d, const DeviceOptions& options) {
    FeatureChain supported;
    vkGetPhysicalDeviceFeatures2(d.physical_, &supported.core);

    FeatureChain enabled;
    enabled.core.features.shaderInt16 = supported.core.features.shaderInt16;
    enabled.v11.storageBuffer16BitAccess = supported.v11.storageBuffer16BitAccess;
    enabled.v12.storageBuffer8BitAccess = supported.v12.storageBuffer8BitAccess;
    enabled.v12.shaderFloat16 = supported.v12.shaderFloat16;
    enabled.v12.shaderInt8 = supported.v12.shaderInt8;
    enabled.v12.timelineSemaphore = supported.v12.timelineSemaphore;

    std::vector<const char*> extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    if (d.caps_.calibrated_timestamps) extensions.push_back(VK_EXT_CALIBRATED_TIMESTAMPS_EXTENSION_NAME);
    // Raster: checked present by evaluate().
    auto dynamic_rendering = vk_struct<VkPhysicalDeviceDynamicRenderingFeaturesKHR>(
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES_KHR);
    if (options.graphics) {
        extensions.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
        dynamic_rendering.dynamicRendering = VK_TRUE;
        enabled.v12.pNext = &dynamic_rendering;
        enabled.v12.imagelessFramebuffer = VK_TRUE;
    }
    extensions.insert(extensions.end(), options.device_extensions.begin(),
                      options.device_extensions.end());

    const float priority = 1.0f;
    auto queue = vk_struct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue.queueFamilyIndex = d.queue_family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;

    auto info = vk_struct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    info.pNext = &enabled.core;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    const VkResult result = vkCreateDevice(d.physical_, &info, nullptr, &d.device_);
    if (result != VK_SUCCESS) {
        d.device_ = VK_NULL_HANDLE;
        return no_device("vkCreateDevice failed for '" + d.name_ + "' with " + vk_result_name(result));
    }
    vkGetDeviceQueue(d.device_, d.queue_family_, 0, &d.queue_);

    d.caps_.shader_int16 = enabled.core.features.shaderInt16;
    d.caps_.storage_buffer_16bit = enabled.v11.storageBuffer16BitAccess;
    d.caps_.storage_buffer_8bit = enabled.v12.storageBuffer8BitAccess;
    d.caps_.shader_float16 = enabled.v12.shaderFloat16;
    d.caps_.shader_int8 = enabled.v12.shaderInt8;
    d.caps_.timeline_semaphore = enabled.v12.timelineSemaphore;
    d.caps_.graphics = options.graphics;
    return {};
}

void DeviceBuilder::fill_capabilities(Device& d, std::uint32_t timestamp_valid_bits) {
    auto v11 = vk_struct<VkPhysicalDeviceVulkan11Properties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES);
    auto props = vk_struct<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2);
    props.pNext = &v11;
    vkGetPhysicalDeviceProperties2(d.physical_, &props);
    const VkPhysicalDeviceLimits& limits = props.properties.limits;

    Capabilities& caps = d.caps_;
    caps.api_version = props.properties.apiVersion;
    caps.timestamps = timestamp_valid_bits > 0 && limits.timestampPeriod > 0.0f;
    caps.timestamp_valid_bits = timestamp_valid_bits;
    caps.timestamp_period_ns = limits.timestampPeriod;
    caps.subgroup_size = v11.subgroupSize;
    caps.min_storage_buffer_offset_alignment = limits.minStorageBufferOffsetAlignment;
    caps.min_uniform_buffer_offset_alignment = limits.minUniformBufferOffsetAlignment;
    caps.min_texel_buffer_offset_alignment = limits.minTexelBufferOffsetAlignment;
    caps.max_uniform_buffer_range = limits.maxUniformBufferRange;
    caps.max_storage_buffer_range = limits.maxStorageBufferRange;
    caps.max_texel_buffer_elements = limits.maxTexelBufferElements;
    caps.max_push_constants_size = limits.maxPushConstantsSize;
    caps.max_compute_workgroup_invocations = limits.maxComputeWorkGroupInvocations;
    for (int i = 0; i < 3; ++i) {
        caps.max_compute_workgroup_size[i] = limits.maxComputeWorkGroupSize[i];
        caps.max_compute_workgroup_count[i] = limits.maxComputeWorkGroupCount[i];
    }
    vkGetPhysicalDeviceMemoryProperties(d.physical_, &d.memory_properties_);
}

void DeviceBuilder::load_dispatch(Device& d) {
    auto& f = *d.dispatch_;
    f.cmd_push_descriptor_set = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(d.device_, "vkCmdPushDescriptorSetKHR"));
    LANTERN_VERIFY(f.cmd_push_descriptor_set, "vkCmdPushDescriptorSetKHR missing on a device that lists it");
    if (d.caps_.calibrated_timestamps)
        f.get_calibrated_timestamps = reinterpret_cast<PFN_vkGetCalibratedTimestampsEXT>(
            vkGetDeviceProcAddr(d.device_, "vkGetCalibratedTimestampsEXT"));
    d.caps_.calibrated_timestamps = f.get_calibrated_timestamps != nullptr;
    if (d.caps_.graphics) {
        f.cmd_begin_rendering = reinterpret_cast<PFN_vkCmdBeginRenderingKHR>(
            vkGetDeviceProcAddr(d.device_, "vkCmdBeginRenderingKHR"));
        f.cmd_end_rendering = reinterpret_cast<PFN_vkCmdEndRenderingKHR>(
            vkGetDeviceProcAddr(d.device_, "vkCmdEndRenderingKHR"));
        LANTERN_VERIFY(f.cmd_begin_rendering && f.cmd_end_rendering,
                       "vkCmdBeginRenderingKHR missing on a device that lists "
                       "VK_KHR_dynamic_rendering");
    }
    if (d.caps_.debug_utils) {
        // Instance-level extension: its commands come from the instance.
        f.set_object_name = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(d.instance_, "vkSetDebugUtilsObjectNameEXT"));
        f.cmd_begin_label = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(d.instance_, "vkCmdBeginDebugUtilsLabelEXT"));
        f.cmd_end_label = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(d.instance_, "vkCmdEndDebugUtilsLabelEXT"));
    }
}

Result<std::unique_ptr<Device>> Device::create(const DeviceOptions& options) {
    std::unique_ptr<Device> device(new Device());
    if (auto r = DeviceBuilder::create_instance(*device, options); !r) return r.error();
    if (auto r = DeviceBuilder::choose_physical(*device, options); !r) return r.error();
    if (auto r = DeviceBuilder::create_logical(*device, options); !r) return r.error();
    DeviceBuilder::load_dispatch(*device);
    auto cache = vk_struct<VkPipelineCacheCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO);
    VK_CHECK(vkCreatePipelineCache(device->device_, &cache, nullptr, &device->pipeline_cache_));
    LANTERN_LOG_DEBUG("gpu: using device %u '%s' (%s), queue family %u, validation %s",
                      device->physical_index_, device->name_.c_str(), to_string(device->type_),
                      device->queue_family_, device->validation_enabled() ? "on" : "off");
    return device;
}

const char* to_string(DeviceType type) {
    switch (type) {
    case DeviceType::discrete: return "discrete";
    case DeviceType::integrated: return "integrated";
    case DeviceType::virtual_gpu: return "virtual";
    case DeviceType::cpu: return "cpu";
    default: return "other";
    }
}

} // namespace lantern::gpu
