// Graphics pipelines for dynamic rendering: SPIR-V vertex + fragment shaders, one vertex
// buffer layout, depth and blend state, push constants and one descriptor set of push
// descriptors, created by Device::create_graphics_pipeline (devices created with
// DeviceOptions::graphics).
//
// Descriptor layout contract, as for compute pipelines: the shaders' resources are all in
// `layout(set = 0)`, binding i has type bindings[i] and is visible to both stages; each
// draw's resources are pushed with CommandList::push_descriptors. The push-constant block
// is visible to both stages too.
//
// Fixed choices (Lantern draws sprites, tiles and full-screen passes): one colour
// attachment, no multisampling, counter-clockwise front faces, viewport and scissor
// dynamic (CommandList::begin_rendering sets both to the whole target).
//
// Ownership: like ComputePipeline (move-only, destroyed deferred, before the Device).
#pragma once

#include "lantern/gpu/pipeline.hpp"

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace lantern::gpu {

class Device;

// `layout(location = location) in` of the vertex shader, read at byte `offset` of a vertex.
struct VertexAttribute {
    std::uint32_t location = 0;
    VkFormat format = VK_FORMAT_R32G32_SFLOAT;
    std::uint32_t offset = 0;
};

// The layout of the vertex buffer bound with CommandList::bind_vertex_buffer. stride 0 means
// no vertex input: the shader makes its vertices from gl_VertexIndex (full-screen passes).
struct VertexLayout {
    std::uint32_t stride = 0;  // bytes per vertex (or per instance)
    bool per_instance = false; // advance per instance instead of per vertex
    std::vector<VertexAttribute> attributes{};
};

enum class BlendMode : std::uint8_t {
    opaque, // the fragment replaces the target
    alpha,  // rgb = src.rgb * src.a + dst.rgb * (1 - src.a); a = src.a + dst.a * (1 - src.a)
};

struct DepthState {
    bool test = false;  // discard fragments failing `compare` against the depth attachment
    bool write = false; // write passing fragments' depth
    VkCompareOp compare = VK_COMPARE_OP_LESS_OR_EQUAL;
};

struct GraphicsPipelineDesc {
    // SPIR-V words with entry points "main" (see lantern_add_shader_library). Read during the
    // call only.
    std::span<const std::uint32_t> vertex_spirv{};
    std::span<const std::uint32_t> fragment_spirv{};
    VertexLayout vertex{};
    std::vector<BindingType> bindings{};        // binding i of set 0; at most max_bindings
    std::vector<SpecConstant> specialization{}; // given to both stages
    std::uint32_t push_constant_size = 0;       // bytes, a multiple of 4, <= maxPushConstantsSize
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkCullModeFlags cull = VK_CULL_MODE_NONE;
    DepthState depth{};
    BlendMode blend = BlendMode::opaque;
    // The formats of the attachments it draws into (CommandList::begin_rendering): the colour
    // format, and the depth format or VK_FORMAT_UNDEFINED for none.
    VkFormat color_format = VK_FORMAT_UNDEFINED;
    VkFormat depth_format = VK_FORMAT_UNDEFINED;
    const char* name = nullptr; // debug name
};

struct GraphicsPipelineFields : PipelineFields {
    VkFormat color_format_ = VK_FORMAT_UNDEFINED;
    VkFormat depth_format_ = VK_FORMAT_UNDEFINED;
};

// Move-only; reset() (or destruction) queues the pipeline and its layouts for deferred
// destruction.
class GraphicsPipeline : public OwningHandle<GraphicsPipeline, GraphicsPipelineFields> {
  public:
    static constexpr std::uint32_t max_bindings = ComputePipeline::max_bindings;

    explicit operator bool() const { return pipeline_ != VK_NULL_HANDLE; }
    VkPipeline vk() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_; }
    std::span<const BindingType> bindings() const { return {bindings_.data(), binding_count_}; }
    std::uint32_t push_constant_size() const { return push_constant_size_; }
    VkFormat color_format() const { return color_format_; }
    VkFormat depth_format() const { return depth_format_; }

  private:
    friend class Device;
    friend class OwningHandle<GraphicsPipeline, GraphicsPipelineFields>;
    static void retire(GraphicsPipelineFields& f);
};

} // namespace lantern::gpu
