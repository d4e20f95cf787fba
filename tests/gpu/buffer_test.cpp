// Buffers: every memory kind round-trips through upload/read_back; CommandList transfers;
// buffer views.
#include "gpu/gpu_test_support.hpp"

#include "lantern/gpu/device.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <numeric>
#include <vector>

namespace gpu = lantern::gpu;
using lantern::test::bytes_of;
using lantern::test::read_back_as;

namespace {

class Buffers : public lantern::test::GpuTest {};

std::vector<std::byte> pattern(std::size_t size, unsigned seed) {
    std::vector<std::byte> out(size);
    for (std::size_t i = 0; i < size; ++i) out[i] = static_cast<std::byte>((i * 131 + seed * 7 + (i >> 8)) & 0xff);
    return out;
}

} // namespace

TEST_F(Buffers, EveryMemoryKindRoundTrips) {
    // An odd size: the staging copies do not need whole words.
    constexpr std::size_t size = 4096 + 3;
    for (gpu::MemoryKind kind : {gpu::MemoryKind::device_local, gpu::MemoryKind::upload, gpu::MemoryKind::readback}) {
        SCOPED_TRACE(gpu::to_string(kind));
        gpu::Buffer buffer = device().create_buffer({size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, kind, "round trip"});
        ASSERT_TRUE(buffer);
        EXPECT_EQ(buffer.size(), size);
        EXPECT_EQ(buffer.memory(), kind);
        EXPECT_EQ(buffer.mapped() != nullptr, kind != gpu::MemoryKind::device_local);
        EXPECT_TRUE(buffer.usage() & VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
        EXPECT_TRUE(buffer.usage() & VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        EXPECT_TRUE(buffer.usage() & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

        const auto data = pattern(size, static_cast<unsigned>(kind));
        device().upload(buffer, data);
        EXPECT_EQ(device().read_back(buffer), data);
        const std::vector<std::byte> middle(data.begin() + 17, data.begin() + 17 + 1000);
        EXPECT_EQ(device().read_back(buffer, 17, 1000), middle);

        // A partial upload at an offset leaves the rest alone.
        const auto patch = pattern(100, 99);
        device().upload(buffer, patch, 50);
        auto expected = data;
        std::copy(patch.begin(), patch.end(), expected.begin() + 50);
        EXPECT_EQ(device().read_back(buffer), expected);
    }
}

TEST_F(Buffers, CommandListFillUpdateUploadAndCopy) {
    constexpr std::size_t words = 20000; // 80 000 bytes: larger than one vkCmdUpdateBuffer
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    gpu::Buffer a = device().create_buffer({words * 4, usage, gpu::MemoryKind::device_local, "a"});
    gpu::Buffer b = device().create_buffer({words * 4, usage, gpu::MemoryKind::device_local, "b"});
    std::vector<std::uint32_t> big(words);
    std::iota(big.begin(), big.end(), 1000u);
    const std::vector<std::uint32_t> small = {1, 2, 3, 4};

    gpu::CommandList cmd = device().begin("transfers");
    cmd.fill_buffer(a, 0xdeadbeefu);
    cmd.barrier_transfer_to_transfer();
    cmd.update_buffer(a, 8 * 4, bytes_of(small));
    cmd.upload(b, 0, bytes_of(big)); // staging path (too large for an update)
    cmd.barrier_transfer_to_transfer(); // the overlapping write below must land second
    cmd.upload(b, 4, bytes_of(small)); // update path
    cmd.barrier_transfer_to_transfer();
    cmd.copy_buffer(b, 0, a, 100 * 4, 50 * 4);
    device().wait(device().submit(std::move(cmd)));

    std::vector<std::uint32_t> expected_a(words, 0xdeadbeefu);
    std::copy(small.begin(), small.end(), expected_a.begin() + 8);
    std::vector<std::uint32_t> expected_b = big;
    std::copy(small.begin(), small.end(), expected_b.begin() + 1);
    std::copy(expected_b.begin(), expected_b.begin() + 50, expected_a.begin() + 100);
    EXPECT_EQ(read_back_as<std::uint32_t>(device(), a), expected_a);
    EXPECT_EQ(read_back_as<std::uint32_t>(device(), b), expected_b);
}

TEST_F(Buffers, ViewsReportFormatOffsetAndWholeTexelRange) {
    const VkDeviceSize align = device().capabilities().min_texel_buffer_offset_alignment;
    gpu::Buffer buffer = device().create_buffer(
        {align * 4 + 13, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, gpu::MemoryKind::device_local, "texels"});
    gpu::BufferView whole = device().create_buffer_view(buffer, VK_FORMAT_R16G16B16A16_SFLOAT);
    ASSERT_TRUE(whole);
    EXPECT_EQ(whole.format(), VK_FORMAT_R16G16B16A16_SFLOAT);
    EXPECT_EQ(whole.offset(), 0u);
    EXPECT_EQ(whole.range(), (align * 4 + 13) / 8 * 8); // rounded down to whole texels
    gpu::BufferView part = device().create_buffer_view(buffer, VK_FORMAT_R8_UNORM, align, 5, "part");
    EXPECT_EQ(part.offset(), align);
    EXPECT_EQ(part.range(), 5u);

    gpu::BufferView moved = std::move(part);
    EXPECT_FALSE(part); // NOLINT(bugprone-use-after-move): the moved-from state is the contract
    EXPECT_TRUE(moved);
    moved.reset();
    EXPECT_FALSE(moved);
}

TEST_F(Buffers, MovedFromHandlesAreEmptyAndDestroyOnce) {
    gpu::Buffer a = device().create_buffer({256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::upload, "a"});
    const VkBuffer handle = a.vk();
    gpu::Buffer b = std::move(a);
    EXPECT_FALSE(a); // NOLINT(bugprone-use-after-move)
    EXPECT_EQ(a.mapped(), nullptr);
    EXPECT_EQ(b.vk(), handle);
    gpu::Buffer c = device().create_buffer({64, 0, gpu::MemoryKind::device_local, "c"});
    c = std::move(b); // c's old buffer is retired, b's moves in
    EXPECT_EQ(c.vk(), handle);
    device().collect();
    EXPECT_EQ(device().pending_deletions(), 0u); // nothing was in flight: freed at once
}

TEST(BufferContracts, DescriptorOfAnEmptyViewDies) {
    // Re-executes the binary for the death test: forking a process with driver threads is unsafe.
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(gpu::DescriptorWrites().uniform_texel_buffer(0, gpu::BufferView{}), "empty buffer view");
}
