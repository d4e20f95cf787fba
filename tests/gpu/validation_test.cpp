// The validation counter sees invalid Vulkan usage (and GpuTest fails on any message).
#include "gpu/gpu_test_support.hpp"

#include "lantern/gpu/device.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace gpu = lantern::gpu;

namespace {
class Validation : public lantern::test::GpuTest {};
} // namespace

TEST_F(Validation, OutOfRangeBufferBarrierIsCountedAndKept) {
    if (!device().validation_enabled()) LANTERN_SKIP_NO_GPU("VK_LAYER_KHRONOS_validation is not installed");
    ASSERT_EQ(device().validation_message_count(), 0u);
    gpu::Buffer buffer = device().create_buffer({256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                 gpu::MemoryKind::device_local, "barrier target"});
    {
        gpu::CommandList cmd = device().begin("invalid barrier");
        // Raw Vulkan on purpose: CommandList::buffer_barrier asserts on this range first.
        VkBufferMemoryBarrier barrier{};
        barrier.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
        barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.buffer = buffer.vk();
        barrier.offset = 0;
        barrier.size = buffer.size() + 256; // past the end: VUID-VkBufferMemoryBarrier-size-01189
        vkCmdPipelineBarrier(cmd.vk(), VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                             0, nullptr, 1, &barrier, 0, nullptr);
    } // discarded, never submitted

    EXPECT_GE(device().validation_message_count(), 1u);
    const auto messages = device().validation_messages();
    EXPECT_TRUE(std::any_of(messages.begin(), messages.end(), [](const std::string& m) {
        return m.find("VUID-VkBufferMemoryBarrier-size-01189") != std::string::npos;
    })) << "messages: " << ::testing::PrintToString(messages);

    // Accounted for: clear, so TearDown's zero-message check covers the rest of the test.
    device().clear_validation_messages();
    EXPECT_EQ(device().validation_message_count(), 0u);
    EXPECT_TRUE(device().validation_messages().empty());
}
