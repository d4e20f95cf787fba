// StreamBuffer on real Vulkan: a write lands whole, a later write replaces it, and writes up
// to 1 MiB allocate no device memory (they travel inside the command buffer, 64 KiB a
// command), so a per-frame box list of any usual size does not make device memory rise and
// fall every frame.
#include "render_test_support.hpp"

#include "gpu/gpu_test_support.hpp"
#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/render/stream_buffer.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

namespace lantern::render {
namespace {

using StreamBufferTest = test::RenderTest;

TEST_F(StreamBufferTest, WritesUpToAMebibyteLandWholeWithoutAnAllocation) {
    constexpr std::size_t words = (300u << 10) / 4; // 300 KiB: five commands, the last partial
    StreamBuffer stream = StreamBuffer::create(device(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 4 * words + 4096, "test");
    for (std::uint32_t round = 0; round < 3; ++round) {
        std::vector<std::uint32_t> values(words - round * 1000);
        std::iota(values.begin(), values.end(), 7u + round * 100000u);
        const std::uint64_t before = device().memory_allocated();
        gpu::CommandList cmd = device().begin("stream buffer test");
        stream.write(cmd, test::bytes_of(values));
        EXPECT_EQ(device().memory_allocated(), before) << "a staging buffer was allocated";
        device().wait(device().submit(std::move(cmd)));
        const std::vector<std::uint32_t> back = test::read_back_as<std::uint32_t>(device(), stream.buffer());
        ASSERT_GE(back.size(), values.size());
        EXPECT_TRUE(std::equal(values.begin(), values.end(), back.begin())) << "round " << round;
    }
}

TEST_F(StreamBufferTest, LargerWritesStillLandWhole) {
    constexpr std::size_t words = (1300u << 10) / 4; // past the inline limit: a staging copy
    StreamBuffer stream = StreamBuffer::create(device(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 4 * words, "test");
    std::vector<std::uint32_t> values(words);
    std::iota(values.begin(), values.end(), 3u);
    gpu::CommandList cmd = device().begin("stream buffer test");
    stream.write(cmd, test::bytes_of(values));
    device().wait(device().submit(std::move(cmd)));
    EXPECT_EQ(test::read_back_as<std::uint32_t>(device(), stream.buffer()), values);
}

} // namespace
} // namespace lantern::render
