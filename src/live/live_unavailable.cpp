// holoray/live without the GPU path (no Vulkan headers or glslc at build
// time): run_live says how to get it.
#include <stdexcept>

#include "holoray/live.hpp"

namespace holoray::api {

LiveResult run_live(const Scene&, const Camera&, const RenderOptions&, const LiveOptions&) {
  throw std::runtime_error("holoray live: this holoray was built without the GPU path (CMake found no Vulkan headers or "
                           "glslc): install libvulkan-dev and glslc and build again");
}

LiveResult run_live_shot(const std::string&, const std::optional<Camera>&, const RenderOptions&, const LiveOptions&) {
  return run_live(Scene(), Pinhole{}, {}, {});
}

}  // namespace holoray::api
