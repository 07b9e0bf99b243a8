#include "render/display_renderer.hpp"

#include "render/line_renderer.hpp"

namespace holoray {

namespace {
void refuse_aovs(const AovSet& aovs) {
  if (aovs.albedo || aovs.depth || aovs.normal || aovs.id)
    throw std::invalid_argument("AOVs are not written for native panel images yet (colour only)");
}
}  // namespace

ImageBuffer pack_subpixels(const ImageBuffer& s, bool red_first) {
  if (s.width % 3 != 0 || s.channels != 3)
    throw std::invalid_argument(fmt::format("a subpixel image is 3 RGB samples per pixel, got {} wide, {} channels",
                                            s.width, s.channels));
  ImageBuffer out(s.width / 3, s.height, 3);
  for (int j = 0; j < s.height; ++j)
    for (int i = 0; i < out.width; ++i)
      for (int c = 0; c < 3; ++c) out.at(i, j)[c] = s.at(3 * i + (red_first ? c : 2 - c), j)[c];
  return out;
}

FrameBuffers render_display(const RenderContext& scene, const DisplayCamera& camera, bool red_first,
                            const RenderOptions& opt, RenderStats& stats) {
  refuse_aovs(opt.aovs);
  const RecordingMode mode = camera.geometry().mode;
  FrameBuffers fb = detail::render_lines(scene, camera, opt, stats, [&](const PixelLine& line, PrimaryRay& out) {
    const auto pr = primary_ray_along(line, scene.bounds(), scene.epsilon(), mode);
    if (pr) out = *pr;
    return pr.has_value();
  });
  if (camera.geometry().samples_per_pixel == 3) fb.colour = pack_subpixels(fb.colour, red_first);
  return fb;
}

FrameBuffers render_looking_glass(const RenderContext& scene, const LookingGlassCamera& camera,
                                  const RenderOptions& opt, RenderStats& stats) {
  refuse_aovs(opt.aovs);
  FrameBuffers fb = detail::render_lines(scene, camera, opt, stats, detail::eye_ray);
  fb.colour = pack_subpixels(fb.colour, true);
  return fb;
}

}  // namespace holoray
