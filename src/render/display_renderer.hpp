// holoray/render: renders a display's native panel image (issue 14): every
// sample of the display camera (camera/display_camera.hpp) traced along its
// own line, then each colour subpixel's channel taken from its own sample.
// No resampling: the panel image is what the panel shows, pixel for pixel.
#pragma once

#include "camera/display_camera.hpp"
#include "display/looking_glass.hpp"
#include "render/renderer.hpp"

namespace holoray {

/// The panel image (geometry().width x height pixels, RGB): with subpixels,
/// channel R of pixel (i, j) is the R of sample (3i + position of R, j), and
/// so on (SubpixelOrder rgb: R left; bgr: B left); without, each pixel is
/// its sample. The recording mode is the geometry's (orthoscopic rays start
/// beyond the scene and take the last surface along the line). Samples,
/// packets and tiles as render_view's; the result does not depend on the
/// thread count. `red_first` is true for RGB order. Throws
/// std::invalid_argument for AOVs (not written for panel images yet), spp < 1
/// or threads < 0.
FrameBuffers render_display(const RenderContext& scene, const DisplayCamera& camera, bool red_first,
                            const RenderOptions& options, RenderStats& stats);

/// A Looking Glass panel traced natively (display/looking_glass.hpp): each
/// subpixel along its own view, channels packed as RGB (flipSubp is in the
/// views already). Pinhole rays from each view's eye. Throws as render_display.
FrameBuffers render_looking_glass(const RenderContext& scene, const LookingGlassCamera& camera,
                                  const RenderOptions& options, RenderStats& stats);

/// Packs a subpixel image (3W x H samples) into the W x H panel image:
/// channel c of pixel i from sample 3i + (red_first ? c : 2 - c).
ImageBuffer pack_subpixels(const ImageBuffer& samples, bool red_first);

}  // namespace holoray
