// GPU images (with their view) and samplers: move-only handles created by a Device.
//
// An Image is 2D, one mip level, one array layer, optimally tiled, in device-local memory,
// with one VkImageView of the whole image (colour aspect, or depth [+ stencil] for depth
// formats). Device::wrap_image makes an Image of a VkImage created elsewhere (swapchain
// images): that Image owns only its view.
//
// Layouts are not tracked. A new image is in VK_IMAGE_LAYOUT_UNDEFINED; every command that
// uses one is told the layout it is in (CommandList::transition, copies, blits, descriptor
// writes), just as buffer barriers name their stages. Keeping one "resting" layout per image
// between uses (e.g. SHADER_READ_ONLY_OPTIMAL for textures) keeps this simple.
//
// Ownership: like Buffer. Destroying (reset, move-assigning over) an Image or Sampler queues
// it on the Device, which frees it once every submission that may use it completed; every
// handle must be destroyed before its Device.
// Threads: a handle is used by one thread at a time; it may be destroyed on any thread.
#pragma once

#include "lantern/gpu/owning_handle.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>

namespace lantern::gpu {

class Device;

struct ImageDesc {
    std::uint32_t width = 0;  // texels, > 0
    std::uint32_t height = 0; // texels, > 0
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    // SAMPLED, COLOR_ATTACHMENT, DEPTH_STENCIL_ATTACHMENT, STORAGE... TRANSFER_SRC and
    // TRANSFER_DST are always added to created images (upload, read-back, blits, clears);
    // for wrapped images this is the usage the image was created with.
    VkImageUsageFlags usage = 0;
    const char* name = nullptr; // debug name for validation messages and GPU debuggers
};

struct ImageFields {
    Device* device_ = nullptr;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE; // VK_NULL_HANDLE for wrapped images
    VkImageView view_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{};
    VkImageUsageFlags usage_ = 0;
    VkImageAspectFlags aspect_ = 0;
};

// Move-only; reset() (or destruction) queues the image (or, for a wrapped image, its view)
// for deferred destruction.
class Image : public OwningHandle<Image, ImageFields> {
  public:
    explicit operator bool() const { return view_ != VK_NULL_HANDLE; }
    VkImage vk() const { return image_; }
    VkImageView view() const { return view_; }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    std::uint32_t width() const { return extent_.width; }
    std::uint32_t height() const { return extent_.height; }
    VkImageUsageFlags usage() const { return usage_; }
    // Every aspect of the format (COLOR, or DEPTH [| STENCIL]): barriers use all of them.
    VkImageAspectFlags aspect() const { return aspect_; }
    Device* device() const { return device_; }

  private:
    friend class Device;
    friend class OwningHandle<Image, ImageFields>;
    static void retire(ImageFields& f);
};

struct SamplerDesc {
    // Lantern's pixel art and GI textures are point sampled and clamped: the defaults.
    VkFilter filter = VK_FILTER_NEAREST;
    VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    const char* name = nullptr;
};

struct SamplerFields {
    Device* device_ = nullptr;
    VkSampler sampler_ = VK_NULL_HANDLE;
};

class Sampler : public OwningHandle<Sampler, SamplerFields> {
  public:
    explicit operator bool() const { return sampler_ != VK_NULL_HANDLE; }
    VkSampler vk() const { return sampler_; }

  private:
    friend class Device;
    friend class OwningHandle<Sampler, SamplerFields>;
    static void retire(SamplerFields& f);
};

// True for formats with a depth component (D16, D32, D24S8, ...).
bool is_depth_format(VkFormat format);
// The aspects of `format`: COLOR, DEPTH, or DEPTH | STENCIL.
VkImageAspectFlags format_aspects(VkFormat format);
// Bytes per texel that a copy of the image (its depth aspect, for depth formats) to a
// buffer writes: 4 for RGBA8/BGRA8/R32/D32/D24S8, 8 for RGBA16F, ...; 0 for formats images
// do not support here.
std::uint32_t image_texel_size(VkFormat format);

} // namespace lantern::gpu
