// Swapchain: surface checks, (re)creation, acquire/present with two frames in flight.
#include "lantern/render/swapchain.hpp"

#include "lantern/core/log.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/gpu/vk_check.hpp"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace lantern::render {

namespace {

// The swapchain images are cleared and blitted into (record_upscale) and drawn on (overlays).
constexpr VkImageUsageFlags image_usage =
    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
// Where a frame first touches its swapchain image: the acquire semaphore is waited there,
// so work before it in the frame (GI compute) does not wait for the display.
constexpr VkPipelineStageFlags image_wait_stages =
    VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;

template <typename T, typename Query>
std::vector<T> enumerate(Query query) {
    std::uint32_t count = 0;
    VK_CHECK(query(&count, nullptr));
    std::vector<T> out(count);
    if (count > 0) VK_CHECK(query(&count, out.data()));
    out.resize(count);
    return out;
}

VkSemaphore create_semaphore(VkDevice device) {
    VkSemaphoreCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
    VkSemaphore semaphore = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSemaphore(device, &info, nullptr, &semaphore));
    return semaphore;
}

VkCompositeAlphaFlagBitsKHR choose_composite_alpha(VkCompositeAlphaFlagsKHR supported) {
    for (VkCompositeAlphaFlagBitsKHR bit :
         {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
          VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR, VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR}) {
        if (supported & bit) return bit;
    }
    return VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
}

bool has_format(std::span<const VkSurfaceFormatKHR> available, VkFormat format) {
    return std::any_of(available.begin(), available.end(), [&](const VkSurfaceFormatKHR& f) {
        return f.format == format && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    });
}

} // namespace

// --- Pure choices ----------------------------------------------------------------------------

Result<void> add_presentation(gpu::DeviceOptions& options, const platform::Window& window) {
    auto extensions = window.vulkan_instance_extensions();
    if (!extensions) return extensions.error();
    options.graphics = true;
    options.instance_extensions.insert(options.instance_extensions.end(), extensions->begin(),
                                       extensions->end());
    options.device_extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    return {};
}

VkPresentModeKHR choose_present_mode(std::span<const VkPresentModeKHR> available, bool vsync) {
    auto offered = [&](VkPresentModeKHR mode) {
        return std::find(available.begin(), available.end(), mode) != available.end();
    };
    if (!vsync) {
        if (offered(VK_PRESENT_MODE_MAILBOX_KHR)) return VK_PRESENT_MODE_MAILBOX_KHR;
        if (offered(VK_PRESENT_MODE_IMMEDIATE_KHR)) return VK_PRESENT_MODE_IMMEDIATE_KHR;
    }
    return VK_PRESENT_MODE_FIFO_KHR; // every implementation offers it
}

VkSurfaceFormatKHR choose_surface_format(std::span<const VkSurfaceFormatKHR> available, bool srgb) {
    LANTERN_ASSERT(!available.empty(),
                   "render::choose_surface_format: the surface offers no format");
    const std::array<VkFormat, 2> wanted_srgb = {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB};
    const std::array<VkFormat, 2> wanted_unorm = {VK_FORMAT_B8G8R8A8_UNORM,
                                                  VK_FORMAT_R8G8B8A8_UNORM};
    for (const auto& candidates :
         {srgb ? wanted_srgb : wanted_unorm, srgb ? wanted_unorm : wanted_srgb}) {
        for (VkFormat format : candidates) {
            if (has_format(available, format)) return {format, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR};
        }
    }
    return available.front();
}

VkExtent2D choose_extent(const VkSurfaceCapabilitiesKHR& caps, platform::Extent framebuffer) {
    if (caps.currentExtent.width != UINT32_MAX) return caps.currentExtent;
    return {std::clamp(framebuffer.width, caps.minImageExtent.width, caps.maxImageExtent.width),
            std::clamp(framebuffer.height, caps.minImageExtent.height, caps.maxImageExtent.height)};
}

std::uint32_t choose_image_count(const VkSurfaceCapabilitiesKHR& caps) {
    const std::uint32_t count = caps.minImageCount + 1;
    return caps.maxImageCount > 0 ? std::min(count, caps.maxImageCount) : count;
}

// --- State -------------------------------------------------------------------------------------

struct Swapchain::State {
    gpu::Device* device = nullptr;
    platform::Surface surface;
    SwapchainDesc desc;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    VkSurfaceFormatKHR format{};
    VkPresentModeKHR present_mode = VK_PRESENT_MODE_FIFO_KHR;
    VkExtent2D extent{};
    platform::Extent requested{}; // the framebuffer size the swapchain was made for
    bool made_with_vsync = true;  // desc.vsync when it was made
    std::vector<gpu::Image> images;
    std::vector<VkSemaphore> render_finished; // one per image: present waits for its frame
    std::array<VkSemaphore, frames_in_flight> image_acquired{};
    std::array<std::uint64_t, frames_in_flight> slot_serial{};
    std::uint32_t slot = 0;
    bool out_of_date = false;
    bool frame_open = false;
    std::uint64_t generation = 0;

