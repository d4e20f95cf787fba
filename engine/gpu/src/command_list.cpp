// CommandList recording: compute, push descriptors, barriers, transfers, labels. Image and
// raster commands are in raster.cpp.
#include "device_internal.hpp"

#include "lantern/gpu/vk_check.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

namespace lantern::gpu {

namespace {

// The buffer usage (or, for images, image usage) flag a descriptor type needs.
VkFlags required_usage(BindingType type) {
    switch (type) {
    case BindingType::storage_buffer: return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    case BindingType::uniform_buffer: return VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    case BindingType::uniform_texel_buffer: return VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    case BindingType::storage_texel_buffer: return VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT;
    case BindingType::combined_image_sampler: return VK_IMAGE_USAGE_SAMPLED_BIT;
    }
    return 0;
}

VkDescriptorType to_descriptor_type(BindingType type) {
    switch (type) {
    case BindingType::storage_buffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingType::uniform_buffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingType::uniform_texel_buffer: return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    case BindingType::storage_texel_buffer: return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
    case BindingType::combined_image_sampler: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    }
    return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}

constexpr VkDeviceSize max_update_bytes = 65536; // vkCmdUpdateBuffer's limit

} // namespace

// --- DescriptorWrites ------------------------------------------------------------------------

DescriptorWrites& DescriptorWrites::add(const Write& write) {
    LANTERN_ASSERT(count_ < writes_.size(), "gpu: more descriptor writes than max_bindings");
    for (std::uint32_t i = 0; i < count_; ++i)
        LANTERN_ASSERT(writes_[i].binding != write.binding, "gpu: binding written twice");
    writes_[count_++] = write;
    return *this;
}

DescriptorWrites& DescriptorWrites::add_buffer(std::uint32_t binding, BindingType type,
                                               const Buffer& buffer, VkDeviceSize offset,
                                               VkDeviceSize range) {
    LANTERN_ASSERT(buffer, "gpu: descriptor of an empty buffer");
    LANTERN_ASSERT(offset < buffer.size() && (range == VK_WHOLE_SIZE || offset + range <= buffer.size()),
                   "gpu: descriptor range outside the buffer");
    Write w;
    w.binding = binding;
    w.type = type;
    w.buffer = buffer.vk();
    w.offset = offset;
    w.range = range;
    w.buffer_size = buffer.size();
    w.usage = buffer.usage();
    return add(w);
}

DescriptorWrites& DescriptorWrites::storage_buffer(std::uint32_t binding, const Buffer& buffer,
                                                   VkDeviceSize offset, VkDeviceSize range) {
    return add_buffer(binding, BindingType::storage_buffer, buffer, offset, range);
}

DescriptorWrites& DescriptorWrites::uniform_buffer(std::uint32_t binding, const Buffer& buffer,
                                                   VkDeviceSize offset, VkDeviceSize range) {
    return add_buffer(binding, BindingType::uniform_buffer, buffer, offset, range);
}

DescriptorWrites& DescriptorWrites::uniform_texel_buffer(std::uint32_t binding, const BufferView& view) {
    LANTERN_ASSERT(view, "gpu: descriptor of an empty buffer view");
    Write w;
    w.binding = binding;
    w.type = BindingType::uniform_texel_buffer;
    w.view = view.vk();
    w.usage = view.buffer_usage();
    return add(w);
}

DescriptorWrites& DescriptorWrites::storage_texel_buffer(std::uint32_t binding, const BufferView& view) {
    LANTERN_ASSERT(view, "gpu: descriptor of an empty buffer view");
    Write w;
    w.binding = binding;
    w.type = BindingType::storage_texel_buffer;
    w.view = view.vk();
    w.usage = view.buffer_usage();
    return add(w);
}

DescriptorWrites& DescriptorWrites::combined_image_sampler(std::uint32_t binding,
                                                           const Image& image,
                                                           const Sampler& sampler) {
    LANTERN_ASSERT(image && sampler, "gpu: descriptor of an empty image or sampler");
    Write w;
    w.binding = binding;
    w.type = BindingType::combined_image_sampler;
    w.image_view = image.view();
    w.sampler = sampler.vk();
    w.usage = image.usage();
    return add(w);
}

// --- CommandList life -----------------------------------------------------------------------

CommandList::CommandList(CommandList&& other) noexcept { *this = std::move(other); }

CommandList& CommandList::operator=(CommandList&& other) noexcept {
    if (this != &other) {
        if (cmd_) device_->discard(*this);
        device_ = std::exchange(other.device_, nullptr);
        cmd_ = std::exchange(other.cmd_, VK_NULL_HANDLE);
        context_ = other.context_;
        list_id_ = other.list_id_;
        bind_point_ = other.bind_point_;
        push_stages_ = std::exchange(other.push_stages_, 0);
        layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
        rendering_ = std::exchange(other.rendering_, false);
        bindings_ = other.bindings_;
        binding_count_ = std::exchange(other.binding_count_, 0);
        push_constant_size_ = std::exchange(other.push_constant_size_, 0);
        label_depth_ = std::exchange(other.label_depth_, 0);
        tickets_ = std::move(other.tickets_);
        other.tickets_.clear();
    }
    return *this;
}

CommandList::~CommandList() {
    if (cmd_) device_->discard(*this);
}

void CommandList::release() {
    device_ = nullptr;
    cmd_ = VK_NULL_HANDLE;
    push_stages_ = 0;
    layout_ = VK_NULL_HANDLE;
    rendering_ = false;
    binding_count_ = 0;
    push_constant_size_ = 0;
    label_depth_ = 0;
    tickets_.clear();
}

// --- Compute ----------------------------------------------------------------------------------

void CommandList::bind_layout(VkPipelineBindPoint point, VkPipelineLayout layout,
                              std::span<const BindingType> bindings,
                              std::uint32_t push_constant_size, VkShaderStageFlags push_stages) {
    bind_point_ = point;
    layout_ = layout;
    std::copy(bindings.begin(), bindings.end(), bindings_.begin());
    binding_count_ = static_cast<std::uint32_t>(bindings.size());
    push_constant_size_ = push_constant_size;
    push_stages_ = push_stages;
}

void CommandList::bind(const ComputePipeline& pipeline) {
    LANTERN_ASSERT(cmd_ && pipeline, "gpu: bind on a closed list or of an empty pipeline");
    LANTERN_ASSERT(!rendering_, "gpu: compute pipeline bound inside a rendering scope");
    vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.vk());
    bind_layout(VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), pipeline.bindings(),
                pipeline.push_constant_size(), VK_SHADER_STAGE_COMPUTE_BIT);
}

