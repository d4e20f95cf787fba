// Device creation: identity, capabilities, LANTERN_VK_DEVICE, failures as clear errors.
#include "gpu/gpu_test_support.hpp"

#include "lantern/gpu/device.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>

namespace gpu = lantern::gpu;
using lantern::test::ScopedEnv;

namespace {

class Device : public lantern::test::GpuTest {};

gpu::Device* shared_or_skip_reason(std::string& why) { return lantern::test::shared_gpu_device(&why); }

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

} // namespace

TEST_F(Device, ReportsNameTypeAndCapabilities) {
    const gpu::Capabilities& caps = device().capabilities();
    EXPECT_FALSE(device().name().empty());
    EXPECT_NE(device().type(), gpu::DeviceType::other) << device().name();
    EXPECT_GE(caps.api_version, VK_API_VERSION_1_2);
    EXPECT_TRUE(device().validation_enabled()) << "vulkan-validationlayers is a required package";
    EXPECT_TRUE(caps.timestamps);
    EXPECT_TRUE(caps.timeline_semaphore); // required by Vulkan 1.2; the submission tests use it
    EXPECT_GT(caps.timestamp_period_ns, 0.0);
    EXPECT_GT(caps.timestamp_valid_bits, 0u);
    EXPECT_GE(caps.max_push_constants_size, 128u);
    EXPECT_GE(caps.max_uniform_buffer_range, 16384u);
    EXPECT_GE(caps.max_compute_workgroup_invocations, 128u);
    EXPECT_GT(caps.min_texel_buffer_offset_alignment, 0u);
    EXPECT_GT(caps.subgroup_size, 0u);
    for (VkFormat format : {VK_FORMAT_R8_UNORM, VK_FORMAT_R8G8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT})
        EXPECT_TRUE(device().supports_buffer_format(format, VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT));
    EXPECT_NE(device().vk_device(), VK_NULL_HANDLE);
    EXPECT_NE(device().vk_queue(), VK_NULL_HANDLE);
    if (device().type() == gpu::DeviceType::cpu && device().name().find("llvmpipe") != std::string::npos) {
        // What lavapipe is known to offer (the CI device).
        EXPECT_TRUE(caps.storage_buffer_8bit);
        EXPECT_TRUE(caps.storage_buffer_16bit);
        EXPECT_TRUE(caps.shader_float16);
        EXPECT_TRUE(caps.calibrated_timestamps);
        EXPECT_TRUE(caps.debug_utils);
        EXPECT_EQ(caps.timestamp_period_ns, 1.0);
    }
}

TEST(DeviceSelection, EnvOverrideByNameIsCaseInsensitiveAndByIndex) {
    std::string why;
    gpu::Device* shared = shared_or_skip_reason(why);
    if (!shared) LANTERN_SKIP_NO_GPU(why);
    std::string upper = shared->name();
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    {
        ScopedEnv env("LANTERN_VK_DEVICE", upper.c_str());
        auto device = gpu::Device::create();
        ASSERT_TRUE(device) << device.error().message;
        EXPECT_EQ(device.value()->name(), shared->name());
    }
    {
        const std::string index = std::to_string(shared->physical_device_index());
        ScopedEnv env("LANTERN_VK_DEVICE", index.c_str());
        auto device = gpu::Device::create();
        ASSERT_TRUE(device) << device.error().message;
        EXPECT_EQ(device.value()->physical_device_index(), shared->physical_device_index());
    }
}

TEST(DeviceSelection, EnvOverrideMatchingNothingIsAClearError) {
    std::string why;
    gpu::Device* shared = shared_or_skip_reason(why);
    if (!shared) LANTERN_SKIP_NO_GPU(why);
    ScopedEnv env("LANTERN_VK_DEVICE", "no-such-gpu-4711");
    gpu::DeviceOptions options;
    options.device = shared->name(); // the environment wins over the option
    auto device = gpu::Device::create(options);
    ASSERT_FALSE(device);
    const std::string& message = device.error().message;
    EXPECT_TRUE(starts_with(message, "no Vulkan device: LANTERN_VK_DEVICE='no-such-gpu-4711' matches none of: "))
        << message;
    EXPECT_NE(message.find(shared->name()), std::string::npos) << message;
}

TEST(DeviceSelection, OptionSelectsWhenTheEnvironmentIsUnset) {
    std::string why;
    gpu::Device* shared = shared_or_skip_reason(why);
    if (!shared) LANTERN_SKIP_NO_GPU(why);
    ScopedEnv env("LANTERN_VK_DEVICE", nullptr);
    gpu::DeviceOptions options;
    options.device = "no-such-gpu-4711";
    auto device = gpu::Device::create(options);
    ASSERT_FALSE(device);
    EXPECT_TRUE(starts_with(device.error().message, "no Vulkan device: DeviceOptions::device='no-such-gpu-4711'"))
        << device.error().message;
}

TEST(DeviceSelection, NoDriverIsAClearErrorNotACrash) {
    // Point the loader at a driver manifest that does not exist: no ICD, so no device.
    ScopedEnv drivers("VK_DRIVER_FILES", "/nonexistent/lantern_no_driver.json");
    ScopedEnv icds("VK_ICD_FILENAMES", "/nonexistent/lantern_no_driver.json");
    auto device = gpu::Device::create();
    ASSERT_FALSE(device);
    EXPECT_TRUE(starts_with(device.error().message, "no Vulkan device: ")) << device.error().message;
}
