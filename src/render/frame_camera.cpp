#include "render/frame_camera.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "display/display_placement.hpp"
#include "render/display_renderer.hpp"
#include "render/view_renderer.hpp"

namespace holoray {

int FrameCamera::width() const {
  if (array) return array->width();
  if (view) return view->width();
  if (quilt) return quilt->width();
  if (panel) return panel->geometry().width;
  return glass->calibration().width;
}

int FrameCamera::height() const {
  if (array) return array->height();
  if (view) return view->height();
  if (quilt) return quilt->height();
  if (panel) return panel->height();
  return glass->height();
}

int FrameCamera::panel_samples_per_row() const {
  if (panel) return panel->width();
  if (glass) return glass->width();
  return 0;
}

std::optional<double> FrameCamera::pixel_angle() const {
  if (array) return holoray::pixel_angle(array->desc());
  if (view) return holoray::pixel_angle(view->desc());
  return std::nullopt;
}

FrameCamera make_frame_camera(const FrameCameraDesc& d, const std::optional<Viewpoint>& viewpoint,
                              const std::string& scene) {
  using Kind = FrameCameraDesc::Kind;
  // The viewpoint, its `at` moved to the focus distance when one is given.
  std::optional<Viewpoint> focused = viewpoint;
  if (focused && d.focus_distance) focused = viewpoint->focused_at(*d.focus_distance);
  auto need_viewpoint = [&](const char* option, const char* what) -> const Viewpoint& {
    if (!focused) throw std::invalid_argument(fmt::format("{}: '{}' has no viewpoint (NFF 'v'){}", option, scene, what));
    return *focused;
  };
  // Sheared frusta need a perspective centre view.
  auto perspective = [&](const char* option) -> const Viewpoint& {
    const Viewpoint& vp = need_viewpoint(option, " to centre the views on");
    if (vp.ortho_size > 0)
      throw std::invalid_argument(fmt::format("{}: the camera '{}' is orthographic: its views would not part", option, vp.camera));
    return vp;
  };
  FrameCamera c;
  switch (d.kind) {
    case Kind::looking_glass: {
      const Viewpoint& vp = perspective("`LookingGlass`");
      const LookingGlassCalibration& cal = *d.calibration;
      c.glass.emplace(cal, view_of(vp, cal.width, cal.height), d.looking_glass_views);
      break;
    }
    case Kind::quilt: {
      const Viewpoint& vp = perspective("`Quilt`");
      const PinholeDesc centre = view_of(vp, d.quilt.view_width, d.quilt.view_height);
      if (d.quilt_view >= 0) c.view.emplace(quilt_view(d.quilt, centre, d.quilt_view));
      else c.quilt.emplace(d.quilt, centre);
      break;
    }
    case Kind::pinhole: {
      const Viewpoint& vp = need_viewpoint("`Pinhole`", "");
      const int w = d.width > 0 ? d.width : vp.xres > 0 ? vp.xres : 512;
      const int h = d.width > 0 ? d.height : vp.yres > 0 ? vp.yres : 512;
      PinholeDesc pd = view_of(vp, w, h);
      if (d.tachyon_samples) pd.sample_u = 1, pd.sample_v = 0;
      // The window's larger side on the image plane at distance 1.
      const double height = pd.ortho_height > 0 ? pd.ortho_height : 2 * std::tan(pd.fov_deg * std::numbers::pi / 360);
      const double larger = height * std::max(1.0, double(w) / h);
      pd.shift_x = d.shift_x * larger;
      pd.shift_y = d.shift_y * larger;
      c.view.emplace(pd);
      break;
    }
    case Kind::display: {
      const std::optional<Frame> frame = explicit_frame(d.array);
      if (auto eia = as_lens_array(*d.display, focused, frame)) c.array.emplace(*eia);
      else c.panel.emplace(place_display(*d.display, focused, frame));
      c.red_first = d.display->subpixels != SubpixelOrder::bgr;
      break;
    }
    case Kind::integral: c.array.emplace(place_array(d.array, focused)); break;
  }
  return c;
}

FrameBuffers render_through(const RenderScene& scene, const FrameCamera& camera, const RenderOptions& options,
                            RenderStats& stats) {
  if (camera.glass) return render_looking_glass(scene, *camera.glass, options, stats);
  if (camera.view) return render_view(scene, *camera.view, options, stats);
  if (camera.quilt) return render_quilt(scene, *camera.quilt, options, stats);
  if (camera.panel) return render_display(scene, *camera.panel, camera.red_first, options, stats);
  return render_frame(scene, *camera.array, options, stats);
}

}  // namespace holoray