void CommandList::push_descriptors(const DescriptorWrites& writes) {
    LANTERN_ASSERT(cmd_ && layout_, "gpu: push_descriptors needs a bound pipeline");
    const Capabilities& caps = device_->capabilities();
    std::array<VkWriteDescriptorSet, ComputePipeline::max_bindings> vk_writes{};
    std::array<VkDescriptorBufferInfo, ComputePipeline::max_bindings> buffers{};
    std::array<VkDescriptorImageInfo, ComputePipeline::max_bindings> images{};
    for (std::uint32_t i = 0; i < writes.count_; ++i) {
        const DescriptorWrites::Write& w = writes.writes_[i];
        LANTERN_ASSERT(w.binding < binding_count_ && bindings_[w.binding] == w.type,
                       "gpu: descriptor write does not match the bound pipeline's binding type");
        LANTERN_ASSERT((w.usage & required_usage(w.type)) != 0,
                       "gpu: buffer lacks the usage flag its descriptor type needs");
        VkWriteDescriptorSet& vk = vk_writes[i];
        vk.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        vk.dstBinding = w.binding;
        vk.descriptorCount = 1;
        vk.descriptorType = to_descriptor_type(w.type);
        if (w.view) {
            vk.pTexelBufferView = &w.view;
            continue;
        }
        if (w.image_view) {
            images[i] = {w.sampler, w.image_view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            vk.pImageInfo = &images[i];
            continue;
        }
        const bool uniform = w.type == BindingType::uniform_buffer;
        const VkDeviceSize alignment = uniform ? caps.min_uniform_buffer_offset_alignment
                                               : caps.min_storage_buffer_offset_alignment;
        LANTERN_ASSERT(w.offset % alignment == 0, "gpu: descriptor offset misaligned");
        const VkDeviceSize range = w.range == VK_WHOLE_SIZE ? w.buffer_size - w.offset : w.range;
        LANTERN_ASSERT(!uniform || range <= caps.max_uniform_buffer_range,
                       "gpu: uniform buffer range above maxUniformBufferRange");
        buffers[i] = {w.buffer, w.offset, w.range};
        vk.pBufferInfo = &buffers[i];
    }
    device_->dispatch_->cmd_push_descriptor_set(cmd_, bind_point_, layout_, 0, writes.count_,
                                                vk_writes.data());
}

void CommandList::push_constants(const void* data, std::uint32_t size, std::uint32_t offset) {
    LANTERN_ASSERT(cmd_ && layout_, "gpu: push_constants needs a bound pipeline");
    LANTERN_ASSERT(size > 0 && size % 4 == 0 && offset % 4 == 0 && offset + size <= push_constant_size_,
                   "gpu: push constants outside the pipeline's push-constant block");
    vkCmdPushConstants(cmd_, layout_, push_stages_, offset, size, data);
}

void CommandList::dispatch(std::uint32_t groups_x, std::uint32_t groups_y, std::uint32_t groups_z) {
    LANTERN_ASSERT(cmd_ && layout_ && bind_point_ == VK_PIPELINE_BIND_POINT_COMPUTE,
                   "gpu: dispatch needs a bound compute pipeline");
    vkCmdDispatch(cmd_, groups_x, groups_y, groups_z);
}

// --- Barriers -----------------------------------------------------------------------------------

void CommandList::memory_barrier(VkPipelineStageFlags src_stages, VkAccessFlags src_access,
                                 VkPipelineStageFlags dst_stages, VkAccessFlags dst_access) {
    LANTERN_ASSERT(cmd_ && !rendering_,
                   "gpu: barrier on a closed list or inside a rendering scope");
    auto barrier = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    barrier.srcAccessMask = src_access;
    barrier.dstAccessMask = dst_access;
    vkCmdPipelineBarrier(cmd_, src_stages, dst_stages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void CommandList::buffer_barrier(const Buffer& buffer, VkPipelineStageFlags src_stages,
                                 VkAccessFlags src_access, VkPipelineStageFlags dst_stages,
                                 VkAccessFlags dst_access, VkDeviceSize offset, VkDeviceSize size) {
    LANTERN_ASSERT(cmd_ && !rendering_ && buffer,
                   "gpu: buffer barrier on a closed list, in a rendering scope or of no buffer");
    LANTERN_ASSERT(offset < buffer.size() && (size == VK_WHOLE_SIZE || offset + size <= buffer.size()),
                   "gpu: buffer barrier range outside the buffer");
    auto barrier = vk_struct<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
    barrier.srcAccessMask = src_access;
    barrier.dstAccessMask = dst_access;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.buffer = buffer.vk();
    barrier.offset = offset;
    barrier.size = size;
    vkCmdPipelineBarrier(cmd_, src_stages, dst_stages, 0, 0, nullptr, 1, &barrier, 0, nullptr);
}

namespace {
constexpr VkAccessFlags shader_access =
    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT;
constexpr VkAccessFlags transfer_access = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
} // namespace

void CommandList::barrier_compute_to_compute() {
    memory_barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, shader_access);
}

void CommandList::barrier_compute_to_transfer() {
    memory_barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, transfer_access);
}

void CommandList::barrier_transfer_to_compute() {
    memory_barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, shader_access);
}

