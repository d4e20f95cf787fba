// RenderTarget: colour + depth images, the rendering scope around a frame, read-back.
#include "lantern/render/render_target.hpp"

#include "lantern/core/png.hpp"
#include "lantern/gpu/device.hpp"

#include <cstring>
#include <utility>

namespace lantern::render {

namespace {

bool is_bgra(VkFormat format) {
    return format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB;
}

bool is_rgba8_or_bgra8(VkFormat format) {
    return is_bgra(format) || format == VK_FORMAT_R8G8B8A8_UNORM ||
           format == VK_FORMAT_R8G8B8A8_SRGB;
}

} // namespace

std::uint32_t Rgba8Image::at(std::uint32_t x, std::uint32_t y) const {
    LANTERN_ASSERT(x < width && y < height, "render::Rgba8Image::at outside the image");
    std::uint32_t value = 0;
    std::memcpy(&value, pixels.data() + (std::size_t{y} * width + x) * 4, 4);
    return value;
}

Result<void> write_png(const std::string& path, const Rgba8Image& image) {
    return lantern::write_png(path, static_cast<int>(image.width), static_cast<int>(image.height),
                              4, image.pixels);
}

RenderTarget RenderTarget::create(gpu::Device& device, const RenderTargetDesc& desc) {
    LANTERN_ASSERT(is_rgba8_or_bgra8(desc.color_format),
                   "render::RenderTarget: colour format not RGBA8/BGRA8");
    RenderTarget target;
    target.color_ = device.create_image(
        {desc.width, desc.height, desc.color_format,
         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, desc.name});
    if (desc.depth_format != VK_FORMAT_UNDEFINED)
        target.depth_ =
            device.create_image({desc.width, desc.height, desc.depth_format,
                                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, desc.name});
    return target;
}

void RenderTarget::begin(gpu::CommandList& cmd, const VkClearColorValue& clear) {
    LANTERN_ASSERT(color_ && !recording_,
                   "render::RenderTarget::begin twice or on an empty target");
    cmd.transition(color_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    if (depth_)
        cmd.transition(depth_, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    cmd.begin_rendering({&color_, VK_ATTACHMENT_LOAD_OP_CLEAR, clear},
                        {depth_ ? &depth_ : nullptr, VK_ATTACHMENT_LOAD_OP_CLEAR, 1.0f, false});
    recording_ = true;
}

void RenderTarget::end(gpu::CommandList& cmd) {
    LANTERN_ASSERT(recording_, "render::RenderTarget::end without begin");
    cmd.end_rendering();
    cmd.transition(color_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    recording_ = false;
    rendered_ = true;
}

Rgba8Image RenderTarget::read_back() {
    LANTERN_ASSERT(rendered_ && !recording_,
                   "render::RenderTarget::read_back before a frame or inside begin/end");
    Rgba8Image image;
    image.width = color_.width();
    image.height = color_.height();
    const std::vector<std::byte> bytes =
        color_.device()->read_back(color_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    image.pixels.resize(bytes.size());
    std::memcpy(image.pixels.data(), bytes.data(), bytes.size());
    if (is_bgra(color_.format())) {
        for (std::size_t i = 0; i < image.pixels.size(); i += 4)
            std::swap(image.pixels[i], image.pixels[i + 2]);
    }
    return image;
}

} // namespace lantern::render
