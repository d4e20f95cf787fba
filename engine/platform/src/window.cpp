// Window: GLFW window creation, callbacks into InputState and WindowEvents, surfaces.
#include "lantern/platform/window.hpp"

#include "glfw_library.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/gpu/vk_check.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <thread>
#include <utility>

namespace lantern::platform {

// What GLFW's callbacks update (the window's user pointer).
struct detail::WindowState {
    GLFWwindow* window = nullptr;
    std::thread::id thread = std::this_thread::get_id();
    InputState input;
    std::vector<WindowEvent> events;
    bool minimised = false;
    bool focused = false;

    WindowState() = default;
    WindowState(const WindowState&) = delete;
    WindowState& operator=(const WindowState&) = delete;
    ~WindowState() {
        if (!window) return;
        glfwDestroyWindow(window);
        detail::release_glfw();
    }
};

namespace {

detail::WindowState& state_of(GLFWwindow* window) {
    return *static_cast<detail::WindowState*>(glfwGetWindowUserPointer(window));
}

Extent framebuffer_extent(GLFWwindow* window) {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window, &width, &height);
    return {static_cast<std::uint32_t>(std::max(width, 0)),
            static_cast<std::uint32_t>(std::max(height, 0))};
}

// GLFW reports the cursor in screen coordinates; the InputState wants framebuffer pixels.
glm::vec2 to_pixels(GLFWwindow* window, double x, double y) {
    int window_w = 0, window_h = 0, fb_w = 0, fb_h = 0;
    glfwGetWindowSize(window, &window_w, &window_h);
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    const double sx = window_w > 0 ? double(fb_w) / window_w : 1.0;
    const double sy = window_h > 0 ? double(fb_h) / window_h : 1.0;
    return {static_cast<float>(x * sx), static_cast<float>(y * sy)};
}

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
    if (key < 0 || key >= static_cast<int>(InputState::key_count) || action == GLFW_REPEAT) return;
    state_of(window).input.key_event(static_cast<Key>(key), action == GLFW_PRESS);
}

void on_mouse_button(GLFWwindow* window, int button, int action, int /*mods*/) {
    if (button < 0 || button >= static_cast<int>(InputState::button_count)) return;
    state_of(window).input.button_event(static_cast<MouseButton>(button), action == GLFW_PRESS);
}

void on_cursor(GLFWwindow* window, double x, double y) {
    state_of(window).input.cursor_event(to_pixels(window, x, y));
}

void on_scroll(GLFWwindow* window, double x, double y) {
    state_of(window).input.scroll_event({static_cast<float>(x), static_cast<float>(y)});
}

void on_framebuffer_size(GLFWwindow* window, int width, int height) {
    const Extent size{static_cast<std::uint32_t>(std::max(width, 0)),
                      static_cast<std::uint32_t>(std::max(height, 0))};
    state_of(window).events.push_back({WindowEventType::resized, size});
}

void on_iconify(GLFWwindow* window, int iconified) {
    detail::WindowState& s = state_of(window);
    s.minimised = iconified == GLFW_TRUE;
    s.events.push_back({s.minimised ? WindowEventType::minimised : WindowEventType::restored, {}});
}

void on_close(GLFWwindow* window) {
    state_of(window).events.push_back({WindowEventType::close_requested, {}});
}

void on_focus(GLFWwindow* window, int focused) {
    detail::WindowState& s = state_of(window);
    s.focused = focused == GLFW_TRUE;
    // Keys released while another window has the focus never reach this one.
    if (!s.focused) s.input.release_all();
    s.events.push_back(
        {s.focused ? WindowEventType::focus_gained : WindowEventType::focus_lost, {}});
}

void install_callbacks(GLFWwindow* window) {
    glfwSetKeyCallback(window, &on_key);
    glfwSetMouseButtonCallback(window, &on_mouse_button);
    glfwSetCursorPosCallback(window, &on_cursor);
    glfwSetScrollCallback(window, &on_scroll);
    glfwSetFramebufferSizeCallback(window, &on_framebuffer_size);
    glfwSetWindowIconifyCallback(window, &on_iconify);
    glfwSetWindowCloseCallback(window, &on_close);
    glfwSetWindowFocusCallback(window, &on_focus);
}

} // namespace

// --- Window ------------------------------------------------------------------------------------

