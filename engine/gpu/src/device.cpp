// Device: submission contexts, serials, deferred destruction, validation messages.
#include "device_internal.hpp"

#include "lantern/core/clock.hpp"
#include "lantern/core/log.hpp"
#include "lantern/gpu/vk_check.hpp"

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace lantern::gpu {

// --- Validation messages -----------------------------------------------------------------

VKAPI_ATTR VkBool32 VKAPI_CALL Device::Validation::callback(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT /*types*/,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    // The messenger only asks for warnings and errors; filter anyway, the contract says so.
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT || !user) return VK_FALSE;
    auto& v = *static_cast<Validation*>(user);
    const bool error = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    const char* text = data && data->pMessage ? data->pMessage : "(no message)";
    {
        std::lock_guard lock(v.mutex);
        ++v.count;
        if (v.messages.size() < max_kept) v.messages.emplace_back(text);
    }
    if (v.log) {
        if (error) LANTERN_LOG_ERROR("vulkan: %s", text);
        else LANTERN_LOG_WARN("vulkan: %s", text);
    }
    if (error && v.abort_on_error) std::abort();
    return VK_FALSE; // never make the call itself fail
}

std::uint64_t Device::validation_message_count() const {
    if (!validation_) return 0;
    std::lock_guard lock(validation_->mutex);
    return validation_->count;
}

std::vector<std::string> Device::validation_messages() const {
    if (!validation_) return {};
    std::lock_guard lock(validation_->mutex);
    return validation_->messages;
}

void Device::clear_validation_messages() {
    if (!validation_) return;
    std::lock_guard lock(validation_->mutex);
    validation_->count = 0;
    validation_->messages.clear();
}

// --- Life ----------------------------------------------------------------------------------

Device::Device() : dispatch_(std::make_unique<Dispatch>()), deletions_(std::make_unique<Deletions>()) {}

Device::~Device() {
    if (device_) {
        VK_CHECK(vkDeviceWaitIdle(device_));
        recycle_completed();
        std::vector<Deletions::Entry> entries;
        {
            std::lock_guard lock(deletions_->mutex);
            LANTERN_ASSERT(deletions_->live_objects == 0,
                           "gpu::Device destroyed while resources created by it are alive");
            LANTERN_ASSERT(deletions_->open_lists.empty(),
                           "gpu::Device destroyed while a CommandList is being recorded");
            entries = std::move(deletions_->entries);
            deletions_->entries.clear();
        }
        for (const auto& entry : entries) destroy_retired(entry.objects); // takes the lock
        for (const auto& context : contexts_) {
            vkDestroyFence(device_, context->fence, nullptr);
            vkDestroyCommandPool(device_, context->pool, nullptr);
        }
        vkDestroyPipelineCache(device_, pipeline_cache_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_ && dispatch_->destroy_messenger)
        dispatch_->destroy_messenger(instance_, messenger_, nullptr);
    if (instance_) vkDestroyInstance(instance_, nullptr);
    // validation_ dies after the instance: vkDestroyInstance may still report through it.
}

bool Device::supports_buffer_format(VkFormat format, VkFormatFeatureFlags features) const {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(physical_, format, &props);
    return (props.bufferFeatures & features) == features;
}

void Device::set_object_name(VkObjectType type, std::uint64_t handle, const char* name) const {
    if (!name || !dispatch_->set_object_name) return;
    auto info = vk_struct<VkDebugUtilsObjectNameInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT);
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name;
    VK_CHECK(dispatch_->set_object_name(device_, &info));
}

// --- Deferred destruction --------------------------------------------------------------------

void Device::count_live_object() {
    std::lock_guard lock(deletions_->mutex);
    ++deletions_->live_objects;
}

void Device::count_memory(VkDeviceMemory memory, VkDeviceSize bytes) {
    std::lock_guard lock(deletions_->mutex);
    deletions_->memory_sizes.emplace(memory, bytes);
    deletions_->memory_bytes += bytes;
}

