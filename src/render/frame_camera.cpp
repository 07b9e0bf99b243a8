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

namespace {

// std::visit over the five kinds with one lambda per kind.
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
// Written out: clang before 17 deduces no aggregate's template arguments.
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace

int FrameCamera::width() const {
  return std::visit(Overloaded{[](const PanelView& p) { return p.camera.geometry().width; },
                               [](const LookingGlassCamera& g) { return g.calibration().width; },
                               [](const auto& c) { return c.width(); }},
                    placed);
}

int FrameCamera::height() const {
  return std::visit(Overloaded{[](const PanelView& p) { return p.camera.height(); }, [](const auto& c) { return c.height(); }},
                    placed);
}

int FrameCamera::panel_samples_per_row() const {
  if (const PanelView* p = get<PanelView>()) return p->camera.width();
  if (const LookingGlassCamera* g = get<LookingGlassCamera>()) return g->width();
  return 0;
}

std::optional<double> FrameCamera::pixel_angle() const {
  if (const LensArray* a = get<LensArray>()) return holoray::pixel_angle(a->desc());
  if (const PinholeCamera* v = get<PinholeCamera>()) return holoray::pixel_angle(v->desc());
  return std::nullopt;
}

FrameCamera make_frame_camera(const FrameCameraDesc& d, const std::optional<Viewpoint>& viewpoint,
                              const std::string& scene) {
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
  using Desc = FrameCameraDesc;
  return std::visit(
      Overloaded{
          [&](const Desc::Integral& i) { return FrameCamera{LensArray(place_array(i.array, focused))}; },
          [&](const Desc::Pinhole& p) {
            const Viewpoint& vp = need_viewpoint("`Pinhole`", "");
            const int w = p.width > 0 ? p.width : vp.xres > 0 ? vp.xres : 512;
            const int h = p.width > 0 ? p.height : vp.yres > 0 ? vp.yres : 512;
            PinholeDesc pd = view_of(vp, w, h);
            if (p.tachyon_samples) pd.sample_u = 1, pd.sample_v = 0;
            // The window's larger side on the image plane at distance 1.
            const double height = pd.ortho_height > 0 ? pd.ortho_height : 2 * std::tan(pd.fov_deg * std::numbers::pi / 360);
            const double larger = height * std::max(1.0, double(w) / h);
            pd.shift_x = p.shift_x * larger;
            pd.shift_y = p.shift_y * larger;
            return FrameCamera{PinholeCamera(pd)};
          },
          [&](const Desc::Quilt& q) {
            const Viewpoint& vp = perspective("`Quilt`");
            const PinholeDesc centre = view_of(vp, q.layout.view_width, q.layout.view_height);
            if (q.view >= 0) return FrameCamera{PinholeCamera(quilt_view(q.layout, centre, q.view))};
            return FrameCamera{QuiltCamera(q.layout, centre)};
          },
          [&](const Desc::Display& p) {
            if (auto eia = as_lens_array(p.display, focused, p.frame)) return FrameCamera{LensArray(*eia)};
            return FrameCamera{PanelView{DisplayCamera(place_display(p.display, focused, p.frame)),
                                         p.display.subpixels != SubpixelOrder::bgr}};
          },
          [&](const Desc::LookingGlass& g) {
            const Viewpoint& vp = perspective("`LookingGlass`");
            const LookingGlassCalibration& cal = g.calibration;
            return FrameCamera{LookingGlassCamera(cal, view_of(vp, cal.width, cal.height), g.views)};
          }},
      d.kind);
}

FrameBuffers render_through(const RenderContext& scene, const FrameCamera& camera, const RenderOptions& options,
                            RenderStats& stats) {
  // Embree's hierarchy, built here when a move or a new scene left it
  // stale: on all cores, and before the tiles' clocks start.
  scene.accel().build();
  return std::visit(
      Overloaded{[&](const LensArray& a) { return render_frame(scene, a, options, stats); },
                 [&](const PinholeCamera& v) { return render_view(scene, v, options, stats); },
                 [&](const QuiltCamera& q) { return render_quilt(scene, q, options, stats); },
                 [&](const PanelView& p) { return render_display(scene, p.camera, p.red_first, options, stats); },
                 [&](const LookingGlassCamera& g) { return render_looking_glass(scene, g, options, stats); }},
      camera.placed);
}

}  // namespace holoray
