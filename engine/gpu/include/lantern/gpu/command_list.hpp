// Recording GPU work: CommandList (one VkCommandBuffer) and the push-descriptor builder.
//
// Life of a CommandList: Device::begin() hands out one in the recording state; record
// commands; Device::submit(std::move(list)) ends and submits it and returns its serial.
// A list destroyed without being submitted is discarded (its commands never run). Command
// buffers come from per-submission pools that the Device recycles once the submission
// completed, so recording allocates nothing from Vulkan after warm-up.
//
// Synchronisation is explicit: commands in one list, and lists in submission order, run in
// order but may overlap unless a barrier separates them. Put barrier_compute_to_compute()
// between a dispatch that writes and one that reads the same memory, and the transfer
// variants around copy/fill/update/upload. A barrier at the end of a list also orders work
// in later submissions.
//
// Threads: a CommandList is recorded by one thread at a time; different lists may be
// recorded on different threads. Device::begin and Device::submit belong to the
// submission thread (see device.hpp).
#pragma once

#include "lantern/gpu/pipeline.hpp"

#include <vulkan/vulkan.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

namespace lantern::gpu {

class Buffer;
class BufferView;
class Device;
class TimestampQueries;

namespace detail {
struct TimestampTicket;
}

// Resources for the next dispatch, binding by binding, for CommandList::push_descriptors.
// A plain value: build it on the stack per dispatch. Offsets of storage/uniform buffers must
// be multiples of the device's min*BufferOffsetAlignment (Capabilities); the ranges default
// to "to the end of the buffer".
class DescriptorWrites {
  public:
    DescriptorWrites& storage_buffer(std::uint32_t binding, const Buffer& buffer,
                                     VkDeviceSize offset = 0, VkDeviceSize range = VK_WHOLE_SIZE);
    DescriptorWrites& uniform_buffer(std::uint32_t binding, const Buffer& buffer,
                                     VkDeviceSize offset = 0, VkDeviceSize range = VK_WHOLE_SIZE);
    DescriptorWrites& uniform_texel_buffer(std::uint32_t binding, const BufferView& view);
    DescriptorWrites& storage_texel_buffer(std::uint32_t binding, const BufferView& view);

    std::uint32_t size() const { return count_; }

  private:
    friend class CommandList;
    struct Write {
        std::uint32_t binding = 0;
        BindingType type = BindingType::storage_buffer;
        VkBuffer buffer = VK_NULL_HANDLE;
        VkDeviceSize offset = 0;
        VkDeviceSize range = 0;
        VkDeviceSize buffer_size = 0;
        VkBufferUsageFlags usage = 0;
        VkBufferView view = VK_NULL_HANDLE;
    };
    DescriptorWrites& add(const Write& write);
    DescriptorWrites& add_buffer(std::uint32_t binding, BindingType type, const Buffer& buffer,
                                 VkDeviceSize offset, VkDeviceSize range);

    std::array<Write, ComputePipeline::max_bindings> writes_{};
    std::uint32_t count_ = 0;
};

class CommandList {
  public:
    CommandList() = default;
    CommandList(CommandList&& other) noexcept;
    CommandList& operator=(CommandList&& other) noexcept;
    CommandList(const CommandList&) = delete;
    CommandList& operator=(const CommandList&) = delete;
    ~CommandList(); // discards an unsubmitted list

    // True while recording (from Device::begin until submitted or discarded).
    explicit operator bool() const { return cmd_ != VK_NULL_HANDLE; }
    VkCommandBuffer vk() const { return cmd_; }
    Device* device() const { return device_; }

