// GPU buffers and texel views of them: move-only handles created by a Device.
//
// Ownership: a Buffer or BufferView owns its Vulkan objects. Destroying (or reset()ing,
// or move-assigning over) one does not free anything at once: the objects are queued on
// the Device and freed once every submission that may still use them has completed on the
// GPU (docs/gpu.md, "Deferred destruction"). So a handle may be dropped right after the
// CommandList that uses it was recorded or submitted. Every handle must be destroyed
// before its Device.
//
// Threads: a handle is used by one thread at a time; handles may be destroyed on any
// thread (the Device's deletion queue locks).
#pragma once

#include "lantern/gpu/owning_handle.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>

namespace lantern::gpu {

class Device;

// Where a buffer's memory lives and whether the CPU can see it.
enum class MemoryKind : std::uint8_t {
    // GPU memory, not mapped. Fill it with Device::upload, CommandList::upload/copy/fill.
    device_local,
    // Host-visible, host-coherent, mapped for the buffer's lifetime: the CPU writes, the
    // GPU reads (uniforms, per-frame data, staging). CPU writes need no flush; they are seen
    // by submissions made after them. Do not write a range an in-flight submission reads.
    upload,
    // Host-visible, host-coherent, host-cached where the device offers it, mapped: the GPU
    // writes, the CPU reads after the writing submission completed (and after a
    // barrier_to_host() in it).
    readback,
};

const char* to_string(MemoryKind kind);

struct BufferDesc {
    VkDeviceSize size = 0;     // bytes, > 0
    VkBufferUsageFlags usage = 0; // TRANSFER_SRC and TRANSFER_DST are always added
    MemoryKind memory = MemoryKind::device_local;
    const char* name = nullptr; // debug name for validation messages and GPU debuggers
};

struct BufferFields {
    Device* device_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_object_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    VkBufferUsageFlags usage_ = 0;
    MemoryKind memory_ = MemoryKind::device_local;
    std::byte* mapped_ = nullptr;
};

// Move-only; reset() (or destruction) queues the buffer for deferred destruction.
class Buffer : public OwningHandle<Buffer, BufferFields> {
  public:
    explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }
    VkBuffer vk() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    VkBufferUsageFlags usage() const { return usage_; }
    MemoryKind memory() const { return memory_; }
    // The persistent mapping of an upload or readback buffer (size() bytes); nullptr for
    // device_local buffers.
    std::byte* mapped() const { return mapped_; }
    Device* device() const { return device_; }

  private:
    friend class Device;
    friend class OwningHandle<Buffer, BufferFields>;
    static void retire(BufferFields& f);
};

// A typed window onto a buffer (VkBufferView), bound as a uniform texel buffer (reads with
// format conversion, e.g. R8_UNORM -> float, RGBA16F -> vec4) or a storage texel buffer.
// The buffer must outlive the view's last use on the GPU; dropping both handles together
// is fine because both are destroyed deferred.
struct BufferViewFields {
    Device* device_ = nullptr;
    VkBufferView view_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkDeviceSize offset_ = 0;
    VkDeviceSize range_ = 0;
    VkBufferUsageFlags buffer_usage_ = 0;
};

// Move-only; reset() (or destruction) queues the view for deferred destruction.
class BufferView : public OwningHandle<BufferView, BufferViewFields> {
  public:
    explicit operator bool() const { return view_ != VK_NULL_HANDLE; }
    VkBufferView vk() const { return view_; }
    VkFormat format() const { return format_; }
    VkDeviceSize offset() const { return offset_; } // bytes into the buffer
    VkDeviceSize range() const { return range_; }   // bytes, a whole number of texels
    // The viewed buffer's usage flags (the descriptor builder checks them).
    VkBufferUsageFlags buffer_usage() const { return buffer_usage_; }

  private:
    friend class Device;
    friend class OwningHandle<BufferView, BufferViewFields>;
    static void retire(BufferViewFields& f);
};

} // namespace lantern::gpu
