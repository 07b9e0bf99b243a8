// holoray/live: the GLFW module (holoray_glfw.so) found and loaded once per
// process, beside an installed binary in ../lib/holoray, else where the
// build put it (as video/encoder_module.cpp loads FFmpeg's).
#pragma once

#include <memory>

#include "live/window.hpp"

namespace holoray::live {

/// A window as `request` asks. Throws std::runtime_error with the reason:
/// the module missing, no display, no such monitor (listing them).
std::unique_ptr<Window> open_window(const WindowRequest& request);

}  // namespace holoray::live
