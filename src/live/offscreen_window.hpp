// holoray/live: a window that is not there (LiveOptions::offscreen): live's
// own frame loop run on a machine without a display, its frames traced,
// packed and copied on the device to an image of the window's size as they
// would be shown, and nothing presented; input only from an event script.
#pragma once

#include <array>
#include <memory>

#include "live/window.hpp"

namespace holoray::live {

/// A Window of `request`'s size (width x height framebuffer pixels, as a
/// windowed window opens; a full-screen request takes the same size) that
/// no user sees: no events, never closed but by close(). Its surface is
/// none: a Presenter made for it copies each frame to an image of its own.
std::unique_ptr<Window> offscreen_window(const WindowRequest& request);

}  // namespace holoray::live
