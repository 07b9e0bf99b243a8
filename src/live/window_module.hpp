// holoray/live: windows from the GLFW module (holoray_glfw.so), loaded on
// the first (util/module_loader.hpp), as the FFmpeg module is on the first
// video.
#pragma once

#include <memory>

#include "live/window.hpp"

namespace holoray::live {

/// A window as `request` asks. Throws std::runtime_error with the reason:
/// the module missing, no display, no such monitor (listing them).
std::unique_ptr<Window> open_window(const WindowRequest& request);

}  // namespace holoray::live