    State() = default;
    State(const State&) = delete;
    State& operator=(const State&) = delete;
    ~State() {
        if (!device) return;
        device->wait_idle();
        release_images();
        // Guarded: without VK_KHR_swapchain (a failed create) the entry point is missing.
        if (swapchain) vkDestroySwapchainKHR(device->vk_device(), swapchain, nullptr);
        for (VkSemaphore semaphore : image_acquired)
            vkDestroySemaphore(device->vk_device(), semaphore, nullptr);
        // The surface goes after its swapchain (member destruction follows this body).
    }

    Result<void> check_surface();
    bool needs_recreation(platform::Extent framebuffer) const;
    bool recreate(platform::Extent framebuffer);
    void adopt_images();
    void release_images();
};

// Checks what presentation needs and picks the format (fixed for the surface's life).
Result<void> Swapchain::State::check_surface() {
    const VkPhysicalDevice physical = device->vk_physical_device();
    if (!vkGetDeviceProcAddr(device->vk_device(), "vkCreateSwapchainKHR"))
        return make_error("render::Swapchain: the Device lacks VK_KHR_swapchain (create it with "
                          "render::add_presentation)");
    if (!device->capabilities().graphics)
        return make_error(
            "render::Swapchain: the Device was created without DeviceOptions::graphics");
    VkBool32 supported = VK_FALSE;
    VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(physical, device->queue_family(), surface.vk(),
                                                  &supported));
    if (!supported)
        return make_error("render::Swapchain: queue family " +
                          std::to_string(device->queue_family()) + " of '" + device->name() +
                          "' cannot present to this surface");
    VkSurfaceCapabilitiesKHR caps{};
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface.vk(), &caps));
    if ((caps.supportedUsageFlags & image_usage) != image_usage)
        return make_error(
            "render::Swapchain: the surface's images cannot be transfer destinations and "
            "colour attachments");
    const auto formats =
        enumerate<VkSurfaceFormatKHR>([&](std::uint32_t* n, VkSurfaceFormatKHR* out) {
            return vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface.vk(), n, out);
        });
    if (formats.empty()) return make_error("render::Swapchain: the surface offers no format");
    format = choose_surface_format(formats, desc.srgb);
    if (!device->supports_image_format(format.format, VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                                          VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT))
        return make_error("render::Swapchain: the surface format cannot be a blit destination");
    return {};
}

bool Swapchain::State::needs_recreation(platform::Extent framebuffer) const {
    return !swapchain || out_of_date || framebuffer != requested || made_with_vsync != desc.vsync;
}

// Makes a swapchain for `framebuffer`; false (and no swapchain change) when the surface is
// empty, i.e. minimised.
bool Swapchain::State::recreate(platform::Extent framebuffer) {
    const VkPhysicalDevice physical = device->vk_physical_device();
    VkSurfaceCapabilitiesKHR caps{};
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface.vk(), &caps));
    const VkExtent2D size = choose_extent(caps, framebuffer);
    if (size.width == 0 || size.height == 0) return false;
    const auto modes = enumerate<VkPresentModeKHR>([&](std::uint32_t* n, VkPresentModeKHR* out) {
        return vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface.vk(), n, out);
    });

    VkSwapchainCreateInfoKHR info{};
    info.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
    info.surface = surface.vk();
    info.minImageCount = choose_image_count(caps);
    info.imageFormat = format.format;
    info.imageColorSpace = format.colorSpace;
    info.imageExtent = size;
    info.imageArrayLayers = 1;
    info.imageUsage = image_usage;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = choose_composite_alpha(caps.supportedCompositeAlpha);
    info.presentMode = choose_present_mode(modes, desc.vsync);
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSwapchainKHR(device->vk_device(), &info, nullptr, &created));

    // Frames in flight may still use the old images: wait, then retire them.
    device->wait_idle();
    release_images();
    if (swapchain) vkDestroySwapchainKHR(device->vk_device(), swapchain, nullptr);
    swapchain = created;
    present_mode = info.presentMode;
    made_with_vsync = desc.vsync;
    extent = size;
    requested = framebuffer;
    out_of_date = false;
    ++generation;
    adopt_images();
    LANTERN_LOG_DEBUG("render: swapchain %llu: %ux%u, %zu images, present mode %d",
                      static_cast<unsigned long long>(generation), size.width, size.height,
                      images.size(), static_cast<int>(present_mode));
    return true;
}

void Swapchain::State::adopt_images() {
    const VkDevice vk_device = device->vk_device();
    const auto handles = enumerate<VkImage>([&](std::uint32_t* n, VkImage* out) {
        return vkGetSwapchainImagesKHR(vk_device, swapchain, n, out);
    });
    for (VkImage handle : handles) {
        images.push_back(device->wrap_image(
            handle, {extent.width, extent.height, format.format, image_usage, "swapchain image"}));
        render_finished.push_back(create_semaphore(vk_device));
    }
}

