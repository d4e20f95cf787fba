// Compute pipelines: SPIR-V + specialization constants + push constants + one descriptor set
// of push descriptors (VK_KHR_push_descriptor), created by Device::create_compute_pipeline.
//
// Descriptor layout contract: the shader's resources are all in `layout(set = 0)`, binding i
// has type bindings[i] (bindings are dense, 0..n-1). Each dispatch's resources are pushed
// with CommandList::push_descriptors; there are no descriptor pools or sets to manage.
//
// Ownership: like Buffer (move-only, destroyed deferred, before the Device).
#pragma once

#include "lantern/gpu/owning_handle.hpp"

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace lantern::gpu {

class Device;

enum class BindingType : std::uint8_t {
    storage_buffer,       // GLSL `buffer` block (std430), read/write
    uniform_buffer,       // GLSL `uniform` block (std140), at most maxUniformBufferRange bytes
    uniform_texel_buffer, // GLSL `textureBuffer` / `samplerBuffer`, read with texelFetch
    storage_texel_buffer, // GLSL `imageBuffer` with a format qualifier, imageLoad/imageStore
    combined_image_sampler, // GLSL `sampler2D`: an Image (SAMPLED usage) with a Sampler
};

const char* to_string(BindingType type);

// Value of `layout(constant_id = id) const uint|int|bool|float ...`. Booleans are 0/1;
// floats are std::bit_cast<std::uint32_t>(value).
struct SpecConstant {
    std::uint32_t id = 0;
    std::uint32_t value = 0;
};

struct ComputePipelineDesc {
    // SPIR-V words of a compute shader with entry point "main" (see lantern_add_shader_library).
    // Only read during the call.
    std::span<const std::uint32_t> spirv{};
    std::vector<BindingType> bindings{}; // binding i of set 0; at most max_bindings
    std::vector<SpecConstant> specialization{};
    std::uint32_t push_constant_size = 0;  // bytes, a multiple of 4, <= maxPushConstantsSize
    const char* name = nullptr;            // debug name
};

// VK_KHR_push_descriptor guarantees maxPushDescriptors >= 32.
inline constexpr std::uint32_t max_pipeline_bindings = 32;

struct PipelineFields {
    Device* device_ = nullptr;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    std::array<BindingType, max_pipeline_bindings> bindings_{};
    std::uint32_t binding_count_ = 0;
    std::uint32_t push_constant_size_ = 0;
};

// Move-only; reset() (or destruction) queues the pipeline and its layouts for deferred
// destruction.
class ComputePipeline : public OwningHandle<ComputePipeline, PipelineFields> {
  public:
    static constexpr std::uint32_t max_bindings = max_pipeline_bindings;

    explicit operator bool() const { return pipeline_ != VK_NULL_HANDLE; }
    VkPipeline vk() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_; }
    std::span<const BindingType> bindings() const { return {bindings_.data(), binding_count_}; }
    std::uint32_t push_constant_size() const { return push_constant_size_; }

  private:
    friend class Device;
    friend class OwningHandle<ComputePipeline, PipelineFields>;
    static void retire(PipelineFields& f);
};


} // namespace lantern::gpu