std::uint64_t Device::memory_allocated() const {
    std::lock_guard lock(deletions_->mutex);
    return deletions_->memory_bytes;
}

void Device::retire(const Retired& objects) {
    {
        std::lock_guard lock(deletions_->mutex);
        LANTERN_ASSERT(deletions_->live_objects > 0, "gpu: more resources destroyed than created");
        --deletions_->live_objects;
    }
    queue_deletion(objects);
}

void Device::destroy_deferred(VkFramebuffer framebuffer) {
    if (!framebuffer) return;
    Retired retired;
    retired.framebuffer = framebuffer;
    queue_deletion(retired);
}

void Device::queue_deletion(const Retired& objects) {
    std::lock_guard lock(deletions_->mutex);
    Deletions::Entry entry;
    entry.objects = objects;
    if (deletions_->open_lists.empty()) {
        entry.sealed = true;
        entry.serial = deletions_->last_submitted;
    } else {
        entry.newest_open_list = *deletions_->open_lists.rbegin();
    }
    deletions_->entries.push_back(entry);
}

void Device::close_list(std::uint64_t list_id) {
    std::lock_guard lock(deletions_->mutex);
    deletions_->last_submitted = last_submitted_;
    deletions_->open_lists.erase(list_id);
    const std::uint64_t oldest_open =
        deletions_->open_lists.empty() ? UINT64_MAX : *deletions_->open_lists.begin();
    for (auto& entry : deletions_->entries) {
        if (!entry.sealed && entry.newest_open_list < oldest_open) {
            entry.sealed = true;
            entry.serial = last_submitted_;
        }
    }
}

void Device::collect() {
    recycle_completed();
    std::vector<Retired> done;
    {
        std::lock_guard lock(deletions_->mutex);
        auto& entries = deletions_->entries;
        auto freeable = [&](const Deletions::Entry& e) { return e.sealed && e.serial <= completed_; };
        for (const auto& entry : entries) {
            if (freeable(entry)) done.push_back(entry.objects);
        }
        std::erase_if(entries, freeable);
    }
    for (const auto& objects : done) destroy_retired(objects);
}

std::size_t Device::pending_deletions() const {
    std::lock_guard lock(deletions_->mutex);
    return deletions_->entries.size();
}

void Device::destroy_retired(const Retired& o) {
    // Framebuffers before the views they name, views before their buffers and images,
    // memory last, pipelines before their layouts; null handles are ignored.
    vkDestroyFramebuffer(device_, o.framebuffer, nullptr);
    vkDestroyBufferView(device_, o.view, nullptr);
    vkDestroyImageView(device_, o.image_view, nullptr);
    vkDestroyBuffer(device_, o.buffer, nullptr);
    vkDestroyImage(device_, o.image, nullptr);
    if (o.memory) {
        vkFreeMemory(device_, o.memory, nullptr);
        std::lock_guard lock(deletions_->mutex);
        const auto it = deletions_->memory_sizes.find(o.memory);
        if (it != deletions_->memory_sizes.end()) {
            deletions_->memory_bytes -= it->second;
            deletions_->memory_sizes.erase(it);
        }
    }
    vkDestroySampler(device_, o.sampler, nullptr);
    vkDestroyPipeline(device_, o.pipeline, nullptr);
    vkDestroyPipelineLayout(device_, o.layout, nullptr);
    vkDestroyDescriptorSetLayout(device_, o.set_layout, nullptr);
    vkDestroyQueryPool(device_, o.query_pool, nullptr);
}

// --- Submission contexts -----------------------------------------------------------------------

std::uint32_t Device::acquire_context() {
    if (free_contexts_.empty()) recycle_completed();
    if (!free_contexts_.empty()) {
        const std::uint32_t index = free_contexts_.back();
        free_contexts_.pop_back();
        return index;
    }
    auto context = std::make_unique<Context>();
    auto pool_info = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    VK_CHECK(vkCreateCommandPool(device_, &pool_info, nullptr, &context->pool));
    auto alloc = vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    alloc.commandPool = context->pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(device_, &alloc, &context->cmd));
    auto fence_info = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    VK_CHECK(vkCreateFence(device_, &fence_info, nullptr, &context->fence));
    contexts_.push_back(std::move(context));
    return static_cast<std::uint32_t>(contexts_.size() - 1);
}

