// StreamBuffer: per-frame writes ordered against the draws around them.
#include "lantern/render/stream_buffer.hpp"

#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/device.hpp"

#include <algorithm>

namespace lantern::render {

namespace {

// Every stage and access by which draws (and compute) read such buffers.
constexpr VkPipelineStageFlags reader_stages =
    VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
    VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags reader_accesses = VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT |
                                          VK_ACCESS_INDEX_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT |
                                          VK_ACCESS_SHADER_READ_BIT;

constexpr std::size_t max_update_bytes = 65536;     // vkCmdUpdateBuffer's limit per command
constexpr std::size_t max_inline_bytes = 1u << 20;  // in the command buffer up to this size

} // namespace

StreamBuffer StreamBuffer::create(gpu::Device& device, VkBufferUsageFlags usage,
                                  VkDeviceSize capacity, const char* name) {
    StreamBuffer stream;
    stream.buffer_ = device.create_buffer({capacity, usage, gpu::MemoryKind::device_local, name});
    return stream;
}

void StreamBuffer::write(gpu::CommandList& cmd, std::span<const std::byte> bytes) {
    LANTERN_ASSERT(buffer_ && bytes.size() <= buffer_.size() && bytes.size() % 4 == 0,
                   "render::StreamBuffer::write: more bytes than the capacity, or not whole words");
    if (bytes.empty()) return;
    // Write-after-read: the previous frame's draws may still be reading the buffer.
    cmd.memory_barrier(reader_stages, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_TRANSFER_WRITE_BIT);
    if (bytes.size() <= max_inline_bytes) {
        for (std::size_t at = 0; at < bytes.size(); at += max_update_bytes)
            cmd.update_buffer(buffer_, at, bytes.subspan(at, std::min(max_update_bytes, bytes.size() - at)));
    } else {
        cmd.upload(buffer_, 0, bytes);
    }
    cmd.memory_barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, reader_stages,
                       reader_accesses);
}

} // namespace lantern::render
