// Recording GPU work: CommandList (one VkCommandBuffer) and the push-descriptor builder.
// Compute, transfers and barriers on every device; raster commands (dynamic rendering,
// graphics pipelines, draws) on devices created with DeviceOptions::graphics.
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

#include "lantern/gpu/graphics_pipeline.hpp"
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
class Image;
class Sampler;
class TimestampQueries;

namespace detail {
struct TimestampTicket;
}

// Resources for the next dispatch or draw, binding by binding, for CommandList::push_descriptors.
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
    // `image` (SAMPLED usage) must be in SHADER_READ_ONLY_OPTIMAL when the draw or dispatch runs.
    DescriptorWrites& combined_image_sampler(std::uint32_t binding, const Image& image,
                                             const Sampler& sampler);

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
        VkFlags usage = 0; // the buffer's VkBufferUsageFlags, or the image's VkImageUsageFlags
        VkBufferView view = VK_NULL_HANDLE;
        VkImageView image_view = VK_NULL_HANDLE;
        VkSampler sampler = VK_NULL_HANDLE;
    };
    DescriptorWrites& add(const Write& write);
    DescriptorWrites& add_buffer(std::uint32_t binding, BindingType type, const Buffer& buffer,
                                 VkDeviceSize offset, VkDeviceSize range);

    std::array<Write, ComputePipeline::max_bindings> writes_{};
    std::uint32_t count_ = 0;
};

// The attachments of a rendering scope (CommandList::begin_rendering).
struct ColorAttachment {
    const Image* image = nullptr;
    VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR; // or LOAD, DONT_CARE
    VkClearColorValue clear{};                             // used with CLEAR
};
struct DepthAttachment {
    const Image* image = nullptr; // nullptr: no depth attachment
    VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR;
    float clear = 1.0f;
    bool store = false; // keep the depth values after end_rendering (read-back, later scopes)
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
    // Sets the set 0 of the pipeline bound last (compute or graphics). Each write's type must
    // match the pipeline's binding (asserted); buffers need the matching usage flag
    // (STORAGE_BUFFER, UNIFORM_BUFFER, ...), images SAMPLED.
    void push_descriptors(const DescriptorWrites& writes);
    // Bytes [offset, offset + size) of the bound pipeline's push-constant block (both stages
    // of a graphics pipeline); offset and size multiples of 4 within push_constant_size().
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
    void barrier_compute_to_graphics();  // compute writes -> vertex/fragment shader reads
    void barrier_transfer_to_graphics(); // copy/fill/update/upload -> vertex, index, uniform
                                         // and shader reads of draws
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

    // --- Images (each command names the layout the image is in when it runs) -------------
    // A layout transition whose barrier follows from the two layouts: the writes (or reads)
    // that `from` implies finish before the accesses that `to` implies. Handled: UNDEFINED
    // (contents discarded), TRANSFER_SRC/DST_OPTIMAL, COLOR_ATTACHMENT_OPTIMAL,
    // DEPTH_STENCIL_ATTACHMENT_OPTIMAL, SHADER_READ_ONLY_OPTIMAL (fragment and compute
    // reads), PRESENT_SRC_KHR, GENERAL (every stage and access). `from` == `to` is a pure
    // execution and memory barrier (e.g. between two blits into one image).
    void transition(const Image& image, VkImageLayout from, VkImageLayout to);
    // Copies tightly packed rows (width * image_texel_size bytes each, top row first) from
    // src at src_offset into the whole of dst (in TRANSFER_DST_OPTIMAL); colour images only.
    void copy_buffer_to_image(const Buffer& src, VkDeviceSize src_offset, const Image& dst);
    // The inverse: the whole of src (in TRANSFER_SRC_OPTIMAL; its depth aspect for depth
    // formats) into dst at dst_offset, tightly packed.
    void copy_image_to_buffer(const Image& src, const Buffer& dst, VkDeviceSize dst_offset = 0);
    // Fills a colour image (in TRANSFER_DST_OPTIMAL) with `color` (float, int or uint values
    // as the format is).
    void clear_color(const Image& image, const VkClearColorValue& color);
    // Scaled copy of src_rect of src (TRANSFER_SRC_OPTIMAL) into dst_rect of dst
    // (TRANSFER_DST_OPTIMAL), converting formats (both need the BLIT_SRC/BLIT_DST format
    // features). VK_FILTER_NEAREST with an integer scale copies texels exactly.
    void blit(const Image& src, const VkRect2D& src_rect, const Image& dst,
              const VkRect2D& dst_rect, VkFilter filter);

    // --- Raster (devices created with DeviceOptions::graphics) -------------------------------
    // Begins a dynamic-rendering scope over the whole of color.image
    // (COLOR_ATTACHMENT_OPTIMAL) and, when depth.image is set, a depth attachment of the same
    // size (DEPTH_STENCIL_ATTACHMENT_OPTIMAL). Sets viewport and scissor to the whole target.
    // No other command than draws and their state may be recorded until end_rendering.
    void begin_rendering(const ColorAttachment& color, const DepthAttachment& depth = {});
    void end_rendering();
    // Binds `pipeline` for the following push_descriptors, push_constants and draws (inside a
    // rendering scope whose formats are the pipeline's).
    void bind(const GraphicsPipeline& pipeline);
    // Pixels of the target; y grows downwards, depth 0..1.
    void set_viewport(float x, float y, float width, float height);
    void set_scissor(const VkRect2D& rect);
    // The buffer (VERTEX_BUFFER usage) the bound pipeline's VertexLayout reads.
    void bind_vertex_buffer(const Buffer& buffer, VkDeviceSize offset = 0);
    // INDEX_BUFFER usage; offset a multiple of the index size.
    void bind_index_buffer(const Buffer& buffer, VkIndexType type, VkDeviceSize offset = 0);
    void draw(std::uint32_t vertex_count, std::uint32_t instance_count = 1,
              std::uint32_t first_vertex = 0, std::uint32_t first_instance = 0);
    void draw_indexed(std::uint32_t index_count, std::uint32_t instance_count = 1,
                      std::uint32_t first_index = 0, std::int32_t vertex_offset = 0,
                      std::uint32_t first_instance = 0);

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
    void bind_layout(VkPipelineBindPoint point, VkPipelineLayout layout,
                     std::span<const BindingType> bindings, std::uint32_t push_constant_size,
                     VkShaderStageFlags push_stages);

    Device* device_ = nullptr;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    std::uint32_t context_ = 0;  // index of the Device's submission context
    std::uint64_t list_id_ = 0;  // order of Device::begin calls (deferred destruction)
    // The pipeline bound last: push_descriptors and push_constants target it.
    VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
    VkShaderStageFlags push_stages_ = 0;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    bool rendering_ = false; // inside begin_rendering/end_rendering
    std::array<BindingType, ComputePipeline::max_bindings> bindings_{};
    std::uint32_t binding_count_ = 0;
    std::uint32_t push_constant_size_ = 0;
    int label_depth_ = 0;
    // Timestamp query sets recorded here; stamped with this list's serial on submit.
    std::vector<std::shared_ptr<detail::TimestampTicket>> tickets_;
};

} // namespace lantern::gpu
