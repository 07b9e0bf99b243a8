// holoray public API: a light-field page anyone can open in a browser
// (docs/guide/web.md): an EIA's sub-aperture views or a quilt's views,
// looked through with the pointer (parallax), refocused by shift-and-add,
// in WebGL2 from plain files that any static server serves.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "holoray/export.hpp"
#include "holoray/image.hpp"
#include "holoray/preview.hpp"

namespace holoray::api {

/// Writes the light-field page of an EIA into the folder `dir` (made if
/// missing): index.html and holoray_web.js (the page: WebGL2, plain ES
/// modules, no build step), light_field.json (what it shows: lenses, grid,
/// pixels per lens, views), views.png (every sub-aperture view, tiled as
/// view_grid tiles them: view (u, v) at tile column u, row v) and eia.png
/// (the EIA). `encoding`: how the image's values become the page's 8-bit
/// sRGB codes (linear for values read from an 8-bit file, which are codes
/// already; srgb for linear light: a render, an EXR). `name` is shown under
/// the view. Each file goes to a temporary name and is renamed. Throws
/// std::invalid_argument as view_grid does (not whole lenses),
/// std::runtime_error naming a file that cannot be written.
HOLORAY_API void write_web_eia(const Image& eia, const EiaLayout& layout, const std::string& dir, const std::string& name,
                               Encoding encoding);

/// The same page for a quilt of `columns` x `rows` views tiled as Looking
/// Glass tools tile them (view 0, the leftmost, bottom left): views.png is
/// the quilt; u counts its views left to right. With `looking_glass`, a
/// device's calibration file (visual.json), copied beside the page as
/// visual.json: the page's Looking Glass window (#show=looking-glass) then
/// shows the device's native image, interlaced in the fragment shader as
/// interlace_quilt interlaces it. Throws std::invalid_argument when the
/// image is not columns x rows views of whole pixels (1 to 4096 views),
/// std::runtime_error naming the calibration when it is malformed, and as
/// write_web_eia.
HOLORAY_API void write_web_quilt(const Image& quilt, int columns, int rows, const std::string& dir,
                                 const std::string& name, Encoding encoding, const std::string& looking_glass = "");

/// The page of an animation's frames (EIAs of one layout, or quilts of one
/// layout), written a frame at a time so that only one is held: frame k's
/// views go to views_NNNN.png (and its EIA to eia_NNNN.png) as add_eia or
/// add_quilt is called; finish() writes the manifest and the page, which
/// plays the frames in a loop at `fps` (a still, one frame: views.png and
/// eia.png, as write_web_eia writes them). Throws as write_web_eia, and
/// std::invalid_argument for a frame whose layout or size is not the first
/// frame's, or finish() without frames.
class HOLORAY_API WebAnimation {
 public:
  WebAnimation(const std::string& dir, const std::string& name, Encoding encoding, double fps = 24);
  ~WebAnimation();
  void add_eia(const Image& eia, const EiaLayout& layout);
  void add_quilt(const Image& quilt, int columns, int rows, const std::string& looking_glass = "");
  void finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Serves the folder `dir` over HTTP on `host`:`port` (0: a free port) until
/// the process ends, so that the page's modules load (browsers refuse them
/// from file://). `listening` is called once with the page's address when
/// the socket is bound. Loads holoray_http.so (cpp-httplib) on first use.
/// Throws std::runtime_error when `dir` is no folder or the port cannot be
/// bound.
HOLORAY_API void serve_folder(const std::string& dir, const std::string& host, int port,
                              const std::function<void(const std::string& url)>& listening);

}  // namespace holoray::api
