// holoray/image, internal: one file per image format, each written against
// the format's own library (libpng, OpenEXR, libjpeg-turbo, giflib, stb_image
// for the simple raster formats). image_io.cpp picks among them and owns the
// temporary-name-then-rename rule; a format only reads or writes bytes.
//
// Why these libraries and not one umbrella library: holoray starts in a few
// milliseconds with them, where Debian's OpenImageIO alone loads about 270
// shared libraries and costs a third of a second per process.
//
// Every function throws std::runtime_error with the reason only (no path):
// the caller names the file.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "image/image_io.hpp"

namespace holoray::formats {

/// A file being written scanline by scanline, rows from the top.
class ScanlineOutput {
 public:
  virtual ~ScanlineOutput() = default;
  /// `count` rows of width*channels linear values each.
  virtual void write_rows(const float* values, int count) = 0;
  /// Flushes and closes; the file is complete when this returns.
  virtual void close() = 0;
};

/// How a PNG's rows are compressed: the zlib level (0..9) and strategy
/// (zlib's Z_* constants) and the row filters (libpng's PNG_FILTER_* bits).
/// With segment_bytes > 0 the image data is deflated on every core in
/// segments of that many bytes (parallel_deflate.hpp), which needs filters
/// PNG_FILTER_NONE; 0 leaves it to libpng, on one thread.
struct PngCompression {
  int level, strategy, filters;
  size_t segment_bytes = 0;
};

/// The one write_image uses, chosen by measurement (png_format.cpp says
/// which measurement; bench/png_encode.cpp repeats it).
PngCompression default_png_compression();

/// 8-bit PNG (channels 1..4: grey, grey+alpha, RGB, RGBA), codes from
/// encode_8bit; tagged gAMA 1.0 (linear) or sRGB.
std::unique_ptr<ScanlineOutput> open_png(const std::string& file, int width, int height, int channels, Encoding encoding,
                                         PngCompression compression = default_png_compression());

/// 32-bit float OpenEXR, compressed as asked (ZIP: 16 scanlines a block),
/// channels named as OpenImageIO names them (1: Y; 2..4: R, G, B, A; then
/// channelN), so files written before and after the change read the same.
std::unique_ptr<ScanlineOutput> open_exr(const std::string& file, int width, int height, int channels,
                                         ExrCompression compression = ExrCompression::zip);

/// What a reader finds in a header, before any pixel is allocated.
struct Header {
  int width = 0, height = 0, channels = 0;
  std::string format;  ///< "png", "openexr", "jpeg", "pnm", "targa", "bmp", "hdr"
};

/// The format by the file's first bytes (the extension only for Targa, which
/// has no signature); throws for none holoray reads.
std::string detect(const std::string& file);

Header png_header(const std::string& file);
ImageBuffer read_png(const std::string& file);  ///< 8- or 16-bit codes scaled to 0..1, palettes expanded
std::optional<ImageCodes> read_png_codes(const std::string& file);  ///< read_png's 8-bit codes; nullopt for 16-bit
Header exr_header(const std::string& file);
ImageBuffer read_exr(const std::string& file);  ///< first part; R, G, B, A first, other channels after in file order
Header jpeg_header(const std::string& file);
ImageBuffer read_jpeg(const std::string& file);  ///< grey or RGB, libjpeg's default (accurate integer) decoding
ImageCodes read_jpeg_codes(const std::string& file);  ///< read_jpeg's codes
Header stb_header(const std::string& file, const std::string& format);
ImageBuffer read_stb(const std::string& file, const std::string& format);  ///< PNM (binary), Targa, BMP, Radiance HDR, rows from the top

/// An animated GIF looping forever, one local palette per frame (giflib's
/// median-cut quantizer), frame delay round(100 / fps) hundredths.
/// `frames` are width*height*3 8-bit RGB codes each.
void write_gif(const std::string& file, int width, int height, const std::vector<std::vector<uint8_t>>& frames, int fps);

}  // namespace holoray::formats
