// Desktop windows for Vulkan rendering (GLFW): creation, per-frame event polling, window
// events, keyboard and mouse state, Vulkan surface creation; and the display probe that
// lets a game fall back to headless mode.
//
// Use:
//
//   if (auto display = platform::display_available(); !display)
//       return run_headless(display.reason);            // "no DISPLAY or WAYLAND_DISPLAY set"
//   auto window = platform::Window::create({.title = "Lantern", .width = 1280, .height = 720});
//   if (!window) return window.error();
//   auto extensions = window->vulkan_instance_extensions();  // render::add_presentation
//   if (!extensions) return extensions.error();             // does this and more
//   gpu::DeviceOptions options{.instance_extensions = *extensions, .graphics = true};
//   ...create the Device, then window->create_surface(device)...
//   while (!window->should_close()) {
//       window->poll();                                  // input edges and events of this frame
//       if (window->input().pressed(platform::Key::escape)) window->request_close();
//       ...
//   }
//
// Errors: creation and surface creation return lantern::Result with GLFW's or Vulkan's
// reason; they never crash. GLFW is initialised while a Window exists (reference counted)
// and terminated after the last one.
//
// Threads: GLFW allows windows and events on the main thread only, so every function here
// belongs to the thread that created the first Window (asserted where cheap).
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/platform/input.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

struct GLFWwindow;

namespace lantern::gpu {
class Device;
}

namespace lantern::platform {

namespace detail {
struct WindowState;
}

// Whether windows can be opened here, and if not, why.
struct DisplayProbe {
    bool available = false;
    std::string reason; // empty when available
    explicit operator bool() const { return available; }
};

// Checks for a display: DISPLAY or WAYLAND_DISPLAY set, GLFW initialises on it, and GLFW
// finds a Vulkan loader. Cheap (one connection to the display server) but not free: call it
// once at start-up.
DisplayProbe display_available();

struct Extent {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    bool empty() const { return width == 0 || height == 0; }
    friend bool operator==(const Extent&, const Extent&) = default;
};

enum class WindowEventType : std::uint8_t {
    resized,         // the framebuffer size changed (WindowEvent::size; {0, 0} when minimised)
    minimised,       // iconified
    restored,        // no longer iconified
    close_requested, // the user asked to close (should_close() is now true)
    focus_gained,
    focus_lost, // every key and button is released in the InputState
};

struct WindowEvent {
    WindowEventType type = WindowEventType::resized;
    Extent size{}; // the new framebuffer size, for resized
};

struct WindowDesc {
    std::string title = "Lantern";
    std::uint32_t width = 1280; // screen coordinates (pixels on X11)
    std::uint32_t height = 720;
    bool resizable = true;
};

// A VkSurfaceKHR of a Window on a Device's instance. Destroy it (and the swapchain using it)
// before that Device and that Window.
class Surface {
  public:
    Surface() = default;
    Surface(Surface&& other) noexcept;
    Surface& operator=(Surface&& other) noexcept;
    Surface(const Surface&) = delete;
    Surface& operator=(const Surface&) = delete;
    ~Surface();

    explicit operator bool() const { return surface_ != VK_NULL_HANDLE; }
    VkSurfaceKHR vk() const { return surface_; }

  private:
    friend class Window;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
};

class Window {
  public:
    // Opens a visible window with no client API (Vulkan renders into it). An error when
    // there is no display, GLFW cannot initialise, or it finds no Vulkan loader.
    static Result<Window> create(const WindowDesc& desc = {});
    Window(Window&& other) noexcept;
    Window& operator=(Window&& other) noexcept;
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;
    ~Window();

    // --- Per frame ----------------------------------------------------------------------------
    // Starts a frame: clears last frame's events and input edges, then processes every
    // pending event (GLFW polls every window at once: with several windows, poll any one).
    void poll();
    // As poll(), but sleeps until an event arrives or `timeout_seconds` pass (a minimised
    // game has nothing to draw).
    void poll_wait(double timeout_seconds);
    // This frame's window events, in arrival order.
    std::span<const WindowEvent> events() const;
    const InputState& input() const;

    // --- State --------------------------------------------------------------------------------
    bool should_close() const;
    void request_close();
    // Takes a close request back (the game asks first when there is something unsaved).
    void cancel_close();
    Extent framebuffer_size() const; // pixels; {0, 0} while minimised
    Extent window_size() const;      // screen coordinates
    bool minimised() const;
    // False while the window is unmapped: hidden, or unmapped by the window system (another
    // workspace, some window managers' minimise). Asks the window system each call.
    bool visible() const;
    bool focused() const;
    void set_title(const std::string& title);
    // Asks for a new size in screen coordinates; the window system answers asynchronously
    // (a resized event during a later poll).
    void set_size(Extent size);

    // --- Vulkan -------------------------------------------------------------------------------
    // The instance extensions a Device needs to present to this window (VK_KHR_surface and
    // the platform's). The strings live as long as GLFW stays initialised (this Window). An
    // error when the Vulkan loader offers none for this window system (e.g. no driver).
    Result<std::vector<const char*>> vulkan_instance_extensions() const;
    // A surface on `device`'s instance. An error when the instance lacks the extensions above
    // or the window system refuses.
    Result<Surface> create_surface(const gpu::Device& device) const;

    // The GLFW window, for libraries that take one (the ImGui GLFW backend). Do not destroy
    // it or replace its user pointer.
    GLFWwindow* glfw_handle() const;

  private:
    explicit Window(std::unique_ptr<detail::WindowState> state);
    std::unique_ptr<detail::WindowState> state_; // stable address: GLFW's user pointer
};

} // namespace lantern::platform
