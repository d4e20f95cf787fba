// CommandList image commands (layout transitions, copies, clears, blits) and raster
// commands (dynamic rendering, graphics pipelines, draws).
#include "device_internal.hpp"

#include "lantern/gpu/vk_check.hpp"

#include <array>

namespace lantern::gpu {

namespace {

// What a layout implies about the accesses around it: the stages that use an image in it,
// the writes a barrier out of it must make available, the accesses a barrier into it must
// make them visible to.
struct LayoutUse {
    VkPipelineStageFlags stages = 0;
    VkAccessFlags writes = 0;
    VkAccessFlags accesses = 0;
};

LayoutUse layout_use(VkImageLayout layout) {
    switch (layout) {
    // Contents discarded: nothing to make available, but the transition must still wait for
    // every earlier use (write-after-read on the image, and swapchain acquire semaphores
    // waited at any stage), hence ALL_COMMANDS.
    case VK_IMAGE_LAYOUT_UNDEFINED:
        return {VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0};
    case VK_IMAGE_LAYOUT_GENERAL:
        return {VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT};
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL:
        return {VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_ACCESS_TRANSFER_READ_BIT};
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL:
        return {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_ACCESS_TRANSFER_WRITE_BIT};
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL:
        return {VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT};
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL:
        return {VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                    VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
        return {VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                VK_ACCESS_SHADER_READ_BIT};
    // The presentation engine synchronises through the present semaphore; the barrier only
    // has to come last.
    case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR:
        return {VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0};
    default:
        LANTERN_ASSERT(false, "gpu::CommandList::transition: unhandled image layout");
        return {};
    }
}

VkImageSubresourceLayers copy_layers(const Image& image) {
    const VkImageAspectFlags aspect =
        is_depth_format(image.format()) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    return {aspect, 0, 0, 1};
}

bool inside(const VkRect2D& rect, VkExtent2D extent) {
    return rect.offset.x >= 0 && rect.offset.y >= 0 &&
           std::uint64_t(rect.offset.x) + rect.extent.width <= extent.width &&
           std::uint64_t(rect.offset.y) + rect.extent.height <= extent.height;
}

std::array<VkOffset3D, 2> corners(const VkRect2D& rect) {
    return {VkOffset3D{rect.offset.x, rect.offset.y, 0},
            VkOffset3D{rect.offset.x + static_cast<std::int32_t>(rect.extent.width),
                       rect.offset.y + static_cast<std::int32_t>(rect.extent.height), 1}};
}

} // namespace

// --- Images
// ---------------------------------------------------------------------------------------

void CommandList::transition(const Image& image, VkImageLayout from, VkImageLayout to) {
    LANTERN_ASSERT(
        cmd_ && !rendering_ && image,
        "gpu: transition on a closed list, inside a rendering scope or of an empty image");
    LANTERN_ASSERT(to != VK_IMAGE_LAYOUT_UNDEFINED, "gpu: transition to UNDEFINED");
    const LayoutUse src = layout_use(from);
    const LayoutUse dst = layout_use(to);
    auto barrier = vk_struct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    barrier.srcAccessMask = src.writes;
    barrier.dstAccessMask = dst.accesses;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image.vk();
    barrier.subresourceRange = {image.aspect(), 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd_, src.stages, dst.stages, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

void CommandList::copy_buffer_to_image(const Buffer& src, VkDeviceSize src_offset,
                                       const Image& dst) {
    LANTERN_ASSERT(
        cmd_ && !rendering_ && src && dst,
        "gpu: copy on a closed list, inside a rendering scope or with an empty resource");
    LANTERN_ASSERT(!is_depth_format(dst.format()), "gpu: copy_buffer_to_image into a depth image");
    const VkDeviceSize size =
        VkDeviceSize{dst.width()} * dst.height() * image_texel_size(dst.format());
    LANTERN_ASSERT(size > 0 && src_offset + size <= src.size(),
                   "gpu: copy_buffer_to_image reads outside the buffer");
    VkBufferImageCopy region{};
    region.bufferOffset = src_offset;
    region.imageSubresource = copy_layers(dst);
    region.imageExtent = {dst.width(), dst.height(), 1};
    vkCmdCopyBufferToImage(cmd_, src.vk(), dst.vk(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
}

void CommandList::copy_image_to_buffer(const Image& src, const Buffer& dst,
                                       VkDeviceSize dst_offset) {
    LANTERN_ASSERT(
        cmd_ && !rendering_ && src && dst,
        "gpu: copy on a closed list, inside a rendering scope or with an empty resource");
    const VkDeviceSize size =
        VkDeviceSize{src.width()} * src.height() * image_texel_size(src.format());
    LANTERN_ASSERT(size > 0 && dst_offset + size <= dst.size(),
                   "gpu: copy_image_to_buffer writes outside the buffer");
    VkBufferImageCopy region{};
    region.bufferOffset = dst_offset;
    region.imageSubresource = copy_layers(src);
    region.imageExtent = {src.width(), src.height(), 1};
    vkCmdCopyImageToBuffer(cmd_, src.vk(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.vk(), 1,
                           &region);
}

void CommandList::clear_color(const Image& image, const VkClearColorValue& color) {
    LANTERN_ASSERT(
        cmd_ && !rendering_ && image && !is_depth_format(image.format()),
        "gpu: clear_color on a closed list, inside a rendering scope or of a non-colour image");
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd_, image.vk(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &color, 1, &range);
}

void CommandList::blit(const Image& src, const VkRect2D& src_rect, const Image& dst,
                       const VkRect2D& dst_rect, VkFilter filter) {
    LANTERN_ASSERT(cmd_ && !rendering_ && src && dst,
                   "gpu: blit on a closed list, inside a rendering scope or of an empty image");
    LANTERN_ASSERT(inside(src_rect, src.extent()) && inside(dst_rect, dst.extent()),
                   "gpu: blit rectangle outside its image");
    VkImageBlit region{};
    region.srcSubresource = copy_layers(src);
    region.dstSubresource = copy_layers(dst);
    const auto src_corners = corners(src_rect);
    const auto dst_corners = corners(dst_rect);
    region.srcOffsets[0] = src_corners[0];
    region.srcOffsets[1] = src_corners[1];
    region.dstOffsets[0] = dst_corners[0];
    region.dstOffsets[1] = dst_corners[1];
    vkCmdBlitImage(cmd_, src.vk(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.vk(),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, filter);
}

// --- Raster
// ---------------------------------------------------------------------------------------

void CommandList::begin_rendering(const ColorAttachment& color, const DepthAttachment& depth) {
    LANTERN_ASSERT(cmd_ && !rendering_,
                   "gpu: begin_rendering on a closed list or inside a rendering scope");
    LANTERN_ASSERT(device_->caps_.graphics, "gpu: begin_rendering needs DeviceOptions::graphics");
    LANTERN_ASSERT(color.image && *color.image, "gpu: begin_rendering without a colour image");
    const VkExtent2D extent = color.image->extent();
    LANTERN_ASSERT(
        !depth.image ||
            (depth.image->width() == extent.width && depth.image->height() == extent.height &&
             is_depth_format(depth.image->format())),
        "gpu: the depth attachment is not a depth image of the colour attachment's size");

    auto color_info =
        vk_struct<VkRenderingAttachmentInfoKHR>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO_KHR);
    color_info.imageView = color.image->view();
    color_info.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color_info.loadOp = color.load;
    color_info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color_info.clearValue.color = color.clear;
    auto depth_info =
        vk_struct<VkRenderingAttachmentInfoKHR>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO_KHR);
    if (depth.image) {
        depth_info.imageView = depth.image->view();
        depth_info.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        depth_info.loadOp = depth.load;
        depth_info.storeOp =
            depth.store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
        depth_info.clearValue.depthStencil = {depth.clear, 0};
    }
    auto info = vk_struct<VkRenderingInfoKHR>(VK_STRUCTURE_TYPE_RENDERING_INFO_KHR);
    info.renderArea = {{0, 0}, extent};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color_info;
    info.pDepthAttachment = depth.image ? &depth_info : nullptr;
    device_->dispatch_->cmd_begin_rendering(cmd_, &info);
    rendering_ = true;
    set_viewport(0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height));
    set_scissor({{0, 0}, extent});
}

void CommandList::end_rendering() {
    LANTERN_ASSERT(cmd_ && rendering_, "gpu: end_rendering without begin_rendering");
    device_->dispatch_->cmd_end_rendering(cmd_);
    rendering_ = false;
}

void CommandList::bind(const GraphicsPipeline& pipeline) {
    LANTERN_ASSERT(cmd_ && pipeline, "gpu: bind on a closed list or of an empty pipeline");
    vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.vk());
    bind_layout(VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout(), pipeline.bindings(),
                pipeline.push_constant_size(),
                VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
}

void CommandList::set_viewport(float x, float y, float width, float height) {
    LANTERN_ASSERT(cmd_ && width > 0.0f && height > 0.0f, "gpu: empty viewport or closed list");
    const VkViewport viewport{x, y, width, height, 0.0f, 1.0f};
    vkCmdSetViewport(cmd_, 0, 1, &viewport);
}

void CommandList::set_scissor(const VkRect2D& rect) {
    LANTERN_ASSERT(cmd_ && rect.offset.x >= 0 && rect.offset.y >= 0,
                   "gpu: negative scissor or closed list");
    vkCmdSetScissor(cmd_, 0, 1, &rect);
}

void CommandList::bind_vertex_buffer(const Buffer& buffer, VkDeviceSize offset) {
    LANTERN_ASSERT(cmd_ && buffer && offset < buffer.size(),
                   "gpu: vertex buffer empty or offset outside it");
    LANTERN_ASSERT(buffer.usage() & VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                   "gpu: buffer lacks VERTEX_BUFFER usage");
    const VkBuffer vk_buffer = buffer.vk();
    vkCmdBindVertexBuffers(cmd_, 0, 1, &vk_buffer, &offset);
}

void CommandList::bind_index_buffer(const Buffer& buffer, VkIndexType type, VkDeviceSize offset) {
    LANTERN_ASSERT(cmd_ && buffer && offset < buffer.size(),
                   "gpu: index buffer empty or offset outside it");
    LANTERN_ASSERT(buffer.usage() & VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                   "gpu: buffer lacks INDEX_BUFFER usage");
    LANTERN_ASSERT(offset % (type == VK_INDEX_TYPE_UINT16 ? 2 : 4) == 0,
                   "gpu: index buffer offset misaligned");
    vkCmdBindIndexBuffer(cmd_, buffer.vk(), offset, type);
}

void CommandList::draw(std::uint32_t vertex_count, std::uint32_t instance_count,
                       std::uint32_t first_vertex, std::uint32_t first_instance) {
    LANTERN_ASSERT(cmd_ && rendering_ && layout_ && bind_point_ == VK_PIPELINE_BIND_POINT_GRAPHICS,
                   "gpu: draw needs a rendering scope and a bound graphics pipeline");
    vkCmdDraw(cmd_, vertex_count, instance_count, first_vertex, first_instance);
}

void CommandList::draw_indexed(std::uint32_t index_count, std::uint32_t instance_count,
                               std::uint32_t first_index, std::int32_t vertex_offset,
                               std::uint32_t first_instance) {
    LANTERN_ASSERT(cmd_ && rendering_ && layout_ && bind_point_ == VK_PIPELINE_BIND_POINT_GRAPHICS,
                   "gpu: draw needs a rendering scope and a bound graphics pipeline");
    vkCmdDrawIndexed(cmd_, index_count, instance_count, first_index, vertex_offset, first_instance);
}

} // namespace lantern::gpu
