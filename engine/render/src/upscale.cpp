// Whole-number upscaling with letterboxing, and its recording (clear + nearest blit).
#include "lantern/render/upscale.hpp"

#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/image.hpp"

#include <algorithm>
#include <cmath>

namespace lantern::render {

namespace {

// The aspect-kept shrink of `source` into a smaller `destination` (at least 1x1).
platform::Extent shrink_to_fit(platform::Extent source, platform::Extent destination) {
    const std::uint64_t sw = source.width, sh = source.height;
    const std::uint64_t dw = destination.width, dh = destination.height;
    if (dw * sh <= dh * sw) // width-limited
        return {destination.width,
                static_cast<std::uint32_t>(std::max<std::uint64_t>(1, sh * dw / sw))};
    return {static_cast<std::uint32_t>(std::max<std::uint64_t>(1, sw * dh / sh)),
            destination.height};
}

} // namespace

PresentRect fit_integer_scale(platform::Extent source, platform::Extent destination) {
    if (source.empty() || destination.empty()) return {};
    const std::uint32_t scale =
        std::min(destination.width / source.width, destination.height / source.height);
    const platform::Extent size =
        scale > 0 ? platform::Extent{source.width * scale, source.height * scale}
                  : shrink_to_fit(source, destination);
    PresentRect rect;
    rect.x = static_cast<std::int32_t>((destination.width - size.width) / 2);
    rect.y = static_cast<std::int32_t>((destination.height - size.height) / 2);
    rect.width = size.width;
    rect.height = size.height;
    rect.scale = scale;
    return rect;
}

platform::Extent fill_integer_scale(platform::Extent design, platform::Extent destination) {
    if (design.empty() || destination.empty()) return {};
    const double ratio = std::min(double(destination.width) / double(design.width),
                                  double(destination.height) / double(design.height));
    return fill_at_scale(design, destination, static_cast<std::uint32_t>(std::max(1.0, std::floor(ratio + 0.5))));
}

platform::Extent fill_at_scale(platform::Extent design, platform::Extent destination, std::uint32_t scale) {
    if (design.empty() || destination.empty()) return {};
    scale = std::max(scale, 1u);
    const auto axis = [scale](std::uint32_t dest, std::uint32_t des) {
        const std::uint64_t limit = std::uint64_t(des) * 4;
        return static_cast<std::uint32_t>(std::clamp<std::uint64_t>(dest / scale, 1, limit));
    };
    return {axis(destination.width, design.width), axis(destination.height, design.height)};
}

std::optional<glm::vec2> destination_to_source(const PresentRect& rect, platform::Extent source,
                                               glm::vec2 p) {
    if (rect.empty()) return std::nullopt;
    const glm::vec2 local = p - glm::vec2(rect.x, rect.y);
    if (local.x < 0.0f || local.y < 0.0f || local.x >= float(rect.width) ||
        local.y >= float(rect.height))
        return std::nullopt;
    return glm::vec2(local.x * float(source.width) / float(rect.width),
                     local.y * float(source.height) / float(rect.height));
}

void record_upscale(gpu::CommandList& cmd, const gpu::Image& source, const gpu::Image& destination,
                    const PresentRect& rect, VkImageLayout final_layout) {
    cmd.transition(destination, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    cmd.clear_color(destination, VkClearColorValue{{0.0f, 0.0f, 0.0f, 1.0f}});
    if (!rect.empty()) {
        // The blit overwrites part of the clear: order the two writes.
        cmd.transition(destination, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        cmd.blit(source, {{0, 0}, source.extent()}, destination,
                 {{rect.x, rect.y}, {rect.width, rect.height}}, VK_FILTER_NEAREST);
    }
    cmd.transition(destination, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, final_layout);
}

} // namespace lantern::render
