// The window's swapchain: image acquisition and presentation with at most two frames in
// flight, recreation on resize, on VK_ERROR_OUT_OF_DATE_KHR / VK_SUBOPTIMAL_KHR and on a
// vsync change, and minimised windows (nothing to present: the frame is skipped).
//
//   gpu::DeviceOptions options;
//   if (auto ok = render::add_presentation(options, window); !ok) return ok.error();
//   auto device = gpu::Device::create(options);
//   auto surface = window.create_surface(**device);
//   auto swapchain = render::Swapchain::create(**device, std::move(*surface),
//                                              window.framebuffer_size(), {.vsync = true});
//   while (...) {
//       window.poll();
//       auto frame = swapchain->acquire(window.framebuffer_size());
//       if (!frame) { window.poll_wait(0.1); continue; }  // minimised
//       gpu::CommandList cmd = device->begin("frame");
//       ... record; leave frame->image() in PRESENT_SRC_KHR ...
//       swapchain->present(std::move(*frame), std::move(cmd));
//   }
//
// Frames in flight: each frame uses one of two slots (an acquire semaphore and the serial of
// its submission). acquire() first waits for the submission made two frames ago, so the CPU
// never runs more than two frames ahead and per-frame resources can be reused after that
// wait. A render-finished semaphore per swapchain image orders present after the frame.
//
// Recreation waits for the GPU to go idle (resizes are rare; in-flight frames still use the
// old images) and re-wraps the new images; the Image references of earlier frames are then
// stale. Every acquired frame must be presented (asserted): an acquired image cannot be
// given back.
//
// Ownership: the Swapchain owns the Surface. Destroy it before the Device and the Window;
// destruction waits for the GPU. Threads: the submission thread of the Device.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gpu/image.hpp"
#include "lantern/platform/window.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>

namespace lantern::gpu {
class CommandList;
class Device;
struct DeviceOptions;
} // namespace lantern::gpu

namespace lantern::render {

// Adds what presenting to `window` needs to device options: DeviceOptions::graphics, the
// window's instance extensions and VK_KHR_swapchain. An error (options unchanged) when the
// window system has no Vulkan surface support.
Result<void> add_presentation(gpu::DeviceOptions& options, const platform::Window& window);

struct SwapchainDesc {
    bool vsync = true; // FIFO; off: MAILBOX, else IMMEDIATE, else FIFO (always available)
    bool srgb = true;  // prefer an *_SRGB format (else *_UNORM): match the render target's
};

// The present mode for `vsync` among `available` (see SwapchainDesc::vsync).
VkPresentModeKHR choose_present_mode(std::span<const VkPresentModeKHR> available, bool vsync);
// B8G8R8A8 or R8G8B8A8 in the wanted encoding with the sRGB colour space, else the other
// encoding, else the first format offered.
VkSurfaceFormatKHR choose_surface_format(std::span<const VkSurfaceFormatKHR> available, bool srgb);
// The surface's current extent, or (when the surface lets the swapchain decide) the
// framebuffer size clamped to the surface's limits.
VkExtent2D choose_extent(const VkSurfaceCapabilitiesKHR& caps, platform::Extent framebuffer);
// One image more than the minimum (the CPU can record while the GPU and the display hold
// the others), within the maximum.
std::uint32_t choose_image_count(const VkSurfaceCapabilitiesKHR& caps);

// One acquired swapchain image, to be presented with Swapchain::present.
class SwapchainFrame {
  public:
    // The swapchain image: contents undefined at acquire (transition from UNDEFINED); it
    // must be in PRESENT_SRC_KHR when the frame's commands end. COLOR_ATTACHMENT and
    // TRANSFER_DST usage.
    const gpu::Image& image() const { return *image_; }
    std::uint32_t image_index() const { return image_index_; }
    std::uint32_t slot() const { return slot_; } // frame-in-flight slot, 0 or 1

  private:
    friend class Swapchain;
    const gpu::Image* image_ = nullptr;
    std::uint32_t image_index_ = 0;
    std::uint32_t slot_ = 0;
};

class Swapchain {
  public:
    static constexpr std::uint32_t frames_in_flight = 2;

    // An error when the device's queue cannot present to `surface`, when the surface lacks
    // the usages or formats presentation needs, or when the device was created without
    // add_presentation. An empty framebuffer_size (minimised) is fine: the swapchain is
    // made at the first acquire with a size.
    static Result<Swapchain> create(gpu::Device& device, platform::Surface surface,
                                    platform::Extent framebuffer_size,
                                    const SwapchainDesc& desc = {});
    Swapchain(Swapchain&& other) noexcept;
    Swapchain& operator=(Swapchain&& other) noexcept;
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;
    ~Swapchain();

    // Waits for the frame slot's previous submission, recreates the swapchain when needed
    // (size differs from framebuffer_size, out of date, suboptimal, vsync changed) and
    // acquires the next image. nullopt when there is nothing to present to: the framebuffer
    // or the surface is empty (minimised); then nothing was acquired, skip the frame.
    std::optional<SwapchainFrame> acquire(platform::Extent framebuffer_size);
    // Submits `cmd` (waiting for the image at the transfer and colour-output stages) and
    // presents the frame's image. Returns the submission's serial. An out-of-date or
    // suboptimal present schedules a recreation at the next acquire.
    std::uint64_t present(SwapchainFrame&& frame, gpu::CommandList&& cmd);

    // Takes effect at the next acquire (the swapchain is recreated with the new mode).
    void set_vsync(bool vsync);
    bool vsync() const;
    VkPresentModeKHR present_mode() const;
    VkFormat format() const;
    VkExtent2D extent() const; // {0, 0} before the first swapchain exists
    std::uint32_t image_count() const;
    // How many VkSwapchainKHRs were created so far (1 after the first; +1 per recreation).
    std::uint64_t generation() const;

  private:
    struct State;
    explicit Swapchain(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

} // namespace lantern::render
