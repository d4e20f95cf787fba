// The device choice rule, without a GPU: preference order, selectors, error messages.
#include "lantern/gpu/device_choice.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace gpu = lantern::gpu;

namespace {

std::vector<gpu::DeviceCandidate> three_devices() {
    return {
        {0, "llvmpipe (LLVM 15.0.6, 256 bits)", gpu::DeviceType::cpu, {}},
        {1, "Intel(R) UHD Graphics 630", gpu::DeviceType::integrated, {}},
        {2, "NVIDIA GeForce RTX 4090", gpu::DeviceType::discrete, {}},
    };
}

std::size_t chosen(const std::vector<gpu::DeviceCandidate>& c, std::string_view selector = {}) {
    auto result = gpu::choose_device(c, selector, "LANTERN_VK_DEVICE");
    EXPECT_TRUE(result) << (result ? "" : result.error().message);
    return result ? *result : SIZE_MAX;
}

} // namespace

TEST(DeviceChoice, PrefersDiscreteThenIntegratedThenVirtualThenCpu) {
    auto c = three_devices();
    EXPECT_EQ(chosen(c), 2u);
    c[2].problems = {"missing VK_KHR_push_descriptor"};
    EXPECT_EQ(chosen(c), 1u);
    c[1].type = gpu::DeviceType::virtual_gpu;
    EXPECT_EQ(chosen(c), 1u);
    c[1].problems = {"Vulkan 1.1.0 < 1.2"};
    EXPECT_EQ(chosen(c), 0u);
    EXPECT_LT(gpu::device_type_rank(gpu::DeviceType::discrete), gpu::device_type_rank(gpu::DeviceType::integrated));
    EXPECT_LT(gpu::device_type_rank(gpu::DeviceType::integrated), gpu::device_type_rank(gpu::DeviceType::virtual_gpu));
    EXPECT_LT(gpu::device_type_rank(gpu::DeviceType::virtual_gpu), gpu::device_type_rank(gpu::DeviceType::cpu));
}

TEST(DeviceChoice, FirstListedWinsAmongEquals) {
    std::vector<gpu::DeviceCandidate> c = {{0, "GPU A", gpu::DeviceType::discrete, {}},
                                           {1, "GPU B", gpu::DeviceType::discrete, {}}};
    EXPECT_EQ(chosen(c), 0u);
}

TEST(DeviceChoice, SelectorByIndexOrCaseInsensitiveNameSubstring) {
    const auto c = three_devices();
    EXPECT_EQ(chosen(c, "0"), 0u);
    EXPECT_EQ(chosen(c, "1"), 1u);
    EXPECT_EQ(chosen(c, "LLVMPIPE"), 0u);
    EXPECT_EQ(chosen(c, "uhd graphics"), 1u);
    EXPECT_EQ(chosen(c, "rtx"), 2u);
}

TEST(DeviceChoice, SelectorMatchingNothingListsTheDevices) {
    const auto c = three_devices();
    auto result = gpu::choose_device(c, "radeon", "LANTERN_VK_DEVICE");
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message,
              "no Vulkan device: LANTERN_VK_DEVICE='radeon' matches none of: 0 'llvmpipe (LLVM 15.0.6, "
              "256 bits)' (cpu), 1 'Intel(R) UHD Graphics 630' (integrated), 2 'NVIDIA GeForce RTX "
              "4090' (discrete)");
    EXPECT_FALSE(gpu::choose_device(c, "7", "LANTERN_VK_DEVICE"));
}

TEST(DeviceChoice, UnsuitableMatchesExplainWhy) {
    auto c = three_devices();
    c[2].problems = {"missing VK_KHR_push_descriptor", "R8_UNORM lacks UNIFORM_TEXEL_BUFFER"};
    auto result = gpu::choose_device(c, "nvidia", "LANTERN_VK_DEVICE");
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message,
              "no Vulkan device: no suitable device: 2 'NVIDIA GeForce RTX 4090' (discrete): missing "
              "VK_KHR_push_descriptor; R8_UNORM lacks UNIFORM_TEXEL_BUFFER");
}

TEST(DeviceChoice, NoDevicesIsAnError) {
    auto result = gpu::choose_device({}, "", "LANTERN_VK_DEVICE");
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message.rfind("no Vulkan device: ", 0), 0u);
}
