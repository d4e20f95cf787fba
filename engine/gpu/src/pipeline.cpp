// Compute pipelines with push-descriptor set layouts and specialization constants.
#include "device_internal.hpp"

#include "lantern/gpu/reflect.hpp"
#include "lantern/gpu/vk_check.hpp"

#include <string>
#include <utility>
#include <vector>

namespace lantern::gpu {

namespace {

VkDescriptorType descriptor_type(BindingType type) {
    switch (type) {
    case BindingType::storage_buffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingType::uniform_buffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingType::uniform_texel_buffer: return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    case BindingType::storage_texel_buffer: return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
    case BindingType::combined_image_sampler: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    }
    return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}

} // namespace

namespace detail {

VkDescriptorSetLayout create_set_layout(VkDevice device, std::span<const BindingType> bindings,
                                        VkShaderStageFlags stages) {
    std::vector<VkDescriptorSetLayoutBinding> vk_bindings;
    for (std::uint32_t i = 0; i < bindings.size(); ++i) {
        VkDescriptorSetLayoutBinding b{};
        b.binding = i;
        b.descriptorType = descriptor_type(bindings[i]);
        b.descriptorCount = 1;
        b.stageFlags = stages;
        vk_bindings.push_back(b);
    }
    auto info = vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    info.bindingCount = static_cast<std::uint32_t>(vk_bindings.size());
    info.pBindings = vk_bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorSetLayout(device, &info, nullptr, &layout));
    return layout;
}

VkPipelineLayout create_pipeline_layout(VkDevice device, VkDescriptorSetLayout set_layout,
                                        std::uint32_t push_constant_size,
                                        VkShaderStageFlags stages) {
    VkPushConstantRange range{stages, 0, push_constant_size};
    auto info = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    info.setLayoutCount = set_layout ? 1 : 0;
    info.pSetLayouts = &set_layout;
    info.pushConstantRangeCount = push_constant_size > 0 ? 1 : 0;
    info.pPushConstantRanges = &range;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VK_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &layout));
    return layout;
}

VkShaderModule create_shader_module(VkDevice device, std::span<const std::uint32_t> spirv) {
    auto info = vk_struct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    info.codeSize = spirv.size_bytes();
    info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
    return module;
}

Specialization::Specialization(std::span<const SpecConstant> constants) {
    for (const SpecConstant& c : constants) {
        const auto offset = static_cast<std::uint32_t>(values_.size() * sizeof(std::uint32_t));
        entries_.push_back({c.id, offset, sizeof(std::uint32_t)});
        values_.push_back(c.value);
    }
    info_.mapEntryCount = static_cast<std::uint32_t>(entries_.size());
    info_.pMapEntries = entries_.data();
    info_.dataSize = values_.size() * sizeof(std::uint32_t);
    info_.pData = values_.data();
}

} // namespace detail

const char* to_string(BindingType type) {
    switch (type) {
    case BindingType::storage_buffer: return "storage_buffer";
    case BindingType::uniform_buffer: return "uniform_buffer";
    case BindingType::uniform_texel_buffer: return "uniform_texel_buffer";
    case BindingType::storage_texel_buffer: return "storage_texel_buffer";
    case BindingType::combined_image_sampler: return "combined_image_sampler";
    }
    return "?";
}

