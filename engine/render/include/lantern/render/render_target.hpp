// The offscreen target a frame is drawn into at the game's internal resolution (pixel art:
// 480x270 by default), colour + depth, with dynamic rendering. Windowed, it is then shown
// with record_upscale (upscale.hpp); headless, it is read back (screenshots, tests).
//
//   RenderTarget target = RenderTarget::create(device);            // 480x270 RGBA8 sRGB + D32
//   target.begin(cmd, {{0.1f, 0.1f, 0.2f, 1.0f}});                 // cleared colour and depth
//   cmd.bind(pipeline); ... draws ...                               // pipelines made with
//   target.end(cmd);                                                // target.color_format() etc.
//   record_upscale(cmd, target.color(), frame.image(), rect, ...);  // or, headless after submit:
//   write_png("shot.png", target.read_back());
//
// Layouts: between frames the colour image rests in TRANSFER_SRC_OPTIMAL (what the upscale
// blit and the read-back want); begin() discards the previous contents (every frame redraws
// the whole target), so the target needs no first-frame initialisation.
//
// Ownership: the images are gpu::Image handles (deferred destruction); the RenderTarget is
// move-only and must be destroyed before its Device. Threads: the recording thread.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gpu/image.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace lantern::gpu {
class CommandList;
class Device;
} // namespace lantern::gpu

namespace lantern::render {

// 8-bit RGBA pixels, rows top to bottom (a read-back target, a captured window).
struct Rgba8Image {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::uint8_t> pixels; // width * height * 4 bytes: r, g, b, a
    // The pixel at (x, y) as 0xAABBGGRR (little-endian RGBA bytes read as one word).
    std::uint32_t at(std::uint32_t x, std::uint32_t y) const;
};

// Writes `image` as an RGBA PNG (atomically, see write_png in core).
Result<void> write_png(const std::string& path, const Rgba8Image& image);

struct RenderTargetDesc {
    std::uint32_t width = 480;
    std::uint32_t height = 270;
    // RGBA8 or BGRA8, UNORM or SRGB. Match the swapchain's encoding (SRGB with SRGB) so the
    // upscale blit copies values unchanged.
    VkFormat color_format = VK_FORMAT_R8G8B8A8_SRGB;
    VkFormat depth_format = VK_FORMAT_D32_SFLOAT; // VK_FORMAT_UNDEFINED: no depth buffer
    const char* name = "render target";
};

class RenderTarget {
  public:
    // The formats must be supported as attachments (asserted; D32_SFLOAT and RGBA8 are
    // universal). The colour image can also be a blit source and be sampled.
    static RenderTarget create(gpu::Device& device, const RenderTargetDesc& desc = {});
    RenderTarget() = default;

    // Starts a rendering scope over the whole target: colour cleared to `clear`, depth to 1.0.
    void begin(gpu::CommandList& cmd, const VkClearColorValue& clear = {{0.0f, 0.0f, 0.0f, 1.0f}});
    // Ends it; the colour image is left in TRANSFER_SRC_OPTIMAL.
    void end(gpu::CommandList& cmd);

    // Blocking: the colour image after the submitted frames (at least one), as RGBA8 (BGRA
    // swizzled). For screenshots, headless reports and tests, not per frame.
    Rgba8Image read_back();

    const gpu::Image& color() const { return color_; }
    const gpu::Image& depth() const { return depth_; } // empty without a depth format
    VkFormat color_format() const { return color_.format(); }
    VkFormat depth_format() const { return depth_ ? depth_.format() : VK_FORMAT_UNDEFINED; }
    VkExtent2D extent() const { return color_.extent(); }

  private:
    gpu::Image color_;
    gpu::Image depth_;
    bool recording_ = false; // between begin and end
    bool rendered_ = false;  // end() was recorded at least once: the colour image has content
};

} // namespace lantern::render
