// holoray: the public C++ API. One include for all of it.
//
//   scene.hpp    Scene: load(path), or add_mesh / add_sphere / add_light / set_viewpoint
//   camera.hpp   LensArray, Pinhole, Quilt, Display, LookingGlass: plain data
//   render.hpp   Renderer (placed and built once), render(), RenderOptions, Result
//   animate.hpp  Animation: a shot frame by frame, with keyframe reuse
//   image.hpp    Image (float, linear), read_image, write_image, psnr
//   errors.hpp   SceneError (file:line:col), Cancelled
//
// Link with holoray::holoray (find_package(holoray)). Example: examples/api/.
#pragma once

#include "holoray/animate.hpp"
#include "holoray/camera.hpp"
#include "holoray/errors.hpp"
#include "holoray/image.hpp"
#include "holoray/render.hpp"
#include "holoray/scene.hpp"

namespace holoray::api {

/// The library's version, "MAJOR.MINOR.PATCH".
HOLORAY_API const char* version();

}  // namespace holoray::api
