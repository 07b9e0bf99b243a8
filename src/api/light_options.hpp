// holoray/api (internal): the light options a still (RenderOptions) and an
// animation (AnimateOptions) both take: checked once here, and the path
// integrator's environment built from them.
#pragma once

#include <memory>
#include <string>

#include "holoray/render.hpp"
#include "render/environment.hpp"
#include "scene/scene_desc.hpp"

namespace holoray::api {

/// Throws std::invalid_argument naming the option: an environment under
/// Whitted's integrator, a strength, rotation or colour out of range, the
/// path integrator with the shadow `cache`.
void check_light(Integrator integrator, const Environment& environment, bool cache);

/// The path integrator's environment: `env`'s image (read here, so that the
/// build step reads no file; its top row toward `desc`'s up: +z where its
/// viewpoint has z up, else +y), else its colour, else `desc`'s background
/// colour. Throws ImageReadError for an unreadable image,
/// std::invalid_argument naming the file for one EnvironmentMap refuses.
std::unique_ptr<EnvironmentMap> environment_of(const Environment& env, const SceneDesc& desc);

}  // namespace holoray::api