    // --- Compute ---------------------------------------------------------------------------
    // Binds `pipeline` for the following push_descriptors, push_constants and dispatches.
    void bind(const ComputePipeline& pipeline);
    // Sets the bound pipeline's set 0. Each write's type must match the pipeline's binding
    // (asserted); buffers need the matching usage flag (STORAGE_BUFFER, UNIFORM_BUFFER, ...).
    void push_descriptors(const DescriptorWrites& writes);
    // Bytes [offset, offset + size) of the bound pipeline's push-constant block; offset and
    // size multiples of 4 within push_constant_size().
    void push_constants(const void* data, std::uint32_t size, std::uint32_t offset = 0);
    template <typename T>
    void push_constants(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>, "push constants are plain bytes");
        push_constants(&value, static_cast<std::uint32_t>(sizeof(T)));
    }
    // Work groups (not invocations) in x, y, z.
    void dispatch(std::uint32_t groups_x, std::uint32_t groups_y = 1, std::uint32_t groups_z = 1);

    // --- Barriers (global memory barriers; cheap on every driver Lantern targets) -----------
    void barrier_compute_to_compute();  // shader writes -> shader reads/writes
    void barrier_compute_to_transfer(); // shader writes -> copy/fill/update
    void barrier_transfer_to_compute(); // copy/fill/update/upload -> shader reads/writes
    void barrier_transfer_to_transfer();
    void barrier_to_host();             // shader and transfer writes -> host reads (readback)
    // The general forms, for anything the helpers above do not cover.
    void memory_barrier(VkPipelineStageFlags src_stages, VkAccessFlags src_access,
                        VkPipelineStageFlags dst_stages, VkAccessFlags dst_access);
    void buffer_barrier(const Buffer& buffer, VkPipelineStageFlags src_stages,
                        VkAccessFlags src_access, VkPipelineStageFlags dst_stages,
                        VkAccessFlags dst_access, VkDeviceSize offset = 0,
                        VkDeviceSize size = VK_WHOLE_SIZE);

    // --- Transfers (ranges in bytes; offsets and sizes of fill/update multiples of 4) -------
    void copy_buffer(const Buffer& src, VkDeviceSize src_offset, const Buffer& dst,
                     VkDeviceSize dst_offset, VkDeviceSize size);
    // Sets every 32-bit word of the range to `value`; size VK_WHOLE_SIZE = to the end.
    void fill_buffer(const Buffer& dst, std::uint32_t value, VkDeviceSize offset = 0,
                     VkDeviceSize size = VK_WHOLE_SIZE);
    // Copies `bytes` into the command buffer itself (at most 65536 bytes): for small,
    // per-frame data.
    void update_buffer(const Buffer& dst, VkDeviceSize offset, std::span<const std::byte> bytes);
    // Writes `bytes` to dst at `offset` when this list runs, any size: small aligned writes
    // use update_buffer, larger ones a temporary upload buffer (one allocation each: fine for
    // a few per frame, use a persistent upload buffer + copy_buffer for streaming). Follow
    // with barrier_transfer_to_compute() before shaders read the range.
    void upload(const Buffer& dst, VkDeviceSize offset, std::span<const std::byte> bytes);

    // --- Debugging ---------------------------------------------------------------------------
    // Named regions for GPU debuggers and validation messages (VK_EXT_debug_utils labels;
    // no-ops without it). `name` is read during the call only. Must be balanced by submit.
    void begin_label(const char* name);
    void end_label();
    // Writes the GPU clock into `query` of `pool` once all earlier commands completed
    // (BOTTOM_OF_PIPE). TimestampQueries wraps this; use it rather than the raw form.
    void write_timestamp(VkQueryPool pool, std::uint32_t query);

  private:
    friend class Device;
    friend class TimestampQueries;
    void release();

    Device* device_ = nullptr;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    std::uint32_t context_ = 0;  // index of the Device's submission context
    std::uint64_t list_id_ = 0;  // order of Device::begin calls (deferred destruction)
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    std::array<BindingType, ComputePipeline::max_bindings> bindings_{};
    std::uint32_t binding_count_ = 0;
    std::uint32_t push_constant_size_ = 0;
    int label_depth_ = 0;
    // Timestamp query sets recorded here; stamped with this list's serial on submit.
    std::vector<std::shared_ptr<detail::TimestampTicket>> tickets_;
};

} // namespace lantern::gpu
