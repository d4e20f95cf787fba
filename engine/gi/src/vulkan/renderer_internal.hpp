// The Vulkan renderer's private pieces shared by its files: renderer.cpp (textures,
// uploads, recording), renderer_timings.cpp (timestamp query sets) and
// renderer_read_back.cpp (read back and the copy baseline).
#pragma once

#include "lantern/gi/vulkan/pass_params.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gpu/reflect.hpp"
#include "lantern/profile/profiler.hpp"
#include "lantern_gi_shaders.hpp"

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <future>
#include <map>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
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

// Pipelines by (shader, specialisation), created on first use and kept. lavapipe compiles a
// pipeline in 50-100 ms, so a variant first needed mid-game (the first shadow proxy, the
// first sunrise) was a frame hitch: rows prefetch on background threads the variants a later
// frame may need (the direct row: its own with proxies and walls flipped, and the suns'). A
// frame that needs a pipeline the thread is creating waits for it; one still queued it
// creates itself (a frame must not wait for the whole queue ahead of it: the shader warm-up's
// frames, systems::GiFrameOptions::warm_up_shaders, need several at once). Each lavapipe
// pipeline holds about 5 MB of JIT code, so only those are prefetched.
using PipelineKey = std::tuple<ShaderLookup, std::string, bool, bool, bool, bool, bool, bool, std::uint32_t, std::uint32_t>;

// A PipelineSpec with the renderer's block and workgroup sizes filled in.
struct ResolvedSpec {
    std::uint32_t block_h, gx, gy;
    bool proxies, walls, per_channel, segment_check;
    std::uint32_t features, faces;
    bool linear_penumbra, proxy_registers;
    PipelineKey key(ShaderLookup shaders, const char* shader) const {
        return {shaders, std::string(shader), proxies, walls, per_channel, segment_check, linear_penumbra, proxy_registers,
                features, faces};
    }
};

struct Renderer::Pipelines {
    using Key = PipelineKey;
    using Spec = ResolvedSpec;

    gpu::Device* device = nullptr;
    std::uint32_t exact_rounding = 1; // EXACT_ROUNDING in gi_exact.glsl (Renderer::create)
    std::map<Key, gpu::ComputePipeline> cache;
    std::map<Key, std::future<gpu::ComputePipeline>> pending;
    // One background thread creates the prefetched pipelines in turn: a thread per pipeline
    // left a malloc arena per thread holding the compiler's scratch (about 18 MB each).
    std::mutex mutex;
    std::condition_variable wake;
    std::deque<std::pair<Key, std::packaged_task<gpu::ComputePipeline()>>> queue;
    bool stopping = false;
    std::thread worker;

    // The queued pipelines are dropped, not created (their futures, never waited for now,
    // hold broken promises); the one under way is waited for.
    ~Pipelines() {
        {
            std::lock_guard lock(mutex);
            stopping = true;
            queue.clear();
        }
        wake.notify_one();
        if (worker.joinable()) worker.join();
    }

    void work() {
        for (;;) {
            std::packaged_task<gpu::ComputePipeline()> task;
            {
                std::unique_lock lock(mutex);
                wake.wait(lock, [&] { return stopping || !queue.empty(); });
                if (queue.empty()) return;
                task = std::move(queue.front().second);
                queue.pop_front();
            }
            task();
        }
    }

    gpu::ComputePipelineDesc describe(ShaderLookup shaders, const char* shader, std::span<const gpu::ScalarKind> kinds,
                                      const Spec& s) const {
        gpu::ComputePipelineDesc desc;
        desc.spirv = shaders(shader);
        LANTERN_VERIFY(!desc.spirv.empty(), (std::string("GI shader '") + shader + "' missing from its pass row's "
                                             "shader library").c_str());
        check_params_layout(shader, desc.spirv, kinds); // the bindings come from the shader itself
        desc.specialization = {{spec_block_h, s.block_h},       {spec_group_x, s.gx},
                               {spec_group_y, s.gy},            {spec_has_proxies, s.proxies ? 1u : 0u},
                               {spec_has_walls, s.walls ? 1u : 0u}, {spec_per_channel, s.per_channel ? 1u : 0u},
                               {spec_segment_check, s.segment_check ? 1u : 0u}, {spec_features, s.features},
                               {spec_faces, s.faces},           {spec_linear_penumbra, s.linear_penumbra ? 1u : 0u},
                               {spec_proxy_registers, s.proxy_registers ? 1u : 0u}, {spec_exact_rounding, exact_rounding}};
        if (std::string(shader) == "gi_direct.comp" || std::string(shader) == "gi_light_bins.comp")
            desc.specialization.push_back({spec_max_lights, max_gpu_lights});
        desc.push_constant_size = sizeof(GiPassParams);
        desc.name = shader;
        return desc;
    }

    // Starts creating the pipeline on a background thread unless it exists or is under way.
    void prefetch(ShaderLookup shaders, const char* shader, std::span<const gpu::ScalarKind> kinds, const Spec& s) {
        if (!shaders) shaders = lantern_gi_shaders_spirv;
        const Key key = s.key(shaders, shader);
        if (cache.count(key) || pending.count(key)) return;
        gpu::ComputePipelineDesc desc = describe(shaders, shader, kinds, s);
        gpu::Device* d = device;
        std::packaged_task<gpu::ComputePipeline()> task([d, desc = std::move(desc)] { return d->create_compute_pipeline(desc); });
        pending.emplace(key, task.get_future());
        {
            std::lock_guard lock(mutex);
            queue.emplace_back(key, std::move(task));
        }
        if (!worker.joinable()) worker = std::thread([this] { work(); });
        wake.notify_one();
    }

    const gpu::ComputePipeline& get(ShaderLookup shaders, const char* shader, std::span<const gpu::ScalarKind> kinds,
                                    const Spec& s) {
        if (!shaders) shaders = lantern_gi_shaders_spirv;
        const Key key = s.key(shaders, shader);
        if (auto it = cache.find(key); it != cache.end()) return it->second;
        if (auto it = pending.find(key); it != pending.end()) { // prefetched
            std::packaged_task<gpu::ComputePipeline()> queued;
            {
                std::lock_guard lock(mutex);
                const auto q = std::find_if(queue.begin(), queue.end(), [&](const auto& e) { return e.first == key; });
                if (q != queue.end()) {
                    queued = std::move(q->second);
                    queue.erase(q);
                }
            }
            if (queued.valid()) { // still queued: create it here
                LANTERN_PROFILE_SCOPE("gi.create_pipeline");
                queued();
            } else { // under way (or done) on the thread: wait for it
                LANTERN_PROFILE_SCOPE("gi.pipeline_wait");
                it->second.wait();
            }
            gpu::ComputePipeline p = it->second.get();
            pending.erase(it);
            return cache.emplace(key, std::move(p)).first->second;
        }
        LANTERN_PROFILE_SCOPE("gi.create_pipeline");
        return cache.emplace(key, device->create_compute_pipeline(describe(shaders, shader, kinds, s))).first->second;
    }
};

struct Renderer::QuerySet {
    gpu::TimestampQueries queries;
    struct Measured {
        Pass pass;
        const char* part = nullptr; // a part of the pass (PassRecorder::begin_part), else the whole
    };
    std::vector<Measured> passes; // region i measured passes[i]
    bool pending = false;     // recorded, not yet read
    std::uint64_t frame = 0;
};

} // namespace lantern::gi::vk
