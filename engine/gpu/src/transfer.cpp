// Convenience transfers: Device::upload and the blocking Device::read_back.
#include "device_internal.hpp"

#include "lantern/gpu/vk_check.hpp"

#include <cstring>

namespace lantern::gpu {

std::uint64_t Device::upload(const Buffer& dst, std::span<const std::byte> bytes, VkDeviceSize offset) {
    LANTERN_ASSERT(dst && dst.device() == this && offset + bytes.size() <= dst.size(),
                   "gpu::Device::upload outside the buffer");
    if (bytes.empty()) return completed_serial();
    if (dst.mapped()) {
        // Coherent memory: the write is visible to every later submission.
        std::memcpy(dst.mapped() + offset, bytes.data(), bytes.size());
        return completed_serial();
    }
    Buffer staging = create_buffer({bytes.size(), 0, MemoryKind::upload, "Device::upload staging"});
    std::memcpy(staging.mapped(), bytes.data(), bytes.size());
    CommandList cmd = begin("Device::upload");
    // Earlier submissions may still read or write dst: order the copy after them.
    cmd.memory_barrier(VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    cmd.copy_buffer(staging, 0, dst, offset, bytes.size());
    cmd.memory_barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                           VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                           VK_ACCESS_TRANSFER_WRITE_BIT);
    return submit(std::move(cmd));
    // staging is destroyed here, after the submit: freed once that serial completed.
}

std::vector<std::byte> Device::read_back(const Buffer& src, VkDeviceSize offset, VkDeviceSize size) {
    LANTERN_ASSERT(src && src.device() == this && offset <= src.size(), "gpu::Device::read_back outside the buffer");
    if (size == VK_WHOLE_SIZE) size = src.size() - offset;
    LANTERN_ASSERT(offset + size <= src.size(), "gpu::Device::read_back outside the buffer");
    std::vector<std::byte> out(size);
    if (size == 0) return out;

    CommandList cmd = begin("Device::read_back");
    // Every earlier write (any stage) -> the copy below or the host read.
    cmd.memory_barrier(VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                       VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT);
    Buffer staging;
    const std::byte* source = src.mapped() ? src.mapped() + offset : nullptr;
    if (!source) {
        staging = create_buffer({size, 0, MemoryKind::readback, "Device::read_back staging"});
        cmd.copy_buffer(src, offset, staging, 0, size);
        cmd.barrier_to_host();
        source = staging.mapped();
    }
    wait(submit(std::move(cmd)));
    std::memcpy(out.data(), source, size);
    return out;
}

} // namespace lantern::gpu
