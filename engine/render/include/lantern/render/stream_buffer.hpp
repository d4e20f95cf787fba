// A GPU buffer rewritten by the CPU every frame (vertices, instances, indices), written
// inside the frame's CommandList so that frames in flight never see each other's data.
//
//   StreamBuffer instances = StreamBuffer::create(device, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
//                                                 64 * 1024, "sprites");
//   instances.write(cmd, std::as_bytes(std::span(sprites)));   // outside a rendering scope
//   target.begin(cmd); cmd.bind_vertex_buffer(instances.buffer()); ... draws ...
//
// The write is ordered after every earlier draw reading the buffer (in this list or an
// earlier submission) and before every later one, so one device-local buffer serves any
// number of frames in flight. Up to 1 MiB the bytes travel inside the command buffer
// (vkCmdUpdateBuffer, 64 KiB a command): no allocation per frame. (The game's box list
// passes 64 KiB in big views; with a staging buffer per write, device memory rose and fell
// every frame: the soak test's "no growth" saw it.) Larger writes take a staging buffer per
// write (one allocation: fine for a few per frame).
//
// Static geometry needs none of this: create the buffer once and Device::upload it.
// Ownership: move-only (a gpu::Buffer); destroy before the Device.
#pragma once

#include "lantern/gpu/buffer.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <span>

namespace lantern::gpu {
class CommandList;
class Device;
} // namespace lantern::gpu

namespace lantern::render {

class StreamBuffer {
  public:
    // `usage`: VERTEX_BUFFER, INDEX_BUFFER, UNIFORM_BUFFER, STORAGE_BUFFER; capacity in bytes.
    static StreamBuffer create(gpu::Device& device, VkBufferUsageFlags usage, VkDeviceSize capacity,
                               const char* name);
    StreamBuffer() = default;

    // Records the write of `bytes` (at most capacity(), a multiple of 4) at offset 0, with
    // the barriers around it. Outside rendering scopes.
    void write(gpu::CommandList& cmd, std::span<const std::byte> bytes);

    const gpu::Buffer& buffer() const { return buffer_; }
    VkDeviceSize capacity() const { return buffer_.size(); }

  private:
    gpu::Buffer buffer_;
};

} // namespace lantern::render
