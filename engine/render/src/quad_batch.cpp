// QuadBatch: instance packing, the quad pipeline, one instanced draw.
#include "lantern/render/quad_batch.hpp"

#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/device.hpp"

#include "lantern_render_shaders.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace lantern::render {

namespace {

static_assert(sizeof(QuadBatch::Instance) == 40, "render_quad.vert.glsl reads 40-byte instances");
static_assert(offsetof(QuadBatch::Instance, uv) == 16 &&
                  offsetof(QuadBatch::Instance, color) == 32 &&
                  offsetof(QuadBatch::Instance, depth) == 36,
              "QuadBatch::Instance must match the attribute offsets");

struct alignas(16) QuadPush {
    float inverse_target_size[2];
};
static_assert(sizeof(QuadPush) == 16,
              "QuadPush mirrors render_quad.vert.glsl's push block (padded)");

std::uint32_t pack_unorm8(const glm::vec4& color) {
    std::uint32_t packed = 0;
    for (int i = 0; i < 4; ++i) {
        const float c = std::clamp(color[i], 0.0f, 1.0f);
        packed |= static_cast<std::uint32_t>(std::lround(c * 255.0f)) << (8 * i);
    }
    return packed;
}

gpu::GraphicsPipelineDesc pipeline_desc(const QuadBatchDesc& desc) {
    const bool depth = desc.depth_format != VK_FORMAT_UNDEFINED;
    gpu::GraphicsPipelineDesc p;
    p.vertex_spirv = lantern_render_shaders_spirv("render_quad.vert");
    p.fragment_spirv = lantern_render_shaders_spirv("render_quad.frag");
    p.vertex.stride = sizeof(QuadBatch::Instance);
    p.vertex.per_instance = true;
    p.vertex.attributes = {{0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(QuadBatch::Instance, rect)},
                           {1, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(QuadBatch::Instance, uv)},
                           {2, VK_FORMAT_R8G8B8A8_UNORM, offsetof(QuadBatch::Instance, color)},
                           {3, VK_FORMAT_R32_SFLOAT, offsetof(QuadBatch::Instance, depth)}};
    p.bindings = {gpu::BindingType::combined_image_sampler};
    p.push_constant_size = sizeof(QuadPush);
    p.depth = {depth, depth, VK_COMPARE_OP_LESS_OR_EQUAL};
    p.blend = desc.blend;
    p.color_format = desc.color_format;
    p.depth_format = desc.depth_format;
    p.name = "QuadBatch";
    return p;
}

} // namespace

QuadBatch QuadBatch::create(gpu::Device& device, const QuadBatchDesc& desc) {
    LANTERN_ASSERT(desc.max_quads > 0, "render::QuadBatch of 0 quads");
    QuadBatch batch;
    batch.pipeline_ = device.create_graphics_pipeline(pipeline_desc(desc));
    batch.sampler_ = device.create_sampler(
        {VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "QuadBatch"});
    batch.white_ = device.create_image(
        {1, 1, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "QuadBatch white"});
    const std::array<std::byte, 4> white = {std::byte{255}, std::byte{255}, std::byte{255},
                                            std::byte{255}};
    device.upload(batch.white_, white, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    batch.buffer_ = StreamBuffer::create(device, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                         VkDeviceSize{desc.max_quads} * sizeof(Instance),
                                         "QuadBatch instances");
    batch.max_quads_ = desc.max_quads;
    batch.instances_.reserve(desc.max_quads);
    return batch;
}

void QuadBatch::clear() {
    instances_.clear();
    dirty_ = true;
}

void QuadBatch::add(const Quad& quad) {
    LANTERN_ASSERT(instances_.size() < max_quads_, "render::QuadBatch::add beyond max_quads");
    instances_.push_back({{quad.min.x, quad.min.y, quad.max.x, quad.max.y},
                          {quad.uv_min.x, quad.uv_min.y, quad.uv_max.x, quad.uv_max.y},
                          pack_unorm8(quad.color),
                          quad.depth});
    dirty_ = true;
}

void QuadBatch::upload(gpu::CommandList& cmd) {
    LANTERN_ASSERT(pipeline_, "render::QuadBatch::upload on an empty batch object");
    buffer_.write(cmd, std::as_bytes(std::span<const Instance>(instances_)));
    uploaded_ = instances_.size();
    dirty_ = false;
}

void QuadBatch::draw(gpu::CommandList& cmd, VkExtent2D target, const gpu::Image* texture) {
    LANTERN_ASSERT(!dirty_, "render::QuadBatch::draw: quads changed since upload()");
    if (uploaded_ == 0) return;
    cmd.bind(pipeline_);
    cmd.push_descriptors(
        gpu::DescriptorWrites().combined_image_sampler(0, texture ? *texture : white_, sampler_));
    cmd.push_constants(QuadPush{{1.0f / float(target.width), 1.0f / float(target.height)}});
    cmd.bind_vertex_buffer(buffer_.buffer());
    cmd.draw(6, static_cast<std::uint32_t>(uploaded_));
}

} // namespace lantern::render
