// holoray: the public C++ API. One include for all of it.
//
//   scene.hpp    Scene: load(path), or add_mesh / add_sphere / add_light / set_viewpoint
//   camera.hpp   LensArray, Pinhole, Quilt, Display, LookingGlass: plain data
//   render.hpp   Renderer (placed and built once), render(), RenderOptions, Result
//   world.hpp    World: a scene built once for many cameras and either device
//   animate.hpp  Animation: a shot frame by frame, with keyframe reuse
//   image.hpp    Image (float, linear), read_image, write_image, ImageWriter, BackgroundWriter, compare_images
//   preview.hpp  sub-aperture views, view grids and sweeps, simulate_view, interlace_quilt
//   video.hpp    VideoWriter (FFV1, H.264)
//   files.hpp    write_text_file (whole or not at all)
//   errors.hpp   SceneError (file:line:col), Cancelled
//   pick.hpp, stopwatch.hpp  named choices and the clock, for front ends
//
// Link with holoray::holoray (find_package(holoray)). Example: examples/api/.
#pragma once

#include <string>

#include "holoray/animate.hpp"
#include "holoray/camera.hpp"
#include "holoray/errors.hpp"
#include "holoray/files.hpp"
#include "holoray/image.hpp"
#include "holoray/live.hpp"
#include "holoray/pick.hpp"
#include "holoray/preview.hpp"
#include "holoray/render.hpp"
#include "holoray/scene.hpp"
#include "holoray/stopwatch.hpp"
#include "holoray/video.hpp"
#include "holoray/world.hpp"
#include "holoray/web.hpp"

namespace holoray::api {

/// The library's version, "MAJOR.MINOR.PATCH".
HOLORAY_API const char* version();
/// The libraries built in and their versions, as `holoray --version` lists
/// them: "Embree 4.3.3, oneTBB 2022.0.0, libpng 1.6.44, ...".
HOLORAY_API std::string built_with();

}  // namespace holoray::api
