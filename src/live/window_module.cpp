#include "live/window_module.hpp"

#include <stdexcept>
#include <string>

#include "util/module_loader.hpp"

namespace holoray::live {

namespace {

using OpenFn = decltype(&holoray_open_window);

OpenFn load_module() {
#ifdef HOLORAY_GLFW_MODULE
  return reinterpret_cast<OpenFn>(
      module_symbol("holoray_glfw.so", HOLORAY_GLFW_MODULE, "holoray_open_window", "holoray's window module is not installed"));
#else
  return reinterpret_cast<OpenFn>(module_symbol("holoray_glfw.so", "", "holoray_open_window",
                                                "this holoray was built without its window module (CMake found no GLFW): "
                                                "install libglfw3-dev and build again"));
#endif
}

}  // namespace

std::unique_ptr<Window> open_window(const WindowRequest& request) {
  const OpenFn open = load_module();
  char error[1024] = "";
  Window* window = open(&request, error, sizeof error);
  if (!window) throw std::runtime_error(error);
  return std::unique_ptr<Window>(window);
}

}  // namespace holoray::live