// Moves the completed prefix of in_flight_ back to the free list. A queue completes its
// submissions in order, so the first unsignalled fence ends the scan.
void Device::recycle_completed() {
    std::size_t done = 0;
    for (; done < in_flight_.size(); ++done) {
        Context& context = *contexts_[in_flight_[done]];
        const VkResult status = vkGetFenceStatus(device_, context.fence);
        if (status == VK_NOT_READY) break;
        VK_CHECK(status);
        VK_CHECK(vkResetFences(device_, 1, &context.fence));
        VK_CHECK(vkResetCommandPool(device_, context.pool, 0));
        completed_ = std::max(completed_, context.serial);
        free_contexts_.push_back(in_flight_[done]);
    }
    in_flight_.erase(in_flight_.begin(), in_flight_.begin() + static_cast<std::ptrdiff_t>(done));
}

std::uint64_t Device::completed_serial() {
    recycle_completed();
    return completed_;
}

void Device::wait(std::uint64_t serial) {
    LANTERN_ASSERT(serial <= last_submitted_, "gpu::Device::wait for a serial not submitted yet");
    std::vector<VkFence> fences;
    for (const std::uint32_t index : in_flight_) {
        if (contexts_[index]->serial > serial) break;
        fences.push_back(contexts_[index]->fence);
    }
    if (!fences.empty())
        VK_CHECK(vkWaitForFences(device_, static_cast<std::uint32_t>(fences.size()), fences.data(),
                                 VK_TRUE, UINT64_MAX));
    collect();
}

void Device::wait_idle() {
    VK_CHECK(vkDeviceWaitIdle(device_));
    collect();
}

// --- Recording and submission --------------------------------------------------------------

CommandList Device::begin(const char* name) {
    const std::uint32_t index = acquire_context();
    Context& context = *contexts_[index];
    auto info = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(context.cmd, &info));
    set_object_name(VK_OBJECT_TYPE_COMMAND_BUFFER, reinterpret_cast<std::uint64_t>(context.cmd), name);

    CommandList list;
    list.device_ = this;
    list.cmd_ = context.cmd;
    list.context_ = index;
    list.list_id_ = next_list_id_++;
    std::lock_guard lock(deletions_->mutex);
    deletions_->open_lists.insert(list.list_id_);
    return list;
}

namespace {

struct SubmitArrays {
    std::vector<VkSemaphore> wait_semaphores;
    std::vector<std::uint64_t> wait_values;
    std::vector<VkPipelineStageFlags> wait_stages;
    std::vector<VkSemaphore> signal_semaphores;
    std::vector<std::uint64_t> signal_values;

    explicit SubmitArrays(const SubmitInfo& info) {
        for (const auto& w : info.waits) {
            wait_semaphores.push_back(w.semaphore);
            wait_values.push_back(w.value);
            wait_stages.push_back(w.stages);
        }
        for (const auto& s : info.signals) {
            signal_semaphores.push_back(s.semaphore);
            signal_values.push_back(s.value);
        }
    }
};

} // namespace