namespace detail {

PipelineLayoutInfo resolve_layout(std::span<const std::span<const std::uint32_t>> stages,
                                  std::span<const BindingType> declared, std::uint32_t declared_push_size,
                                  const char* name) {
    const std::string who = std::string("gpu: pipeline '") + (name ? name : "?") + "': ";
    ShaderLayout merged;
    for (std::span<const std::uint32_t> words : stages) {
        auto layout = reflect_spirv(words);
        LANTERN_VERIFY(layout.ok(), (who + (layout.ok() ? "" : layout.error().message)).c_str());
        auto both = merge_layouts(merged, *layout);
        LANTERN_VERIFY(both.ok(), (who + (both.ok() ? "" : both.error().message)).c_str());
        merged = std::move(*both);
    }
    auto dense = merged.dense_bindings();
    LANTERN_VERIFY(dense.ok(), (who + (dense.ok() ? "" : dense.error().message)).c_str());
    PipelineLayoutInfo out{std::move(*dense), merged.push_constant_size};
    if (!declared.empty()) {
        std::string mismatch;
        if (declared.size() != out.bindings.size())
            mismatch = "the description lists " + std::to_string(declared.size()) + " bindings, the shaders declare " +
                       std::to_string(out.bindings.size());
        for (std::size_t i = 0; mismatch.empty() && i < declared.size(); ++i)
            if (declared[i] != out.bindings[i])
                mismatch = "binding " + std::to_string(i) + " is " + to_string(declared[i]) + " in the description, " +
                           to_string(out.bindings[i]) + " in the shader";
        LANTERN_VERIFY(mismatch.empty(), (who + mismatch).c_str());
    }
    if (declared_push_size != 0) {
        // The C++ struct may be padded past the block's end (alignas(16)); never shorter.
        LANTERN_VERIFY(declared_push_size >= out.push_constant_size,
                       (who + "push constants of " + std::to_string(declared_push_size) +
                        " bytes in the description, but the shader's block is " +
                        std::to_string(out.push_constant_size) + " bytes")
                           .c_str());
        out.push_constant_size = declared_push_size;
    }
    return out;
}

} // namespace detail

ComputePipeline Device::create_compute_pipeline(const ComputePipelineDesc& desc) {
    LANTERN_ASSERT(desc.spirv.size() >= 5 && desc.spirv[0] == 0x07230203u,
                   "gpu: compute pipeline needs SPIR-V words (empty lookup result?)");
    LANTERN_ASSERT(desc.bindings.size() <= ComputePipeline::max_bindings,
                   "gpu: more bindings than ComputePipeline::max_bindings");
    LANTERN_ASSERT(desc.push_constant_size % 4 == 0 &&
                       desc.push_constant_size <= caps_.max_push_constants_size,
                   "gpu: push-constant size must be a multiple of 4 within maxPushConstantsSize");

    const std::span<const std::uint32_t> stages[] = {desc.spirv};
    const detail::PipelineLayoutInfo layout =
        detail::resolve_layout(stages, desc.bindings, desc.push_constant_size, desc.name);
    LANTERN_ASSERT(layout.bindings.size() <= ComputePipeline::max_bindings,
                   "gpu: more bindings than ComputePipeline::max_bindings");
    LANTERN_ASSERT(layout.push_constant_size <= caps_.max_push_constants_size,
                   "gpu: push constants larger than maxPushConstantsSize");

    ComputePipeline p;
    p.device_ = this;
    p.binding_count_ = static_cast<std::uint32_t>(layout.bindings.size());
    std::copy(layout.bindings.begin(), layout.bindings.end(), p.bindings_.begin());
    p.push_constant_size_ = layout.push_constant_size;
    if (!layout.bindings.empty())
        p.set_layout_ = detail::create_set_layout(device_, layout.bindings, VK_SHADER_STAGE_COMPUTE_BIT);
    p.layout_ = detail::create_pipeline_layout(device_, p.set_layout_, layout.push_constant_size,
                                               VK_SHADER_STAGE_COMPUTE_BIT);
    const detail::Specialization specialization(desc.specialization);

    const VkShaderModule module = detail::create_shader_module(device_, desc.spirv);
    auto info = vk_struct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = specialization.info();
    info.layout = p.layout_;
    VK_CHECK(vkCreateComputePipelines(device_, pipeline_cache_, 1, &info, nullptr, &p.pipeline_));
    // The pipeline keeps what it needs; the module may go at once.
    vkDestroyShaderModule(device_, module, nullptr);

    set_object_name(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<std::uint64_t>(p.pipeline_), desc.name);
    set_object_name(VK_OBJECT_TYPE_PIPELINE_LAYOUT, reinterpret_cast<std::uint64_t>(p.layout_), desc.name);
    std::lock_guard lock(deletions_->mutex);
    ++deletions_->live_objects;
    return p;
}

void ComputePipeline::retire(PipelineFields& f) {
    Device::Retired retired;
    retired.pipeline = f.pipeline_;
    retired.layout = f.layout_;
    retired.set_layout = f.set_layout_;
    f.device_->retire(retired);
}

} // namespace lantern::gpu
