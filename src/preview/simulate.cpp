#include "preview/simulate.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "display/display_placement.hpp"

namespace holoray {

Vec3 seen_panel_point(const DisplayCamera& camera, const Vec3& eye, const Vec3& q) {
  const DisplayGeometry& g = camera.geometry();
  const Vec3 w = q - eye;                 // the eye's ray, toward the panel (w.z < 0)
  const double k = g.gap / -w.z;          // the chief ray parallel to w, lens plane to panel
  const Vec3 panel_q{q.x, q.y, -g.gap};
  const DisplayLens l = camera.lens_at(panel_q);
  if (g.grid != Grid::lenticular) {
    const Vec3 c = camera.lens_centre_local(l);
    return {c.x + k * w.x, c.y + k * w.y, -g.gap};
  }
  // Across the lenticule: through its axis; along it: straight on from q.
  const double s = std::sin(g.slant_rad), co = std::cos(g.slant_rad);
  const Vec3 axis = camera.axis_point_local(l, q);
  const double across = (axis.x * co - axis.y * s) + k * (w.x * co - w.y * s);
  const double along = (q.x * s + q.y * co) + k * (w.x * s + w.y * co);
  return {across * co + along * s, -across * s + along * co, -g.gap};
}

ImageBuffer simulate_view(const ImageBuffer& panel, const DisplayDesc& d, const SimulateOptions& o) {
  if (panel.width != d.width || panel.height != d.height)
    throw std::invalid_argument(fmt::format("the panel image is {}x{} pixels; the display file's panel is {}x{}",
                                            panel.width, panel.height, d.width, d.height));
  if (!(o.eye_mm.z > 0) || !is_finite(o.eye_mm))
    throw std::invalid_argument(fmt::format("the eye must be in front of the lens sheet (z > 0 mm), got z = {} mm", o.eye_mm.z));
  if (o.width < 1 || o.width > 16384)
    throw std::invalid_argument(fmt::format("the view must be 1 to 16384 pixels wide, got {}", o.width));
  if (o.samples < 1 || o.samples > 16)
    throw std::invalid_argument(fmt::format("samples per pixel side must be 1 to 16, got {}", o.samples));
  DisplayDesc mm = d;
  mm.units_per_mm = 1, mm.depth = 0;
  const DisplayCamera camera(place_display(mm, std::nullopt, Frame{}));
  const DisplayGeometry& g = camera.geometry();
  const double panel_w = d.width * g.pixel_pitch, panel_h = d.height * g.pixel_pitch;
  const int out_h = std::max(1, static_cast<int>(std::lround(o.width * panel_h / panel_w)));
  const double step_x = panel_w / o.width, step_y = panel_h / out_h;
  ImageBuffer out(o.width, out_h, 3);
  const int spp = d.samples_per_pixel();
  const double sample_w = g.pixel_pitch / spp;
  for (int y = 0; y < out_h; ++y)
    for (int x = 0; x < o.width; ++x) {
      double sum[3] = {0, 0, 0}, n[3] = {0, 0, 0};
      for (int sy = 0; sy < o.samples; ++sy)
        for (int sx = 0; sx < o.samples; ++sx) {
          const Vec3 q{-panel_w / 2 + (x + (sx + 0.5) / o.samples) * step_x,
                       panel_h / 2 - (y + (sy + 0.5) / o.samples) * step_y, 0};
          const Vec3 p = seen_panel_point(camera, o.eye_mm, q);
          const double fc = (p.x + panel_w / 2) / sample_w, fr = (panel_h / 2 - p.y) / g.pixel_pitch;
          const bool on = fc >= 0 && fc < d.width * spp && fr >= 0 && fr < d.height;
          const int c = on ? static_cast<int>(fc) : 0, r = on ? static_cast<int>(fr) : 0;
          const float* px = on ? panel.at(c / spp, r) : nullptr;
          if (spp == 1) {
            for (int ch = 0; ch < 3; ++ch) sum[ch] += on ? px[ch] : 0, n[ch] += 1;
          } else {
            // The stripe under the point lights its own channel only.
            const int ch = d.subpixels == SubpixelOrder::bgr ? 2 - c % 3 : c % 3;
            sum[ch] += on ? px[ch] : 0, n[ch] += 1;
          }
        }
      for (int ch = 0; ch < 3; ++ch) out.at(x, y)[ch] = n[ch] > 0 ? static_cast<float>(sum[ch] / n[ch]) : 0.0f;
    }
  return out;
}

}  // namespace holoray