void CommandList::barrier_transfer_to_transfer() {
    memory_barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, transfer_access);
}

void CommandList::barrier_compute_to_graphics() {
    memory_barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT);
}

void CommandList::barrier_transfer_to_graphics() {
    memory_barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                       VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_INDEX_READ_BIT |
                       VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_READ_BIT);
}

void CommandList::barrier_to_host() {
    memory_barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

// --- Transfers -----------------------------------------------------------------------------------

void CommandList::copy_buffer(const Buffer& src, VkDeviceSize src_offset, const Buffer& dst,
                              VkDeviceSize dst_offset, VkDeviceSize size) {
    LANTERN_ASSERT(cmd_ && !rendering_ && src && dst,
                   "gpu: copy on a closed list, inside a rendering scope or with an empty buffer");
    LANTERN_ASSERT(size > 0 && src_offset + size <= src.size() && dst_offset + size <= dst.size(),
                   "gpu: copy range outside a buffer");
    const VkBufferCopy region{src_offset, dst_offset, size};
    vkCmdCopyBuffer(cmd_, src.vk(), dst.vk(), 1, &region);
}

void CommandList::fill_buffer(const Buffer& dst, std::uint32_t value, VkDeviceSize offset,
                              VkDeviceSize size) {
    LANTERN_ASSERT(cmd_ && !rendering_ && dst,
                   "gpu: fill on a closed list, inside a rendering scope or of an empty buffer");
    LANTERN_ASSERT(offset % 4 == 0 && offset < dst.size() &&
                       (size == VK_WHOLE_SIZE || (size % 4 == 0 && offset + size <= dst.size())),
                   "gpu: fill range misaligned or outside the buffer");
    vkCmdFillBuffer(cmd_, dst.vk(), offset, size, value);
}

void CommandList::update_buffer(const Buffer& dst, VkDeviceSize offset, std::span<const std::byte> bytes) {
    LANTERN_ASSERT(cmd_ && !rendering_ && dst,
                   "gpu: update on a closed list, inside a rendering scope or of an empty buffer");
    LANTERN_ASSERT(!bytes.empty() && bytes.size() <= max_update_bytes && bytes.size() % 4 == 0 &&
                       offset % 4 == 0 && offset + bytes.size() <= dst.size(),
                   "gpu: update_buffer needs <= 65536 bytes, 4-byte aligned, inside the buffer");
    vkCmdUpdateBuffer(cmd_, dst.vk(), offset, bytes.size(), bytes.data());
}

void CommandList::upload(const Buffer& dst, VkDeviceSize offset, std::span<const std::byte> bytes) {
    LANTERN_ASSERT(cmd_ && dst && offset + bytes.size() <= dst.size(), "gpu: upload outside the buffer");
    if (bytes.empty()) return;
    if (bytes.size() <= max_update_bytes && bytes.size() % 4 == 0 && offset % 4 == 0) {
        update_buffer(dst, offset, bytes);
        return;
    }
    // Destroyed right away: deferred destruction keeps it until this list completed.
    Buffer staging = device_->create_buffer({bytes.size(), 0, MemoryKind::upload, "upload staging"});
    std::memcpy(staging.mapped(), bytes.data(), bytes.size());
    copy_buffer(staging, 0, dst, offset, bytes.size());
}

// --- Debugging ---------------------------------------------------------------------------------

void CommandList::begin_label(const char* name) {
    LANTERN_ASSERT(cmd_ && name, "gpu: label on a closed list or without a name");
    ++label_depth_;
    if (!device_->dispatch_->cmd_begin_label) return;
    auto label = vk_struct<VkDebugUtilsLabelEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT);
    label.pLabelName = name;
    device_->dispatch_->cmd_begin_label(cmd_, &label);
}

void CommandList::end_label() {
    LANTERN_ASSERT(cmd_ && label_depth_ > 0, "gpu: end_label without begin_label");
    --label_depth_;
    if (device_->dispatch_->cmd_end_label) device_->dispatch_->cmd_end_label(cmd_);
}

void CommandList::write_timestamp(VkQueryPool pool, std::uint32_t query) {
    LANTERN_ASSERT(cmd_, "gpu: timestamp on a closed list");
    vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool, query);
}

} // namespace lantern::gpu
