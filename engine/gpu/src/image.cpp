// Images, samplers, image uploads and read-backs.
#include "device_internal.hpp"

#include "lantern/gpu/vk_check.hpp"

#include <cstring>
#include <utility>

namespace lantern::gpu {

namespace {

// The optimal-tiling format features each usage needs.
VkFormatFeatureFlags required_features(VkImageUsageFlags usage) {
    VkFormatFeatureFlags features = 0;
    if (usage & VK_IMAGE_USAGE_SAMPLED_BIT) features |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    if (usage & VK_IMAGE_USAGE_STORAGE_BIT) features |= VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
    if (usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT)
        features |= VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT;
    if (usage & VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT)
        features |= VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT;
    if (usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) features |= VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if (usage & VK_IMAGE_USAGE_TRANSFER_DST_BIT) features |= VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    return features;
}

VkImageView create_view(VkDevice device, VkImage image, VkFormat format) {
    auto info = vk_struct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    info.image = image;
    info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    info.format = format;
    info.subresourceRange = {format_aspects(format), 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImageView(device, &info, nullptr, &view));
    return view;
}

} // namespace

bool is_depth_format(VkFormat format) {
    switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
        return true;
    default:
        return false;
    }
}

VkImageAspectFlags format_aspects(VkFormat format) {
    switch (format) {
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
        return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default:
        return is_depth_format(format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

std::uint32_t image_texel_size(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8_UINT:
        return 1;
    case VK_FORMAT_R8G8_UNORM:
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D16_UNORM_S8_UINT:
        return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R8G8B8A8_UINT:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D24_UNORM_S8_UINT: // the depth aspect copies as 32-bit words
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
        return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
        return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
        return 16;
    default:
        return 0;
    }
}

// --- Creation ----------------------------------------------------------------------------------

bool Device::supports_image_format(VkFormat format, VkFormatFeatureFlags features) const {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(physical_, format, &props);
    return (props.optimalTilingFeatures & features) == features;
}

Image Device::create_image(const ImageDesc& desc) {
    LANTERN_ASSERT(desc.width > 0 && desc.height > 0, "gpu::Device::create_image of size 0");
    const VkImageUsageFlags usage =
        desc.usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    LANTERN_ASSERT(supports_image_format(desc.format, required_features(usage)),
                   "gpu::Device::create_image: the format does not support this usage");
    Image img;
    img.device_ = this;
    img.format_ = desc.format;
    img.extent_ = {desc.width, desc.height};
    img.usage_ = usage;
    img.aspect_ = format_aspects(desc.format);

    auto info = vk_struct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = {desc.width, desc.height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VK_CHECK(vkCreateImage(device_, &info, nullptr, &img.image_));

    VkMemoryRequirements requirements{};
    vkGetImageMemoryRequirements(device_, img.image_, &requirements);
    const std::uint32_t type = detail::choose_memory_type(
        memory_properties_, requirements.memoryTypeBits, MemoryKind::device_local);
    LANTERN_VERIFY(type != UINT32_MAX, "gpu: the device has no memory type for this image");
    auto alloc = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = requirements.size;
    alloc.memoryTypeIndex = type;
    VK_CHECK(vkAllocateMemory(device_, &alloc, nullptr, &img.memory_));
    count_memory(img.memory_, alloc.allocationSize);
    VK_CHECK(vkBindImageMemory(device_, img.image_, img.memory_, 0));
    img.view_ = create_view(device_, img.image_, desc.format);

    set_object_name(VK_OBJECT_TYPE_IMAGE, reinterpret_cast<std::uint64_t>(img.image_), desc.name);
    set_object_name(VK_OBJECT_TYPE_IMAGE_VIEW, reinterpret_cast<std::uint64_t>(img.view_),
                    desc.name);
    count_live_object();
    return img;
}

Image Device::wrap_image(VkImage image, const ImageDesc& desc) {
    LANTERN_ASSERT(image && desc.width > 0 && desc.height > 0,
                   "gpu::Device::wrap_image of nothing");
    Image img;
    img.device_ = this;
    img.image_ = image;
    img.format_ = desc.format;
    img.extent_ = {desc.width, desc.height};
    img.usage_ = desc.usage;
    img.aspect_ = format_aspects(desc.format);
    img.view_ = create_view(device_, image, desc.format);
    set_object_name(VK_OBJECT_TYPE_IMAGE_VIEW, reinterpret_cast<std::uint64_t>(img.view_),
                    desc.name);
    count_live_object();
    return img;
}

Sampler Device::create_sampler(const SamplerDesc& desc) {
    auto info = vk_struct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
    info.magFilter = desc.filter;
    info.minFilter = desc.filter;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = desc.address;
    info.addressModeV = desc.address;
    info.addressModeW = desc.address;
    info.maxLod = 0.0f; // images have one mip level
    info.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    Sampler s;
    s.device_ = this;
    VK_CHECK(vkCreateSampler(device_, &info, nullptr, &s.sampler_));
    set_object_name(VK_OBJECT_TYPE_SAMPLER, reinterpret_cast<std::uint64_t>(s.sampler_), desc.name);
    count_live_object();
    return s;
}

// --- Transfers -----------------------------------------------------------------------------------

std::uint64_t Device::upload(const Image& dst, std::span<const std::byte> texels,
                             VkImageLayout final_layout) {
    LANTERN_ASSERT(dst && dst.device() == this && !is_depth_format(dst.format()),
                   "gpu::Device::upload needs a colour image of this device");
    const VkDeviceSize size =
        VkDeviceSize{dst.width()} * dst.height() * image_texel_size(dst.format());
    LANTERN_ASSERT(size > 0 && texels.size() == size,
                   "gpu::Device::upload: texels are not the whole image");
    Buffer staging = create_buffer({size, 0, MemoryKind::upload, "Device::upload staging"});
    std::memcpy(staging.mapped(), texels.data(), size);
    CommandList cmd = begin("Device::upload image");
    // UNDEFINED: the old contents go; the transition waits for every earlier use of the image.
    cmd.transition(dst, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    cmd.copy_buffer_to_image(staging, 0, dst);
    cmd.transition(dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, final_layout);
    return submit(std::move(cmd));
}

std::vector<std::byte> Device::read_back(const Image& src, VkImageLayout layout) {
    LANTERN_ASSERT(src && src.device() == this,
                   "gpu::Device::read_back of an empty or foreign image");
    const VkDeviceSize size =
        VkDeviceSize{src.width()} * src.height() * image_texel_size(src.format());
    LANTERN_ASSERT(size > 0, "gpu::Device::read_back: image format not in image_texel_size()");
    Buffer staging = create_buffer({size, 0, MemoryKind::readback, "Device::read_back staging"});
    CommandList cmd = begin("Device::read_back image");
    // Every earlier write (any stage, any submission) -> the copy.
    cmd.memory_barrier(VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    cmd.transition(src, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    cmd.copy_image_to_buffer(src, staging, 0);
    cmd.transition(src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
    cmd.barrier_to_host();
    wait(submit(std::move(cmd)));
    std::vector<std::byte> out(size);
    std::memcpy(out.data(), staging.mapped(), size);
    return out;
}

// --- Handles -------------------------------------------------------------------------------------

void Image::retire(ImageFields& f) {
    Device::Retired retired;
    retired.image_view = f.view_;
    // A wrapped image has no memory of ours and is not ours to destroy.
    if (f.memory_) retired.image = f.image_;
    retired.memory = f.memory_;
    f.device_->retire(retired);
}

void Sampler::retire(SamplerFields& f) {
    Device::Retired retired;
    retired.sampler = f.sampler_;
    f.device_->retire(retired);
}

} // namespace lantern::gpu
