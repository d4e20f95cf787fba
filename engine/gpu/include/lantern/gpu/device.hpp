// The Vulkan device: instance, physical-device choice, one queue, resource creation,
// submission with serials, deferred destruction, validation-message capture.
//
// Raster work (images as attachments, graphics pipelines, dynamic rendering) needs a device
// created with DeviceOptions::graphics; compute, buffers, images and samplers work on any.
//
// Creation never crashes: no loader driver, no device, or a device without what Lantern
// needs gives an Error whose message starts with "no Vulkan device: " and says why.
//
// Device choice: the best suitable device by type, discrete > integrated > virtual > CPU
// (lavapipe). LANTERN_VK_DEVICE=<index | case-insensitive name substring> (or, when that
// variable is unset or empty, DeviceOptions::device) picks one instead; it is an error when
// it matches no device or only unsuitable ones. Suitable = Vulkan 1.2+, a queue family with
// compute, VK_KHR_push_descriptor, uniform texel buffers of R8_UNORM, R8G8_UNORM and
// R16G16B16A16_SFLOAT, plus DeviceOptions' extra extensions (and, with
// DeviceOptions::graphics, raster support). Optional features are enabled when present and
// reported in Capabilities.
//
// Validation (DeviceOptions::validation or LANTERN_VK_VALIDATION=1; =sync adds the layer's
// synchronization validation): VK_LAYER_KHRONOS_validation plus a debug-utils messenger.
// Every warning and error message is counted and its text kept (the first 1000;
// validation_messages()); info and verbose messages are ignored. Messages are logged
// (log_validation_messages) and abort the process only with abort_on_validation_error.
// A missing layer logs a warning and leaves validation_enabled() false.
//
// Submission model: one queue. Device::submit returns a serial (1, 2, 3, ...); a submission
// "completes" when the GPU finished it, and serials complete in order. Any number of
// submissions may be in flight; each has its own fence and command pool, recycled when it
// completes.
//
// Deferred destruction: destroying a resource queues its Vulkan objects. They are freed by
// collect() (also run by submit, wait and wait_idle) once every submission that could use
// them completed: the submissions made before the destruction, and the CommandLists that
// were being recorded at that moment. ~Device waits for the GPU and frees everything;
// resources must all be destroyed before it (asserted).
//
// Threads: create_* and resource destruction may be called from any thread. begin, submit,
// wait*, completed_serial, collect, upload and read_back belong to one thread at a time
// (the submission thread). The validation accessors may be called from any thread.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gpu/buffer.hpp"
#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/graphics_pipeline.hpp"
#include "lantern/gpu/image.hpp"
#include "lantern/gpu/pipeline.hpp"
#include "lantern/gpu/timestamps.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace lantern::gpu {

enum class DeviceType : std::uint8_t { discrete, integrated, virtual_gpu, cpu, other };
const char* to_string(DeviceType type);

struct DeviceOptions {
    bool validation = false;                 // also enabled by LANTERN_VK_VALIDATION=1
    bool synchronization_validation = false; // the layer's hazard checks (slower; implies nothing
                                             // without validation; LANTERN_VK_VALIDATION=sync)
    bool log_validation_messages = true;     // log each counted message (warn/error level)
    bool abort_on_validation_error = false;  // abort on error-severity messages
    std::string device{};                    // selector, overridden by LANTERN_VK_DEVICE
    std::string application_name = "lantern";
    std::vector<const char*> instance_extensions{}; // extra required extensions (e.g. surfaces)
    std::vector<const char*> device_extensions{};   // extra required extensions (e.g. swapchain)
    // Raster work: the queue family must also do graphics, and VK_KHR_dynamic_rendering with
    // its dynamicRendering feature and the imagelessFramebuffer feature (render-pass-based
    // code such as UI backends) are required and enabled. Devices without them are unsuitable.
    bool graphics = false;
};

// What the chosen device offers. Optional features are enabled when present.
struct Capabilities {
    std::uint32_t api_version = 0;           // VK_MAKE_API_VERSION of the device
    bool storage_buffer_8bit = false;        // storageBuffer8BitAccess (uint8_t in SSBOs)
    bool storage_buffer_16bit = false;       // storageBuffer16BitAccess (float16_t/uint16_t in SSBOs)
    bool shader_float16 = false;             // float16_t arithmetic
    bool shader_int8 = false;
    bool shader_int16 = false;
    bool timeline_semaphore = false;         // host-signalled waits in SubmitInfo
    bool timestamps = false;                 // the queue family writes timestamps
    std::uint32_t timestamp_valid_bits = 0;
    double timestamp_period_ns = 0.0;        // nanoseconds per timestamp tick
    bool calibrated_timestamps = false;      // GPU and now_ns() clocks can be calibrated
    bool debug_utils = false;                // object names and labels reach debuggers
    bool graphics = false;                   // DeviceOptions::graphics: raster commands work
    std::uint32_t subgroup_size = 0;
    VkDeviceSize min_storage_buffer_offset_alignment = 0;
    VkDeviceSize min_uniform_buffer_offset_alignment = 0;
    VkDeviceSize min_texel_buffer_offset_alignment = 0;
    std::uint32_t max_uniform_buffer_range = 0;
    std::uint32_t max_storage_buffer_range = 0;
    std::uint32_t max_texel_buffer_elements = 0;
    std::uint32_t max_push_constants_size = 0;
    std::uint32_t max_compute_workgroup_invocations = 0;
    std::uint32_t max_compute_workgroup_size[3] = {};
    std::uint32_t max_compute_workgroup_count[3] = {};
};

