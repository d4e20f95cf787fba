// The Vulkan renderer's private pieces shared by its files: renderer.cpp (textures,
// uploads, recording), renderer_timings.cpp (timestamp query sets) and
// renderer_read_back.cpp (read back and the copy baseline).
#pragma once

#include "lantern/gi/vulkan/pass_params.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gpu/reflect.hpp"
#include "lantern_gi_shaders.hpp"

#include <cstddef>
#include <map>
#include <span>
#include <string>
#include <tuple>
#include <vector>

namespace lantern::gi::vk {

inline constexpr int num_query_sets = 3; // frames in flight + one being recorded

inline int pitch_of(int width) { return (width + 3) & ~3; }

inline std::span<const std::byte> bytes_of(const void* data, std::size_t size) {
    return {static_cast<const std::byte*>(data), size};
}

// Checks a GI shader's push-constant block against GiPush<P>: the size, the shared fields'
// offsets, and each of the pass's parameters (offset and scalar type, in order).
void check_params_layout(const char* shader, std::span<const std::uint32_t> spirv,
                         std::span<const gpu::ScalarKind> kinds);

// Pipelines by (shader, specialisation), created on first use and kept.
struct Renderer::Pipelines {
    gpu::Device* device = nullptr;
    std::map<std::tuple<ShaderLookup, std::string, bool, bool, bool, bool, std::uint32_t, std::uint32_t>, gpu::ComputePipeline>
        cache;

    const gpu::ComputePipeline& get(ShaderLookup shaders, const char* shader, std::span<const gpu::ScalarKind> kinds,
                                    std::uint32_t block_h, std::uint32_t gx, std::uint32_t gy, bool proxies = true,
                                    bool walls = true, bool per_channel = true, bool segment_check = true,
                                    std::uint32_t features = 0, std::uint32_t faces = 15) {
        if (!shaders) shaders = lantern_gi_shaders_spirv;
        auto key = std::make_tuple(shaders, std::string(shader), proxies, walls, per_channel, segment_check, features, faces);
        auto it = cache.find(key);
        if (it != cache.end()) return it->second;
        gpu::ComputePipelineDesc desc;
        desc.spirv = shaders(shader);
        LANTERN_VERIFY(!desc.spirv.empty(), (std::string("GI shader '") + shader + "' missing from its pass row's "
                                             "shader library").c_str());
        check_params_layout(shader, desc.spirv, kinds); // the bindings come from the shader itself
        desc.specialization = {{spec_block_h, block_h},       {spec_group_x, gx},
                               {spec_group_y, gy},            {spec_has_proxies, proxies ? 1u : 0u},
                               {spec_has_walls, walls ? 1u : 0u}, {spec_per_channel, per_channel ? 1u : 0u},
                               {spec_segment_check, segment_check ? 1u : 0u}, {spec_features, features},
                               {spec_faces, faces}};
        if (std::string(shader) == "gi_direct.comp" || std::string(shader) == "gi_light_bins.comp")
            desc.specialization.push_back({spec_max_lights, max_gpu_lights});
        desc.push_constant_size = sizeof(GiPassParams);
        desc.name = shader;
        return cache.emplace(key, device->create_compute_pipeline(desc)).first->second;
    }
};

struct Renderer::QuerySet {
    gpu::TimestampQueries queries;
    std::vector<Pass> passes; // region i measured passes[i]
    bool pending = false;     // recorded, not yet read
    std::uint64_t frame = 0;
};

} // namespace lantern::gi::vk