// Only after the GPU is idle: the semaphores are destroyed at once.
void Swapchain::State::release_images() {
    images.clear(); // views: deferred, freed by the next collect
    device->collect();
    for (VkSemaphore semaphore : render_finished)
        vkDestroySemaphore(device->vk_device(), semaphore, nullptr);
    render_finished.clear();
}

// --- Swapchain ---------------------------------------------------------------------------------

Result<Swapchain> Swapchain::create(gpu::Device& device, platform::Surface surface,
                                    platform::Extent framebuffer_size, const SwapchainDesc& desc) {
    LANTERN_ASSERT(surface, "render::Swapchain::create without a surface");
    auto state = std::make_unique<State>();
    state->device = &device;
    state->surface = std::move(surface);
    state->desc = desc;
    if (auto ok = state->check_surface(); !ok) return ok.error();
    for (VkSemaphore& semaphore : state->image_acquired)
        semaphore = create_semaphore(device.vk_device());
    if (!framebuffer_size.empty()) state->recreate(framebuffer_size);
    return Swapchain(std::move(state));
}

Swapchain::Swapchain(std::unique_ptr<State> state) : state_(std::move(state)) {}
Swapchain::Swapchain(Swapchain&& other) noexcept = default;
Swapchain& Swapchain::operator=(Swapchain&& other) noexcept = default;
Swapchain::~Swapchain() = default;

std::optional<SwapchainFrame> Swapchain::acquire(platform::Extent framebuffer_size) {
    State& s = *state_;
    LANTERN_ASSERT(!s.frame_open,
                   "render::Swapchain::acquire before the previous frame was presented");
    if (framebuffer_size.empty()) return std::nullopt;
    if (s.slot_serial[s.slot] != 0) s.device->wait(s.slot_serial[s.slot]);
    if (s.needs_recreation(framebuffer_size) && !s.recreate(framebuffer_size)) return std::nullopt;
    // Out of date between the check and the acquire (a resize in flight): recreate once more.
    for (int attempt = 0; attempt < 2; ++attempt) {
        std::uint32_t index = 0;
        const VkResult result =
            vkAcquireNextImageKHR(s.device->vk_device(), s.swapchain, UINT64_MAX,
                                  s.image_acquired[s.slot], VK_NULL_HANDLE, &index);
        if (result == VK_ERROR_OUT_OF_DATE_KHR) {
            if (!s.recreate(framebuffer_size)) return std::nullopt;
            continue;
        }
        if (result == VK_SUBOPTIMAL_KHR)
            s.out_of_date = true; // still presentable: use it, then recreate
        else
            VK_CHECK(result);
        SwapchainFrame frame;
        frame.image_ = &s.images[index];
        frame.image_index_ = index;
        frame.slot_ = s.slot;
        s.frame_open = true;
        return frame;
    }
    return std::nullopt;
}

std::uint64_t Swapchain::present(SwapchainFrame&& frame, gpu::CommandList&& cmd) {
    State& s = *state_;
    LANTERN_ASSERT(s.frame_open && frame.slot_ == s.slot &&
                       frame.image_ == &s.images[frame.image_index_],
                   "render::Swapchain::present of a frame this swapchain did not just acquire");
    const gpu::SemaphoreWait wait{s.image_acquired[s.slot], 0, image_wait_stages};
    const gpu::SemaphoreSignal signal{s.render_finished[frame.image_index_], 0};
    const std::uint64_t serial = s.device->submit(std::move(cmd), {{&wait, 1}, {&signal, 1}});
    s.slot_serial[s.slot] = serial;

    VkPresentInfoKHR info{};
    info.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &signal.semaphore;
    info.swapchainCount = 1;
    info.pSwapchains = &s.swapchain;
    info.pImageIndices = &frame.image_index_;
    const VkResult result = vkQueuePresentKHR(s.device->vk_queue(), &info);
    // Out of date: the semaphore wait still happened; recreate before the next acquire.
    if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR)
        s.out_of_date = true;
    else
        VK_CHECK(result);
    s.frame_open = false;
    s.slot = (s.slot + 1) % frames_in_flight;
    return serial;
}

void Swapchain::set_vsync(bool vsync) {
    state_->desc.vsync = vsync;
}
bool Swapchain::vsync() const {
    return state_->desc.vsync;
}
VkPresentModeKHR Swapchain::present_mode() const {
    return state_->present_mode;
}
VkFormat Swapchain::format() const {
    return state_->format.format;
}
VkExtent2D Swapchain::extent() const {
    return state_->extent;
}
std::uint32_t Swapchain::image_count() const {
    return static_cast<std::uint32_t>(state_->images.size());
}
std::uint64_t Swapchain::generation() const {
    return state_->generation;
}

} // namespace lantern::render