// A wait on a semaphore before a submission runs (value: 0 for binary semaphores, the
// value to wait for on timeline semaphores).
struct SemaphoreWait {
    VkSemaphore semaphore = VK_NULL_HANDLE;
    std::uint64_t value = 0;
    VkPipelineStageFlags stages = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
};
struct SemaphoreSignal {
    VkSemaphore semaphore = VK_NULL_HANDLE;
    std::uint64_t value = 0; // 0 for binary semaphores
};
struct SubmitInfo {
    std::span<const SemaphoreWait> waits{};
    std::span<const SemaphoreSignal> signals{};
};

// A pair of simultaneous readings of the GPU timestamp clock and now_ns().
struct ClockCalibration {
    std::uint64_t gpu_ticks = 0;
    std::int64_t cpu_ns = 0;
    std::int64_t max_deviation_ns = 0; // the driver's bound on the pair's error
};

class Device {
  public:
    static Result<std::unique_ptr<Device>> create(const DeviceOptions& options = {});
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    // --- Identity ---------------------------------------------------------------------------
    const std::string& name() const { return name_; }
    DeviceType type() const { return type_; }
    std::uint32_t physical_device_index() const { return physical_index_; } // enumeration order
    const Capabilities& capabilities() const { return caps_; }
    // True when every bit of `features` is in the buffer features of `format`.
    bool supports_buffer_format(VkFormat format, VkFormatFeatureFlags features) const;

    // --- Resources (all VK_CHECKed: out of device memory aborts) ----------------------------
    Buffer create_buffer(const BufferDesc& desc);
    // A view of `buffer` as `format` texels. The buffer needs UNIFORM_TEXEL_BUFFER or
    // STORAGE_TEXEL_BUFFER usage; offset a multiple of min_texel_buffer_offset_alignment;
    // range (VK_WHOLE_SIZE: to the end, rounded down to whole texels) at most
    // max_texel_buffer_elements texels.
    BufferView create_buffer_view(const Buffer& buffer, VkFormat format, VkDeviceSize offset = 0,
                                  VkDeviceSize range = VK_WHOLE_SIZE, const char* name = nullptr);
    // Shares the Device's VkPipelineCache, so re-creating a pipeline with other
    // specialization constants is cheap on drivers that cache.
    ComputePipeline create_compute_pipeline(const ComputePipelineDesc& desc);
    // A 2D image with its view (see image.hpp). The format must support the usage as an
    // optimally tiled image (asserted: query supports_image_format first for optional ones).
    Image create_image(const ImageDesc& desc);
    // An Image of `image`, created elsewhere (swapchain images) with desc's size, format and
    // usage: the handle owns only its view; whoever created `image` destroys it, after the
    // handle.
    Image wrap_image(VkImage image, const ImageDesc& desc);
    Sampler create_sampler(const SamplerDesc& desc = {});
    // True when optimally tiled images of `format` have every bit of `features`.
    bool supports_image_format(VkFormat format, VkFormatFeatureFlags features) const;
    // Needs DeviceOptions::graphics (asserted).
    GraphicsPipeline create_graphics_pipeline(const GraphicsPipelineDesc& desc);
    // An error when the queue writes no timestamps (capabilities().timestamps).
    Result<TimestampQueries> create_timestamp_queries(std::uint32_t max_regions,
                                                      const char* name = nullptr);

    // --- Recording and submission -----------------------------------------------------------
    // A CommandList in the recording state. `name` labels the command buffer for debuggers.
    CommandList begin(const char* name = nullptr);
    // Ends and submits `list` (all labels closed) and returns its serial.
    std::uint64_t submit(CommandList&& list, const SubmitInfo& info = {});
    std::uint64_t last_submitted_serial() const { return last_submitted_; }
    // The highest serial the GPU has completed (all lower ones too). Polls, never blocks.
    std::uint64_t completed_serial();
    bool is_complete(std::uint64_t serial) { return serial <= completed_serial(); }
    // Blocks until `serial` (<= last_submitted_serial()) completed, then collects.
    void wait(std::uint64_t serial);
    void wait_idle();
    // Frees the queued objects whose submissions completed.
    void collect();
    // Destroyed handles whose objects are not freed yet (a TimestampQueries counts twice:
    // its query pool and its results buffer).
    std::size_t pending_deletions() const;
    // Bytes of device memory this Device has allocated and not yet freed (buffers and images;
    // memory of destroyed objects counts until deferred destruction frees it). What a soak
    // samples to show that the GPU side does not grow.
    std::uint64_t memory_allocated() const;
    std::size_t submissions_in_flight() const { return in_flight_.size(); }

