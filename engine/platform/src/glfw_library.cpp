// Reference-counted glfwInit/glfwTerminate, GLFW error capture and the display probe.
#include "glfw_library.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/platform/window.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <cstdlib>

namespace lantern::platform {

namespace {

// GLFW is main-thread only, so plain globals are enough.
int glfw_users = 0;
std::string glfw_error;

void on_glfw_error(int code, const char* description) {
    glfw_error = (description ? description : "unknown error") + std::string(" (GLFW error ") +
                 std::to_string(code) + ")";
}

bool env_set(const char* name) {
    const char* value = std::getenv(name);
    return value && *value;
}

} // namespace

namespace detail {

Result<void> acquire_glfw() {
    if (glfw_users > 0) {
        ++glfw_users;
        return {};
    }
    glfwSetErrorCallback(&on_glfw_error);
    glfw_error.clear();
    if (glfwInit() != GLFW_TRUE) return make_error("glfwInit failed: " + last_glfw_error());
    if (glfwVulkanSupported() != GLFW_TRUE) {
        glfwTerminate();
        return make_error("GLFW found no Vulkan loader (install libvulkan1 and a driver)");
    }
    ++glfw_users;
    return {};
}

void release_glfw() {
    LANTERN_ASSERT(glfw_users > 0, "platform: GLFW released more often than acquired");
    if (--glfw_users == 0) glfwTerminate();
}

std::string last_glfw_error() {
    return glfw_error.empty() ? "no reason given" : glfw_error;
}

} // namespace detail

DisplayProbe display_available() {
    if (!env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY"))
        return {false, "no DISPLAY or WAYLAND_DISPLAY set"};
    if (auto glfw = detail::acquire_glfw(); !glfw) return {false, glfw.error().message};
    detail::release_glfw();
    return {true, {}};
}

} // namespace lantern::platform