Result<Window> Window::create(const WindowDesc& desc) {
    LANTERN_ASSERT(desc.width > 0 && desc.height > 0, "platform::Window::create of size 0");
    if (auto glfw = detail::acquire_glfw(); !glfw)
        return make_error("cannot open a window: " + glfw.error().message);
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, desc.resizable ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window =
        glfwCreateWindow(static_cast<int>(desc.width), static_cast<int>(desc.height),
                         desc.title.c_str(), nullptr, nullptr);
    if (!window) {
        const std::string why = detail::last_glfw_error();
        detail::release_glfw();
        return make_error("cannot open a window: glfwCreateWindow failed: " + why);
    }
    auto state = std::make_unique<detail::WindowState>();
    state->window = window;
    state->focused = glfwGetWindowAttrib(window, GLFW_FOCUSED) == GLFW_TRUE;
    glfwSetWindowUserPointer(window, state.get());
    install_callbacks(window);
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    state->input.cursor_event(to_pixels(window, x, y));
    state->input.begin_frame();
    return Window(std::move(state));
}

Window::Window(std::unique_ptr<detail::WindowState> state) : state_(std::move(state)) {}
Window::Window(Window&& other) noexcept = default;
Window& Window::operator=(Window&& other) noexcept = default;
Window::~Window() = default;

void Window::poll() {
    LANTERN_ASSERT(state_ && state_->thread == std::this_thread::get_id(),
                   "platform::Window::poll off the main thread or on a moved-from window");
    state_->input.begin_frame();
    state_->events.clear();
    glfwPollEvents();
}

void Window::poll_wait(double timeout_seconds) {
    LANTERN_ASSERT(state_ && state_->thread == std::this_thread::get_id(),
                   "platform::Window::poll_wait off the main thread or on a moved-from window");
    state_->input.begin_frame();
    state_->events.clear();
    glfwWaitEventsTimeout(timeout_seconds);
}

std::span<const WindowEvent> Window::events() const {
    return state_->events;
}
const InputState& Window::input() const {
    return state_->input;
}

bool Window::should_close() const {
    return glfwWindowShouldClose(state_->window) == GLFW_TRUE;
}
void Window::request_close() {
    glfwSetWindowShouldClose(state_->window, GLFW_TRUE);
}
void Window::cancel_close() {
    glfwSetWindowShouldClose(state_->window, GLFW_FALSE);
}
Extent Window::framebuffer_size() const {
    return framebuffer_extent(state_->window);
}

Extent Window::window_size() const {
    int width = 0, height = 0;
    glfwGetWindowSize(state_->window, &width, &height);
    return {static_cast<std::uint32_t>(std::max(width, 0)),
            static_cast<std::uint32_t>(std::max(height, 0))};
}

bool Window::minimised() const {
    return state_->minimised;
}
bool Window::visible() const {
    return glfwGetWindowAttrib(state_->window, GLFW_VISIBLE) == GLFW_TRUE;
}
bool Window::focused() const {
    return state_->focused;
}
void Window::set_title(const std::string& title) {
    glfwSetWindowTitle(state_->window, title.c_str());
}

void Window::set_size(Extent size) {
    LANTERN_ASSERT(!size.empty(), "platform::Window::set_size to an empty size");
    glfwSetWindowSize(state_->window, static_cast<int>(size.width), static_cast<int>(size.height));
}

GLFWwindow* Window::glfw_handle() const {
    return state_->window;
}

Result<std::vector<const char*>> Window::vulkan_instance_extensions() const {
    std::uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names)
        return make_error("no Vulkan surface extensions for this window system: " +
                          detail::last_glfw_error());
    return std::vector<const char*>(names, names + count);
}

Result<Surface> Window::create_surface(const gpu::Device& device) const {
    Surface surface;
    const VkResult result =
        glfwCreateWindowSurface(device.vk_instance(), state_->window, nullptr, &surface.surface_);
    if (result != VK_SUCCESS) {
        surface.surface_ = VK_NULL_HANDLE;
        return make_error(std::string("cannot create a Vulkan surface: ") +
                          gpu::vk_result_name(result) + " (" + detail::last_glfw_error() +
                          "; was the Device created with Window::vulkan_instance_extensions()?)");
    }
    surface.instance_ = device.vk_instance();
    return surface;
}

// --- Surface -----------------------------------------------------------------------------------

Surface::Surface(Surface&& other) noexcept
    : instance_(std::exchange(other.instance_, VK_NULL_HANDLE)),
      surface_(std::exchange(other.surface_, VK_NULL_HANDLE)) {}

Surface& Surface::operator=(Surface&& other) noexcept {
    if (this != &other) {
        if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
        instance_ = std::exchange(other.instance_, VK_NULL_HANDLE);
        surface_ = std::exchange(other.surface_, VK_NULL_HANDLE);
    }
    return *this;
}

Surface::~Surface() {
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
}

} // namespace lantern::platform