    // --- Transfers (convenience; see docs/gpu.md for the per-frame pattern) ----------------
    // Writes `bytes` at `offset` of dst. Host-visible buffers: a memcpy now (no submission
    // still running may use the range; returns the completed serial). Device-local: a
    // staging copy in its own submission, ordered after earlier work and ending with a
    // transfer->compute/transfer barrier; returns that serial (no wait).
    std::uint64_t upload(const Buffer& dst, std::span<const std::byte> bytes,
                         VkDeviceSize offset = 0);
    // Blocking: waits for all submitted work, copies [offset, offset + size) out of src
    // (VK_WHOLE_SIZE = to the end). For tests and tools, not for frames.
    std::vector<std::byte> read_back(const Buffer& src, VkDeviceSize offset = 0,
                                     VkDeviceSize size = VK_WHOLE_SIZE);
    // Writes the whole colour image `dst` from tightly packed rows (top row first,
    // width * height * image_texel_size bytes) in its own submission, ordered after earlier
    // work; the image's old contents are discarded and it is left in `final_layout` (e.g.
    // SHADER_READ_ONLY_OPTIMAL for textures). Returns the serial (no wait).
    std::uint64_t upload(const Image& dst, std::span<const std::byte> texels,
                         VkImageLayout final_layout);
    // Blocking: waits for all submitted work and returns the whole image (its depth aspect
    // for depth formats) as tightly packed rows, top row first. `layout` is the layout the
    // image is in; it is left in it. For tests, screenshots and tools, not for frames.
    std::vector<std::byte> read_back(const Image& src, VkImageLayout layout);

    // Deferred destruction of a framebuffer created outside engine::gpu on vk_device() (by
    // render-pass-based code such as a UI backend), under the rule handles follow.
    void destroy_deferred(VkFramebuffer framebuffer);

    // --- Clocks -----------------------------------------------------------------------------
    // A fresh calibration, or nullopt without calibrated_timestamps.
    std::optional<ClockCalibration> calibrate_clocks() const;

    // --- Validation -------------------------------------------------------------------------
    bool validation_enabled() const { return validation_ != nullptr; }
    std::uint64_t validation_message_count() const;
    std::vector<std::string> validation_messages() const;
    void clear_validation_messages();

    // --- Raw handles, for interop (swapchains, tools). Do not destroy them. ---------------
    VkInstance vk_instance() const { return instance_; }
    VkPhysicalDevice vk_physical_device() const { return physical_; }
    VkDevice vk_device() const { return device_; }
    VkQueue vk_queue() const { return queue_; }
    std::uint32_t queue_family() const { return queue_family_; }

  private:
    // Implementation state, defined in src/device_internal.hpp.
    struct Dispatch;
    struct Validation;
    struct Retired;
    struct Deletions;
    struct Context;
    friend class Buffer;
    friend class BufferView;
    friend class ComputePipeline;
    friend class GraphicsPipeline;
    friend class Image;
    friend class Sampler;
    friend class CommandList;
    friend class TimestampQueries;
    friend struct DeviceBuilder;

    Device();
    // Queues `objects` for freeing after every use of them has completed.
    void retire(const Retired& objects);
    // The same for objects the Device never counted as live (foreign objects).
    void queue_deletion(const Retired& objects);
    void count_live_object();
    // Records a vkAllocateMemory of `bytes` (destroy_retired subtracts it when freed).
    void count_memory(VkDeviceMemory memory, VkDeviceSize bytes);
    void discard(CommandList& list);
    void record_timestamp_copies(CommandList& list);
    void close_list(std::uint64_t list_id);
    std::uint32_t acquire_context();
    void recycle_completed();
    void set_object_name(VkObjectType type, std::uint64_t handle, const char* name) const;
    void destroy_retired(const Retired& objects);

    // Identity
    std::string name_;
    DeviceType type_ = DeviceType::other;
    std::uint32_t physical_index_ = 0;
    Capabilities caps_;

    // Vulkan objects
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::uint32_t queue_family_ = 0;
    VkPipelineCache pipeline_cache_ = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memory_properties_{};
    std::unique_ptr<Dispatch> dispatch_;
    std::unique_ptr<Validation> validation_;

    // Submission state (submission thread)
    std::vector<std::unique_ptr<Context>> contexts_;
    std::vector<std::uint32_t> free_contexts_;
    std::vector<std::uint32_t> in_flight_; // context indices, oldest first
    std::uint64_t last_submitted_ = 0;
    std::uint64_t completed_ = 0;
    std::uint64_t next_list_id_ = 1;

    // Deferred destruction (any thread)
    std::unique_ptr<Deletions> deletions_;
};

} // namespace lantern::gpu
