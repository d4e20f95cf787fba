// Buffers and buffer views: creation, memory-type choice, move and deferred destruction.
#include "device_internal.hpp"

#include "lantern/gpu/vk_check.hpp"

#include <utility>

namespace lantern::gpu {

namespace {

// Index of the first memory type allowed by `type_bits` that has all `required` flags, or
// UINT32_MAX. Drivers list types in their order of preference, so the first match is best.
std::uint32_t find_memory_type(const VkPhysicalDeviceMemoryProperties& props,
                               std::uint32_t type_bits, VkMemoryPropertyFlags required) {
    for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i) {
        const bool allowed = (type_bits & (1u << i)) != 0;
        if (allowed && (props.memoryTypes[i].propertyFlags & required) == required) return i;
    }
    return UINT32_MAX;
}

// Bytes per texel of the formats Lantern views buffers as (0 = not supported here).
VkDeviceSize texel_size(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8_UINT:
    case VK_FORMAT_R8_SNORM:
    case VK_FORMAT_R8_SINT: return 1;
    case VK_FORMAT_R8G8_UNORM:
    case VK_FORMAT_R8G8_UINT:
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16_UINT:
    case VK_FORMAT_R16_UNORM: return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_UINT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R16G16_UINT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SINT: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_UINT:
    case VK_FORMAT_R16G16B16A16_UNORM:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32_UINT:
    case VK_FORMAT_R32G32_SINT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT:
    case VK_FORMAT_R32G32B32A32_SINT: return 16;
    default: return 0;
    }
}

} // namespace

namespace detail {

// device_local: DEVICE_LOCAL, else anything (integrated GPUs, lavapipe: all types qualify).
// upload: HOST_VISIBLE | HOST_COHERENT (no flushes needed).
// readback: as upload, preferring HOST_CACHED (CPU reads of uncached memory are very slow).
std::uint32_t choose_memory_type(const VkPhysicalDeviceMemoryProperties& props,
                                 std::uint32_t type_bits, MemoryKind kind) {
    constexpr VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                           VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    switch (kind) {
    case MemoryKind::device_local: {
        const std::uint32_t local =
            find_memory_type(props, type_bits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        return local != UINT32_MAX ? local : find_memory_type(props, type_bits, 0);
    }
    case MemoryKind::upload:
        return find_memory_type(props, type_bits, host);
    case MemoryKind::readback: {
        const std::uint32_t cached =
            find_memory_type(props, type_bits, host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        return cached != UINT32_MAX ? cached : find_memory_type(props, type_bits, host);
    }
    }
    return UINT32_MAX;
}

} // namespace detail

const char* to_string(MemoryKind kind) {
    switch (kind) {
    case MemoryKind::device_local: return "device_local";
    case MemoryKind::upload: return "upload";
    case MemoryKind::readback: return "readback";
    }
    return "?";
}

Buffer Device::create_buffer(const BufferDesc& desc) {
    LANTERN_ASSERT(desc.size > 0, "gpu::Device::create_buffer of size 0");
    Buffer b;
    b.device_ = this;
    b.size_ = desc.size;
    b.usage_ = desc.usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    b.memory_ = desc.memory;

    auto info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = desc.size;
    info.usage = b.usage_;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &b.buffer_));

    VkMemoryRequirements requirements{};
    vkGetBufferMemoryRequirements(device_, b.buffer_, &requirements);
    const std::uint32_t type =
        detail::choose_memory_type(memory_properties_, requirements.memoryTypeBits, desc.memory);
    LANTERN_VERIFY(type != UINT32_MAX, "gpu: the device has no memory type for this buffer kind");
    auto alloc = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = requirements.size;
    alloc.memoryTypeIndex = type;
    VK_CHECK(vkAllocateMemory(device_, &alloc, nullptr, &b.memory_object_));
    count_memory(b.memory_object_, alloc.allocationSize);
    VK_CHECK(vkBindBufferMemory(device_, b.buffer_, b.memory_object_, 0));
    if (desc.memory != MemoryKind::device_local) {
        void* mapped = nullptr;
        VK_CHECK(vkMapMemory(device_, b.memory_object_, 0, VK_WHOLE_SIZE, 0, &mapped));
        b.mapped_ = static_cast<std::byte*>(mapped);
    }
    set_object_name(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<std::uint64_t>(b.buffer_), desc.name);
    set_object_name(VK_OBJECT_TYPE_DEVICE_MEMORY, reinterpret_cast<std::uint64_t>(b.memory_object_),
                    desc.name);
    std::lock_guard lock(deletions_->mutex);
    ++deletions_->live_objects;
    return b;
}

BufferView Device::create_buffer_view(const Buffer& buffer, VkFormat format, VkDeviceSize offset,
                                      VkDeviceSize range, const char* name) {
    LANTERN_ASSERT(buffer && buffer.device() == this, "gpu: view of an empty or foreign buffer");
    LANTERN_ASSERT(buffer.usage() & (VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
                                     VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT),
                   "gpu: buffer view needs UNIFORM_TEXEL_BUFFER or STORAGE_TEXEL_BUFFER usage");
    const VkDeviceSize texel = texel_size(format);
    LANTERN_ASSERT(texel > 0, "gpu: buffer view format not in texel_size()");
    LANTERN_ASSERT(offset < buffer.size() && offset % caps_.min_texel_buffer_offset_alignment == 0,
                   "gpu: buffer view offset out of range or misaligned");
    if (range == VK_WHOLE_SIZE) range = (buffer.size() - offset) / texel * texel;
    LANTERN_ASSERT(range > 0 && range % texel == 0 && offset + range <= buffer.size(),
                   "gpu: buffer view range must be whole texels inside the buffer");
    LANTERN_ASSERT(range / texel <= caps_.max_texel_buffer_elements,
                   "gpu: buffer view larger than maxTexelBufferElements");

    BufferView v;
    v.device_ = this;
    v.format_ = format;
    v.offset_ = offset;
    v.range_ = range;
    v.buffer_usage_ = buffer.usage();
    auto info = vk_struct<VkBufferViewCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO);
    info.buffer = buffer.vk();
    info.format = format;
    info.offset = offset;
    info.range = range;
    VK_CHECK(vkCreateBufferView(device_, &info, nullptr, &v.view_));
    set_object_name(VK_OBJECT_TYPE_BUFFER_VIEW, reinterpret_cast<std::uint64_t>(v.view_), name);
    std::lock_guard lock(deletions_->mutex);
    ++deletions_->live_objects;
    return v;
}

// --- Buffer --------------------------------------------------------------------------------

void Buffer::retire(BufferFields& f) {
    Device::Retired retired;
    retired.buffer = f.buffer_;
    retired.memory = f.memory_object_;
    f.device_->retire(retired);
}

// --- BufferView ----------------------------------------------------------------------------

void BufferView::retire(BufferViewFields& f) {
    Device::Retired retired;
    retired.view = f.view_;
    f.device_->retire(retired);
}

} // namespace lantern::gpu
