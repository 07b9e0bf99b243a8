// holoray/api: what the public API's implementation shares: the scene data
// behind api::Scene, images wrapping ImageBuffer without a copy, and the
// public camera turned into the renderer's FrameCameraDesc.
#pragma once

#include "holoray/animate.hpp"
#include "holoray/camera.hpp"
#include "holoray/image.hpp"
#include "holoray/scene.hpp"
#include "display/display_desc.hpp"
#include "display/looking_glass.hpp"
#include "image/image.hpp"
#include "render/frame_camera.hpp"
#include "render/ray_counts.hpp"
#include "scene/scene_desc.hpp"
#include "temporal/sequence.hpp"

namespace holoray::api {

/// The scene description a Scene holds (scene/scene_desc.hpp).
struct SceneData {
  SceneDesc desc;
};

namespace detail {

/// Images whose storage is an ImageBuffer: every api::Image is one.
struct ImageAccess {
  /// Takes `buffer` over; the Image's samples are its samples.
  static Image wrap(ImageBuffer&& buffer);
  /// The buffer behind `image` (empty Image: an empty buffer).
  static const ImageBuffer& buffer(const Image& image);
};

}  // namespace detail

/// The renderer's camera choice for a public camera; display and calibration
/// files are read here (SceneError when malformed).
FrameCameraDesc frame_camera_desc(const Camera& camera);
/// A display file (display-files.md) or a Looking Glass calibration
/// (visual.json): SceneError when malformed, std::system_error when unreadable.
DisplayDesc read_display(const std::string& path);
LookingGlassCalibration read_calibration(const std::string& path);

api::RayCounts to_api(const holoray::RayCounts& r);
FrameRow to_api(const FrameReport& r);
FrameReport from_api(const FrameRow& r);

}  // namespace holoray::api
