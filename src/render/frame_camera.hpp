// holoray/render: the camera an image is rendered through, chosen once.
//
// `render` and `animate` both pick among the integral camera (the EIA,
// camera-model.md), a pinhole view, a Looking Glass quilt (or one of its
// views), a physical display's panel and a Looking Glass's native panel.
// FrameCameraDesc is that choice as plain data, checked by the API;
// make_frame_camera() places it by a viewpoint (a still's, or each frame's);
// render_through() traces it.
#pragma once

#include <optional>
#include <string>
#include <variant>

#include "camera/lens_array.hpp"
#include "camera/pinhole.hpp"
#include "camera/placement.hpp"
#include "camera/quilt_camera.hpp"
#include "camera/display_camera.hpp"
#include "display/display_file.hpp"
#include "display/looking_glass.hpp"
#include "render/renderer.hpp"

namespace holoray {

/// What an image is rendered as, before any viewpoint places it: one kind
/// of five, each with its own settings only.
struct FrameCameraDesc {
  /// The integral camera: the lens array (camera-model.md).
  struct Integral {
    ArraySettings array;
  };
  /// A pinhole view through the viewpoint.
  struct Pinhole {
    /// The view's size in pixels; 0 takes the viewpoint's resolution, else 512x512.
    int width = 0, height = 0;
    bool tachyon_samples = false;  ///< one sample at each pixel's upper-right corner, where Tachyon samples
    /// The window moved right and up by these fractions of its larger side
    /// (a camera's lens shift, Blender's convention).
    double shift_x = 0, shift_y = 0;
  };
  /// A Looking Glass quilt, or one of its views.
  struct Quilt {
    QuiltDesc layout;  ///< its views, cone and one view's size
    int view = -1;     ///< >= 0 renders that view alone, as a pinhole view
  };
  /// A physical display's panel (display-files.md).
  struct Display {
    DisplayDesc display;
    std::optional<Frame> frame;  ///< an explicit placement of the panel (world)
  };
  /// A Looking Glass's native panel, from its calibration.
  struct LookingGlass {
    LookingGlassCalibration calibration;
    int views = kDefaultLookingGlassViews;  ///< the quilt it is the continuous version of
  };

  std::variant<Integral, Pinhole, Quilt, Display, LookingGlass> kind;
  /// The focal plane's distance from the viewpoint, scene units: where a
  /// lens array or a display's panel stands (orthoscopic), the quilt's and
  /// Looking Glass's zero-parallax plane; nullopt: the viewpoint's |from - at|
  /// (a file camera's: the depth of the scene's centre, Viewpoint::Focus).
  std::optional<double> focus_distance;

  /// The settings of kind T, or nullptr.
  template <class T>
  const T* get() const { return std::get_if<T>(&kind); }
  /// Whether the camera stands where its settings say, not by the viewpoint
  /// (a lens array's or a panel's origin, normal and up).
  bool placed_explicitly() const {
    if (const Integral* i = get<Integral>()) return i->array.origin.has_value();
    if (const Display* d = get<Display>()) return d->frame.has_value();
    return false;
  }
};

/// A display's panel where its lenses are not whole pixels: traced per
/// subpixel line, then packed into pixels in its subpixel order.
struct PanelView {
  DisplayCamera camera;
  bool red_first = true;  ///< subpixel order RGB (else BGR)
};

/// A FrameCameraDesc placed: one camera of five, each a PixelCamera
/// (camera/camera.hpp) of its kind. A display whose lenses are whole pixels
/// is its integral camera (as_lens_array), so it renders with every
/// integral-camera feature. `render_through` is the one place that
/// dispatches on the kind.
struct FrameCamera {
  std::variant<LensArray, PinholeCamera, QuiltCamera, PanelView, LookingGlassCamera> placed;

  /// The camera of kind T, or nullptr.
  template <class T>
  const T* get() const { return std::get_if<T>(&placed); }
  /// The integral camera (an EIA, or a display rendered as one), or nullptr.
  const LensArray* lens_array() const { return get<LensArray>(); }

  /// The image's size in pixels (a panel's pixels, not its subpixels).
  int width() const;
  int height() const;
  /// Samples a panel traces per row before packing them into its pixels
  /// (three per pixel with subpixels); 0 for the other cameras, whose
  /// samples are their pixels.
  int panel_samples_per_row() const;
  /// The angle one pixel subtends (radians), for mesh textures' MIP levels
  /// (RenderSettings::footprint); nullopt where the finest level is read.
  std::optional<double> pixel_angle() const;
};

/// `d` placed by `viewpoint` (the scene file's, or a frame's). Throws
/// std::invalid_argument naming the option and `scene` when the camera
/// needs a viewpoint and there is none, and as the placements do.
FrameCamera make_frame_camera(const FrameCameraDesc& d, const std::optional<Viewpoint>& viewpoint,
                              const std::string& scene);

/// The image (or the rows options.rows names) through `camera`, by the
/// renderer of its kind.
FrameBuffers render_through(const RenderContext& scene, const FrameCamera& camera, const RenderOptions& options,
                            RenderStats& stats);

}  // namespace holoray
