// Dear ImGui (1.86) drawn over a finished image at full resolution: the HUD of windowed
// mode, crisp on top of the upscaled pixel art. Wraps ImGui's GLFW and Vulkan backends.
//
//   auto overlay = render::ImGuiOverlay::create(device, {.format = swapchain.format(),
//                                                        .window = &window});
//   overlay->new_frame();                                 // after window.poll()
//   ImGui::Text("frame %.2f ms", ms);                     // any ImGui calls
//   record_upscale(cmd, target.color(), frame->image(), rect,
//                  VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
//   overlay->record(cmd, frame->image());                 // leaves it in PRESENT_SRC_KHR
//
// ImGui 1.86's Vulkan backend predates dynamic rendering: it needs a VkRenderPass. The
// overlay owns one (one colour attachment, loaded and stored, COLOR_ATTACHMENT_OPTIMAL in,
// desc.final_layout out) and one imageless framebuffer per target size, so swapchain images
// need no framebuffers of their own and recreation costs nothing here.
//
// Input: with a window, ImGui's GLFW backend chains its callbacks after the Window's, so
// the game's InputState still sees everything; wants_mouse()/wants_keyboard() tell the game
// when ImGui is using the input. Without a window (headless, tests) new_frame takes the
// display size and ImGui gets no input.
//
// ImGui has one global context and its backends are global: at most one overlay exists at a
// time (asserted). Its per-frame vertex buffers are reused every third record(), so record
// at most once per submitted frame and keep at most two frames in flight (the Swapchain's
// rule); record() waits for the frame two records back to be safe headless.
//
// Ownership: destroy it before the Device and the Window; destruction waits for the GPU
// (ImGui's backend frees its objects at once). Threads: the main thread (GLFW, ImGui).
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/platform/window.hpp"

#include <vulkan/vulkan.h>

#include <memory>

namespace lantern::gpu {
class CommandList;
class Device;
class Image;
} // namespace lantern::gpu

namespace lantern::render {

struct ImGuiOverlayDesc {
    VkFormat format = VK_FORMAT_UNDEFINED; // the targets' format (the swapchain's)
    // Where record() leaves the target: PRESENT_SRC_KHR for swapchain images,
    // TRANSFER_SRC_OPTIMAL to read it back.
    VkImageLayout final_layout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    const platform::Window* window = nullptr; // input and display size; nullptr: headless
};

class ImGuiOverlay {
  public:
    // An error when an overlay already exists or ImGui's backends fail to initialise.
    static Result<ImGuiOverlay> create(gpu::Device& device, const ImGuiOverlayDesc& desc);
    ImGuiOverlay(ImGuiOverlay&& other) noexcept;
    ImGuiOverlay& operator=(ImGuiOverlay&& other) noexcept;
    ImGuiOverlay(const ImGuiOverlay&) = delete;
    ImGuiOverlay& operator=(const ImGuiOverlay&) = delete;
    ~ImGuiOverlay();

    // Starts an ImGui frame (ImGui::NewFrame): every ImGui call of the frame comes after.
    // `display_size` (pixels) is used headless; with a window, the window's size is.
    void new_frame(platform::Extent display_size = {});
    // Ends the ImGui frame (ImGui::Render) and records its draws into `target` (in
    // COLOR_ATTACHMENT_OPTIMAL, contents kept; the desc's format; the size new_frame used),
    // leaving it in desc.final_layout. Records raw commands into cmd: bind pipelines again
    // before later draws.
    void record(gpu::CommandList& cmd, const gpu::Image& target);

    bool wants_mouse() const;    // ImGui uses the mouse (over a window): keep it from the game
    bool wants_keyboard() const; // a text field has the focus

  private:
    struct State;
    explicit ImGuiOverlay(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

} // namespace lantern::render
