// GLFW's process-wide initialisation, shared by every Window and the display probe.
#pragma once

#include "lantern/core/result.hpp"

#include <string>

namespace lantern::platform::detail {

// Initialises GLFW on first use (reference counted): an error with GLFW's reason when
// there is no display or no Vulkan loader. Main thread only.
Result<void> acquire_glfw();
// Terminates GLFW when the last user releases it.
void release_glfw();
// The description of the last GLFW error ("" when none), e.g. "X11: Failed to open display".
std::string last_glfw_error();

} // namespace lantern::platform::detail
