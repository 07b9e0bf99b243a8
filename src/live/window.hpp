// holoray/live: the window `holoray live` shows frames in, its monitors and
// its input, as an interface. GLFW implements it in a module of its own
// (glfw_window.cpp, holoray_glfw.so, loaded on the first window:
// window_module.cpp), so that no other command or library user loads X11.
// Plain C++ types only: the module shares nothing else with the library.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace holoray::live {

/// One input event, in the window's framebuffer pixels.
struct InputEvent {
  enum class Kind { orbit, pan, wheel, key, pointer };
  Kind kind = Kind::key;
  /// orbit and pan: the pointer's move (x right, y down); wheel: dy clicks,
  /// up > 0; pointer: where it is (no button held), from the top left.
  double dx = 0, dy = 0;
  std::string key;        ///< key: its name, as live.md's table writes it ("S", "shift+S", "Up", "Space")
};

/// Where and how large the window opens.
struct WindowRequest {
  int width = 0, height = 0;  ///< framebuffer pixels wanted (a windowed window; clamped to the monitor)
  std::string title;
  std::string monitor;       ///< "" the primary; else a monitor's index or name
  bool fullscreen = false;   ///< on `monitor`, at its own mode
};

class Window {
 public:
  virtual ~Window() = default;
  /// The Vulkan instance extensions its surface needs.
  virtual std::vector<std::string> instance_extensions() const = 0;
  /// Its VkSurfaceKHR for `instance` (a VkInstance); throws std::runtime_error.
  virtual uint64_t create_surface(void* instance) = 0;
  virtual std::array<int, 2> framebuffer_size() const = 0;
  virtual void set_title(const std::string& title) = 0;
  /// Closed by the user (or close()).
  virtual bool closed() const = 0;
  virtual void close() = 0;
  /// The input since the last call; `wait`: blocks until there is some, the
  /// window is closed, wake() is called or half a second passed.
  virtual std::vector<InputEvent> events(bool wait) = 0;
  /// Ends a blocking events() from another thread (a signal's watcher).
  virtual void wake() = 0;
};

}  // namespace holoray::live

/// The module's one entry: a window as `request` asks, or nullptr with
/// `error` (at most error_size bytes) saying why: no display, no monitor of
/// that name (listing them), GLFW failing.
extern "C" holoray::live::Window* holoray_open_window(const holoray::live::WindowRequest* request, char* error, size_t error_size);
