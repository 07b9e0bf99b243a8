#include "live/window_module.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace holoray::live {

namespace {

using OpenFn = decltype(&holoray_open_window);

OpenFn load_module() {
  static std::once_flag once;
  static OpenFn open = nullptr;
  static std::string why;
  std::call_once(once, [] {
    std::vector<std::string> candidates;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back((exe.parent_path().parent_path() / "lib/holoray/holoray_glfw.so").string());
#ifdef HOLORAY_GLFW_MODULE
    candidates.push_back(HOLORAY_GLFW_MODULE);
#endif
    for (const std::string& path : candidates) {
      if (!std::filesystem::exists(path, ec)) continue;
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        why = dlerror();
        return;
      }
      open = reinterpret_cast<OpenFn>(dlsym(handle, "holoray_open_window"));
      if (!open) why = fmt::format("'{}' has no holoray_open_window", path);
      return;
    }
    why = candidates.size() > 1 || candidates.empty()
              ? fmt::format("holoray's window module is not installed (looked for {})", fmt::join(candidates, ", "))
              : "this holoray was built without its window module (CMake found no GLFW): install libglfw3-dev and build again";
  });
  if (!open) throw std::runtime_error(why);
  return open;
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
