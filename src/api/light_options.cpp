#include "api/light_options.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "image/image_io.hpp"

namespace holoray::api {

void check_light(Integrator integrator, const Environment& env, bool cache) {
  if (integrator == Integrator::whitted && env.given())
    throw std::invalid_argument("`environment`: lights the path integrator only (`integrator` path); Whitted's sees the background colour");
  if (!(env.strength >= 0) || !std::isfinite(env.strength))
    throw std::invalid_argument(fmt::format("environment strength: expected a finite number >= 0, got {}", env.strength));
  if (!std::isfinite(env.rotation_deg))
    throw std::invalid_argument(fmt::format("environment rotation: expected a finite angle in degrees, got {}", env.rotation_deg));
  if (env.colour)
    for (double c : *env.colour)
      if (!(c >= 0) || !std::isfinite(c))
        throw std::invalid_argument(fmt::format("environment colour: expected finite values >= 0, got {}", c));
  if (integrator == Integrator::path) {
    if (cache)
      throw std::invalid_argument("`integrator` path: the shadow cache reuses Whitted's point-light visibility, not paths; leave `cache` off");
  }
}

std::unique_ptr<EnvironmentMap> environment_of(const Environment& env, const SceneDesc& desc) {
  if (!env.file.empty()) {
    // The top row toward the scene's up: +z where the viewpoint says so (NFF's SPD scenes, Blender's frame).
    EnvironmentUp up = EnvironmentUp::y;
    if (desc.viewpoint && std::fabs(desc.viewpoint->up.z) > std::fabs(desc.viewpoint->up.y)) up = EnvironmentUp::z;
    const ImageBuffer image = holoray::read_image(env.file);
    try {
      return std::make_unique<EnvironmentMap>(image, env.strength, env.rotation_deg * M_PI / 180, up);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("{}: {}", env.file, e.what()));
    }
  }
  if (env.colour) {
    const auto& c = *env.colour;
    return std::make_unique<EnvironmentMap>(Vec3{c[0], c[1], c[2]} * env.strength);
  }
  return std::make_unique<EnvironmentMap>(desc.background);
}

}  // namespace holoray::api
