// Pixel-art presentation: the low-resolution render target shown in a larger image
// (swapchain image, screenshot) at the largest whole-number scale that fits, centred, with
// black bars around it, every source pixel an exact square of scale x scale pixels.
//
//   PresentRect r = fit_integer_scale({480, 270}, {1280, 720}); // scale 2, at (160, 90), 960x540
//   record_upscale(cmd, target.color(), frame.image(), r, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
//
// When the destination is smaller than the source (a tiny window) there is no whole-number
// scale: the image is shrunk to fit (aspect kept, nearest filtering drops pixels) and scale
// is 0. The functions here are pure except record_upscale.
#pragma once

#include "lantern/platform/window.hpp"

#include <glm/vec2.hpp>

#include <cstdint>
#include <optional>

#include <vulkan/vulkan.h>

namespace lantern::gpu {
class CommandList;
class Image;
} // namespace lantern::gpu

namespace lantern::render {

// Where the scaled source lands in the destination, in destination pixels.
struct PresentRect {
    std::int32_t x = 0; // left edge (the left bar's width)
    std::int32_t y = 0; // top edge (the top bar's height)
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t scale = 0; // whole-number factor; 0 = shrunk to fit (destination too small)
    bool empty() const { return width == 0 || height == 0; }
    friend bool operator==(const PresentRect&, const PresentRect&) = default;
};

// The largest whole-number scale of `source` that fits in `destination`, centred (odd
// leftovers put the extra pixel on the right/bottom bar). Empty when either is empty.
PresentRect fit_integer_scale(platform::Extent source, platform::Extent destination);

// The source size that fills `destination` at a whole-number scale near the design's, for a
// game whose pixel-art resolution follows its window (fit_integer_scale of a fixed 480x270
// leaves 44 % of a 1280x720 window bars). The scale is the smaller of the two axes' ratios
// destination / design rounded to the nearest whole number (at least 1), so pixels stay
// about the design's size on screen; the source is destination / scale rounded down, so
// the bars fit_integer_scale then leaves are narrower than the scale. Each axis is clamped to
// [1, 4 x the design's] (an extreme window shape gets bars rather than a huge source).
//
//   fill_integer_scale({480, 270}, {1280, 720});  // {426, 240}: scale 3, bars of 1 and 0 px
//   fill_integer_scale({480, 270}, {1920, 1080}); // {480, 270}: scale 4
// Empty when either is empty.
platform::Extent fill_integer_scale(platform::Extent design, platform::Extent destination);
// As fill_integer_scale, at a scale the player chose (>= 1): destination / scale rounded
// down, each axis clamped to [1, 4 x the design's].
platform::Extent fill_at_scale(platform::Extent design, platform::Extent destination, std::uint32_t scale);

// The source pixel position under destination pixel position `p` (e.g. the mouse), or
// nullopt when p is on a bar. Positions are continuous: pixel (i, j) covers [i, i+1).
std::optional<glm::vec2> destination_to_source(const PresentRect& rect, platform::Extent source,
                                               glm::vec2 p);

// Records the presentation of `source` (colour, TRANSFER_SRC_OPTIMAL, left so) into
// `destination` (old contents discarded: any layout; TRANSFER_DST usage, BLIT_DST format
// feature): clear to black, nearest-filter blit into `rect`, then a transition to
// `final_layout` (PRESENT_SRC_KHR for a swapchain image, COLOR_ATTACHMENT_OPTIMAL to draw
// an overlay on top). Nothing but the clear happens for an empty rect.
void record_upscale(gpu::CommandList& cmd, const gpu::Image& source, const gpu::Image& destination,
                    const PresentRect& rect, VkImageLayout final_layout);

} // namespace lantern::render