std::uint64_t Device::submit(CommandList&& list, const SubmitInfo& info) {
    LANTERN_ASSERT(list.device_ == this && list.cmd_, "gpu::Device::submit of a list that is not recording");
    LANTERN_ASSERT(list.label_depth_ == 0, "gpu::Device::submit with an open debug label");
    LANTERN_ASSERT(!list.rendering_, "gpu::Device::submit inside a rendering scope");
    Context& context = *contexts_[list.context_];
    record_timestamp_copies(list);
    VK_CHECK(vkEndCommandBuffer(context.cmd));

    // Binary semaphores ignore their value; the timeline struct is valid for both kinds.
    const SubmitArrays arrays(info);
    auto timeline = vk_struct<VkTimelineSemaphoreSubmitInfo>(VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO);
    timeline.waitSemaphoreValueCount = static_cast<std::uint32_t>(arrays.wait_values.size());
    timeline.pWaitSemaphoreValues = arrays.wait_values.data();
    timeline.signalSemaphoreValueCount = static_cast<std::uint32_t>(arrays.signal_values.size());
    timeline.pSignalSemaphoreValues = arrays.signal_values.data();
    auto submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    if (!info.waits.empty() || !info.signals.empty()) submit.pNext = &timeline;
    submit.waitSemaphoreCount = static_cast<std::uint32_t>(arrays.wait_semaphores.size());
    submit.pWaitSemaphores = arrays.wait_semaphores.data();
    submit.pWaitDstStageMask = arrays.wait_stages.data();
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &context.cmd;
    submit.signalSemaphoreCount = static_cast<std::uint32_t>(arrays.signal_semaphores.size());
    submit.pSignalSemaphores = arrays.signal_semaphores.data();

    const std::int64_t submit_ns = now_ns();
    VK_CHECK(vkQueueSubmit(queue_, 1, &submit, context.fence));
    context.serial = ++last_submitted_;
    in_flight_.push_back(list.context_);
    for (const auto& ticket : list.tickets_) {
        ticket->serial = context.serial;
        ticket->submit_cpu_ns = submit_ns;
    }
    close_list(list.list_id_);
    list.release();
    collect();
    return context.serial;
}

// Appends the copies of the list's timestamp queries into their result buffers, so reading
// them later is a memcpy (vkGetQueryPoolResults may block on some drivers, see timestamps.hpp).
void Device::record_timestamp_copies(CommandList& list) {
    bool any = false;
    for (const auto& ticket : list.tickets_) {
        LANTERN_ASSERT(ticket->open_regions == 0, "gpu: submit with a timestamp region not ended");
        if (ticket->query_count == 0) continue;
        // WAIT: the copy waits for the queries' availability; no barrier is needed before it.
        vkCmdCopyQueryPoolResults(list.cmd_, ticket->pool, 0, ticket->query_count, ticket->results, 0,
                                  sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
        any = true;
    }
    if (any) list.barrier_to_host();
}

void Device::discard(CommandList& list) {
    // Resetting the pool returns the recording command buffer to the initial state.
    VK_CHECK(vkResetCommandPool(device_, contexts_[list.context_]->pool, 0));
    free_contexts_.push_back(list.context_);
    close_list(list.list_id_);
    list.release();
}

// --- Clocks ----------------------------------------------------------------------------------

std::optional<ClockCalibration> Device::calibrate_clocks() const {
    if (!dispatch_->get_calibrated_timestamps) return std::nullopt;
#if defined(__linux__)
    VkCalibratedTimestampInfoEXT infos[2] = {
        vk_struct<VkCalibratedTimestampInfoEXT>(VK_STRUCTURE_TYPE_CALIBRATED_TIMESTAMP_INFO_EXT),
        vk_struct<VkCalibratedTimestampInfoEXT>(VK_STRUCTURE_TYPE_CALIBRATED_TIMESTAMP_INFO_EXT)};
    infos[0].timeDomain = VK_TIME_DOMAIN_DEVICE_EXT;
    infos[1].timeDomain = VK_TIME_DOMAIN_CLOCK_MONOTONIC_EXT;
    std::uint64_t values[2] = {};
    std::uint64_t deviation = 0;
    VK_CHECK(dispatch_->get_calibrated_timestamps(device_, 2, infos, values, &deviation));
    ClockCalibration c;
    c.gpu_ticks = values[0];
    c.cpu_ns = static_cast<std::int64_t>(values[1]);
    c.max_deviation_ns = static_cast<std::int64_t>(deviation);
    return c;
#else
    return std::nullopt;
#endif
}

} // namespace lantern::gpu
