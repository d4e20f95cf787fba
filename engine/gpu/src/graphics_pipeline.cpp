// Graphics pipelines for dynamic rendering (VK_KHR_dynamic_rendering), push descriptors.
#include "device_internal.hpp"

#include "lantern/gpu/vk_check.hpp"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace lantern::gpu {

namespace {

constexpr VkShaderStageFlags raster_stages =
    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

bool is_spirv(std::span<const std::uint32_t> words) {
    return words.size() >= 5 && words[0] == 0x07230203u;
}

// The fixed-function state a GraphicsPipelineDesc describes, with the arrays the create
// info points into.
struct FixedState {
    VkVertexInputBindingDescription binding{};
    std::vector<VkVertexInputAttributeDescription> attributes;
    VkPipelineVertexInputStateCreateInfo vertex_input =
        vk_struct<VkPipelineVertexInputStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
    VkPipelineInputAssemblyStateCreateInfo input_assembly =
        vk_struct<VkPipelineInputAssemblyStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
    VkPipelineViewportStateCreateInfo viewport = vk_struct<VkPipelineViewportStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
    VkPipelineRasterizationStateCreateInfo raster =
        vk_struct<VkPipelineRasterizationStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
    VkPipelineMultisampleStateCreateInfo multisample =
        vk_struct<VkPipelineMultisampleStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
    VkPipelineDepthStencilStateCreateInfo depth = vk_struct<VkPipelineDepthStencilStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
    VkPipelineColorBlendAttachmentState blend_attachment{};
    VkPipelineColorBlendStateCreateInfo blend = vk_struct<VkPipelineColorBlendStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
    std::array<VkDynamicState, 2> dynamic_states = {VK_DYNAMIC_STATE_VIEWPORT,
                                                    VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic = vk_struct<VkPipelineDynamicStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
    VkPipelineRenderingCreateInfoKHR rendering = vk_struct<VkPipelineRenderingCreateInfoKHR>(
        VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO_KHR);

    explicit FixedState(const GraphicsPipelineDesc& desc) {
        set_vertex_input(desc.vertex);
        input_assembly.topology = desc.topology;
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = desc.cull;
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f;
        multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        depth.depthTestEnable = desc.depth.test ? VK_TRUE : VK_FALSE;
        depth.depthWriteEnable = desc.depth.write ? VK_TRUE : VK_FALSE;
        depth.depthCompareOp = desc.depth.compare;
        set_blend(desc.blend);
        dynamic.dynamicStateCount = static_cast<std::uint32_t>(dynamic_states.size());
        dynamic.pDynamicStates = dynamic_states.data();
        rendering.colorAttachmentCount = 1;
        rendering.pColorAttachmentFormats = &desc.color_format;
        rendering.depthAttachmentFormat = desc.depth_format;
    }
    FixedState(const FixedState&) = delete;
    FixedState& operator=(const FixedState&) = delete;

    void set_vertex_input(const VertexLayout& layout) {
        if (layout.stride == 0) return; // vertices made in the shader
        binding.binding = 0;
        binding.stride = layout.stride;
        binding.inputRate =
            layout.per_instance ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX;
        for (const VertexAttribute& a : layout.attributes)
            attributes.push_back({a.location, 0, a.format, a.offset});
        vertex_input.vertexBindingDescriptionCount = 1;
        vertex_input.pVertexBindingDescriptions = &binding;
        vertex_input.vertexAttributeDescriptionCount =
            static_cast<std::uint32_t>(attributes.size());
        vertex_input.pVertexAttributeDescriptions = attributes.data();
    }

    void set_blend(BlendMode mode) {
        blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                          VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
        if (mode == BlendMode::alpha) {
            blend_attachment.blendEnable = VK_TRUE;
            blend_attachment.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
            blend_attachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
            blend_attachment.colorBlendOp = VK_BLEND_OP_ADD;
            blend_attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
            blend_attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
            blend_attachment.alphaBlendOp = VK_BLEND_OP_ADD;
        }
        blend.attachmentCount = 1;
        blend.pAttachments = &blend_attachment;
    }
};

VkPipelineShaderStageCreateInfo stage_info(VkShaderStageFlagBits stage, VkShaderModule module,
                                           const VkSpecializationInfo* specialization) {
    auto info = vk_struct<VkPipelineShaderStageCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    info.stage = stage;
    info.module = module;
    info.pName = "main";
    info.pSpecializationInfo = specialization;
    return info;
}

} // namespace

GraphicsPipeline Device::create_graphics_pipeline(const GraphicsPipelineDesc& desc) {
    LANTERN_ASSERT(caps_.graphics,
                   "gpu: graphics pipelines need a device created with DeviceOptions::graphics");
    LANTERN_ASSERT(
        is_spirv(desc.vertex_spirv) && is_spirv(desc.fragment_spirv),
        "gpu: graphics pipeline needs SPIR-V words for both stages (empty lookup result?)");
    LANTERN_ASSERT(desc.bindings.size() <= GraphicsPipeline::max_bindings,
                   "gpu: more bindings than GraphicsPipeline::max_bindings");
    LANTERN_ASSERT(desc.push_constant_size % 4 == 0 &&
                       desc.push_constant_size <= caps_.max_push_constants_size,
                   "gpu: push-constant size must be a multiple of 4 within maxPushConstantsSize");
    LANTERN_ASSERT(desc.color_format != VK_FORMAT_UNDEFINED,
                   "gpu: graphics pipeline without a colour format");
    LANTERN_ASSERT(desc.depth_format == VK_FORMAT_UNDEFINED || is_depth_format(desc.depth_format),
                   "gpu: depth_format is not a depth format");
    LANTERN_ASSERT(!desc.depth.test || desc.depth_format != VK_FORMAT_UNDEFINED,
                   "gpu: depth test without a depth format");

    const std::span<const std::uint32_t> spirv_stages[] = {desc.vertex_spirv, desc.fragment_spirv};
    const detail::PipelineLayoutInfo layout =
        detail::resolve_layout(spirv_stages, desc.bindings, desc.push_constant_size, desc.name);
    LANTERN_ASSERT(layout.bindings.size() <= GraphicsPipeline::max_bindings,
                   "gpu: more bindings than GraphicsPipeline::max_bindings");

    GraphicsPipeline p;
    p.device_ = this;
    p.binding_count_ = static_cast<std::uint32_t>(layout.bindings.size());
    std::copy(layout.bindings.begin(), layout.bindings.end(), p.bindings_.begin());
    p.push_constant_size_ = layout.push_constant_size;
    p.color_format_ = desc.color_format;
    p.depth_format_ = desc.depth_format;
    if (!layout.bindings.empty())
        p.set_layout_ = detail::create_set_layout(device_, layout.bindings, raster_stages);
    p.layout_ = detail::create_pipeline_layout(device_, p.set_layout_, layout.push_constant_size,
                                               raster_stages);

    const detail::Specialization specialization(desc.specialization);
    const VkShaderModule vertex = detail::create_shader_module(device_, desc.vertex_spirv);
    const VkShaderModule fragment = detail::create_shader_module(device_, desc.fragment_spirv);
    const std::array<VkPipelineShaderStageCreateInfo, 2> stages = {
        stage_info(VK_SHADER_STAGE_VERTEX_BIT, vertex, specialization.info()),
        stage_info(VK_SHADER_STAGE_FRAGMENT_BIT, fragment, specialization.info())};
    FixedState state(desc);

    auto info =
        vk_struct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
    info.pNext = &state.rendering; // dynamic rendering: no VkRenderPass
    info.stageCount = static_cast<std::uint32_t>(stages.size());
    info.pStages = stages.data();
    info.pVertexInputState = &state.vertex_input;
    info.pInputAssemblyState = &state.input_assembly;
    info.pViewportState = &state.viewport;
    info.pRasterizationState = &state.raster;
    info.pMultisampleState = &state.multisample;
    info.pDepthStencilState = &state.depth;
    info.pColorBlendState = &state.blend;
    info.pDynamicState = &state.dynamic;
    info.layout = p.layout_;
    VK_CHECK(vkCreateGraphicsPipelines(device_, pipeline_cache_, 1, &info, nullptr, &p.pipeline_));
    vkDestroyShaderModule(device_, vertex, nullptr);
    vkDestroyShaderModule(device_, fragment, nullptr);

    set_object_name(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<std::uint64_t>(p.pipeline_),
                    desc.name);
    set_object_name(VK_OBJECT_TYPE_PIPELINE_LAYOUT, reinterpret_cast<std::uint64_t>(p.layout_),
                    desc.name);
    count_live_object();
    return p;
}

void GraphicsPipeline::retire(GraphicsPipelineFields& f) {
    Device::Retired retired;
    retired.pipeline = f.pipeline_;
    retired.layout = f.layout_;
    retired.set_layout = f.set_layout_;
    f.device_->retire(retired);
}

} // namespace lantern::gpu
