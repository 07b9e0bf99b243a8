// holoray/live: window.hpp's Window through GLFW 3 (Debian libglfw3-dev),
// built as the module holoray_glfw.so. Drag with the left button orbits,
// with shift held or another button pans; the pointer's place without a
// button; the wheel; keys by name.
#include <vulkan/vulkan.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include "live/window.hpp"

namespace {

using holoray::live::InputEvent;

std::string glfw_error;  // the last GLFW error, for the messages below
void on_error(int, const char* text) { glfw_error = text ? text : ""; }

std::string key_name(int key, int mods) {
  std::string name;
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) name = std::string(1, char('A' + key - GLFW_KEY_A));
  else if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) name = std::string(1, char('0' + key - GLFW_KEY_0));
  else switch (key) {
      case GLFW_KEY_UP: name = "Up"; break;
      case GLFW_KEY_DOWN: name = "Down"; break;
      case GLFW_KEY_LEFT: name = "Left"; break;
      case GLFW_KEY_RIGHT: name = "Right"; break;
      case GLFW_KEY_SPACE: name = "Space"; break;
      case GLFW_KEY_ESCAPE: name = "Escape"; break;
      case GLFW_KEY_PAGE_UP: name = "PageUp"; break;
      case GLFW_KEY_PAGE_DOWN: name = "PageDown"; break;
      case GLFW_KEY_HOME: name = "Home"; break;
      default: return "";
    }
  return (mods & GLFW_MOD_SHIFT) ? "shift+" + name : name;
}

class GlfwWindow final : public holoray::live::Window {
 public:
  explicit GlfwWindow(GLFWwindow* w) : window_(w) {
    glfwSetWindowUserPointer(w, this);
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int mods) {
      if (action == GLFW_RELEASE) return;
      const std::string name = key_name(key, mods);
      if (!name.empty()) self(win)->queue_.push_back({InputEvent::Kind::key, 0, 0, name});
    });
    glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
      self(win)->queue_.push_back({InputEvent::Kind::wheel, 0, dy, ""});
    });
    glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int mods) {
      GlfwWindow& me = *self(win);
      if (action == GLFW_RELEASE) {
        me.dragging_ = false;
        return;
      }
      me.dragging_ = true;
      me.panning_ = button != GLFW_MOUSE_BUTTON_LEFT || (mods & GLFW_MOD_SHIFT);
      glfwGetCursorPos(win, &me.x_, &me.y_);
    });
    glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
      GlfwWindow& me = *self(win);
      if (me.dragging_)
        me.queue_.push_back({me.panning_ ? InputEvent::Kind::pan : InputEvent::Kind::orbit, x - me.x_, y - me.y_, ""});
      else
        me.queue_.push_back({InputEvent::Kind::pointer, x, y, ""});
      me.x_ = x, me.y_ = y;
    });
  }
  ~GlfwWindow() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }

  std::vector<std::string> instance_extensions() const override {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    return std::vector<std::string>(names, names + count);
  }
  uint64_t create_surface(void* instance) override {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    if (glfwCreateWindowSurface(static_cast<VkInstance>(instance), window_, nullptr, &surface) != VK_SUCCESS)
      throw std::runtime_error("the window has no Vulkan surface: " + glfw_error);
    return reinterpret_cast<uint64_t>(surface);
  }
  std::array<int, 2> framebuffer_size() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {w, h};
  }
  void set_title(const std::string& title) override { glfwSetWindowTitle(window_, title.c_str()); }
  bool closed() const override { return glfwWindowShouldClose(window_); }
  void close() override { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
  std::vector<InputEvent> events(bool wait) override {
    if (wait) glfwWaitEventsTimeout(0.5);  // the caller asks its stop request twice a second
    else glfwPollEvents();
    return std::move(queue_);
  }
  void wake() override { glfwPostEmptyEvent(); }

 private:
  static GlfwWindow* self(GLFWwindow* w) { return static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w)); }
  GLFWwindow* window_;
  std::vector<InputEvent> queue_;
  bool dragging_ = false, panning_ = false;
  double x_ = 0, y_ = 0;
};

std::string monitor_list(GLFWmonitor** monitors, int count) {
  std::string out;
  for (int k = 0; k < count; ++k) {
    const GLFWvidmode* mode = glfwGetVideoMode(monitors[k]);
    char line[256];
    std::snprintf(line, sizeof line, "%s%d '%s' %dx%d", k ? ", " : "", k, glfwGetMonitorName(monitors[k]),
                  mode ? mode->width : 0, mode ? mode->height : 0);
    out += line;
  }
  return out;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) holoray::live::Window* holoray_open_window(
    const holoray::live::WindowRequest* request, char* error, size_t error_size) {
  auto fail = [&](const std::string& why) -> holoray::live::Window* {
    std::snprintf(error, error_size, "%s", why.c_str());
    return nullptr;
  };
  glfwSetErrorCallback(on_error);
#ifdef GLFW_PLATFORM
  // GLFW 3.4 (Debian 13) tries Wayland first, and libwayland complains on
  // stderr where there is no Wayland session ("XDG_RUNTIME_DIR is invalid"):
  // the platform the environment names, X11 where only DISPLAY is set.
  if (!std::getenv("WAYLAND_DISPLAY") && std::getenv("DISPLAY")) glfwInitHint(GLFW_PLATFORM, GLFW_PLATFORM_X11);
#endif
  if (!glfwInit()) return fail("no window could be opened (GLFW: " + glfw_error + ")");
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    return fail("GLFW found no Vulkan loader to show frames with: install libvulkan1 with mesa-vulkan-drivers or the GPU's driver");
  }
  int count = 0;
  GLFWmonitor** monitors = glfwGetMonitors(&count);
  GLFWmonitor* monitor = count ? monitors[0] : nullptr;
  if (!request->monitor.empty()) {
    monitor = nullptr;
    for (int k = 0; k < count; ++k)
      if (request->monitor == std::to_string(k) || request->monitor == glfwGetMonitorName(monitors[k])) monitor = monitors[k];
    if (!monitor) {
      const std::string list = count ? monitor_list(monitors, count) : "none";
      glfwTerminate();
      return fail("--monitor " + request->monitor + ": no such monitor; this display has " + list);
    }
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  GLFWwindow* window = nullptr;
  if (request->fullscreen && monitor) {
    const GLFWvidmode* mode = glfwGetVideoMode(monitor);
    window = glfwCreateWindow(mode->width, mode->height, request->title.c_str(), monitor, nullptr);
  } else {
    int w = request->width, h = request->height;
    int x = 0, y = 0;
    if (monitor) {
      int mw = 0, mh = 0;
      glfwGetMonitorWorkarea(monitor, &x, &y, &mw, &mh);
      // An image larger than the monitor opens at the monitor's size (shown shrunk).
      if (mw > 0 && mh > 0 && (w > mw || h > mh)) {
        const double s = std::min(double(mw) / w, double(mh) / h);
        w = std::max(1, int(w * s)), h = std::max(1, int(h * s));
      }
    }
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    window = glfwCreateWindow(w, h, request->title.c_str(), nullptr, nullptr);
    if (window) {
      if (monitor) glfwSetWindowPos(window, x, y);
      glfwShowWindow(window);
    }
  }
  if (!window) {
    glfwTerminate();
    return fail("no window could be opened (GLFW: " + glfw_error + ")");
  }
  return new GlfwWindow(window);
}
