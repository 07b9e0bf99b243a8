// holoray/image: reading and writing images. PNG through libpng, OpenEXR
// through OpenEXR, animated GIF through giflib; read also JPEG (libjpeg-turbo)
// and PPM/PGM, Targa, BMP, Radiance HDR (stb_image). Every write
// goes to a temporary name in the destination folder and is renamed into
// place, so a failed or interrupted write never leaves a partial file.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace holoray {

/// How linear values become 8-bit codes in PNG output.
enum class Encoding { linear, srgb };

/// OpenEXR's lossless compressions, by OpenEXR's names. zip (16-row blocks)
/// is the default; none writes a 1024x1024 EIA with three AOVs in a third
/// of zip's time (0.09 s against 0.25 s on 2 cores) at about twice the size:
/// for files read once and deleted, such as the Blender add-on's.
enum class ExrCompression { none, rle, zips, zip, piz };

/// 8-bit code of a linear value v (in 0..1 nominal): floor(255*e(v) + 0.5)
/// clamped to 0..255, where e is the identity (linear) or the sRGB transfer
/// function (IEC 61966-2-1). NaN gives 0.
uint8_t encode_8bit(float v, Encoding encoding);

/// encode_8bit of `count` values, the same codes; the linear case runs four
/// values per SSE2 pass (255 v + 1/2 is exact in double, so truncation after
/// clamping is the floor) and large runs on every core.
void encode_8bit(const float* values, size_t count, uint8_t* codes, Encoding encoding);
/// The same on the calling thread alone: for callers already running as
/// one of several parallel tasks (the PNG writer's deflate segments).
void encode_8bit_here(const float* values, size_t count, uint8_t* codes, Encoding encoding);

/// Writes `image` to `path`; the format follows the extension: `.png` (8-bit,
/// encoded as above) or `.exr` (32-bit float, linear). Throws
/// std::runtime_error naming the path and reason (unknown extension, folder
/// missing or not writable, disk full); the destination is then untouched.
void write_image(const std::string& path, const ImageBuffer& image, Encoding encoding = Encoding::linear,
                 ExrCompression exr = ExrCompression::zip);

/// An image file written band by band, top to bottom, as write_image writes
/// it whole (same format, encoding and bytes): a giant EIA gathered from MPI
/// ranks is written while it arrives, never held whole. The file appears
/// under its name only when finish() succeeds; until then it is a temporary
/// that the destructor removes. Throws as write_image, naming `path`;
/// std::logic_error for rows that do not fit or a finish() before the last row.
class ImageWriter {
 public:
  ImageWriter(const std::string& path, int width, int height, int channels, Encoding encoding = Encoding::linear,
              ExrCompression exr = ExrCompression::zip);
  ~ImageWriter();
  ImageWriter(const ImageWriter&) = delete;
  ImageWriter& operator=(const ImageWriter&) = delete;
  /// The next rows.height rows (rows.width and rows.channels the image's).
  void write_rows(const ImageBuffer& rows);
  /// Closes the file and gives it its name.
  void finish();

 private:
  struct Open;
  std::unique_ptr<Open> open_;  // null once finished
};

/// Writes `frames` (all the same size, RGB) as an animated GIF looping
/// forever at `fps` frames per second, through a temporary name as
/// write_image. Throws std::runtime_error naming the path (not `.gif`, no
/// frames, sizes that differ, folder missing, disk full).
void write_animation(const std::string& path, const std::vector<ImageBuffer>& frames, int fps,
                     Encoding encoding = Encoding::linear);

/// The largest image read_image reads, in pixels; larger headers are
/// refused before anything is allocated.
inline constexpr int64_t kMaxImagePixels = int64_t{1} << 30;

/// What read_image and read_image_header throw: what() names the file,
/// reason() is the cause alone, for callers that name the file their way.
class ImageReadError : public std::runtime_error {
 public:
  ImageReadError(const std::string& path, const std::string& reason);
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

/// What an image file's header says, read without its pixels.
struct ImageHeader {
  int width = 0, height = 0, channels = 0;
  std::string format;  ///< "png", "openexr", "jpeg", "pnm", "targa", "bmp", "hdr"
};

/// The header of any image read_image reads; the format is found by the
/// file's signature (by the extension only for Targa, which has none).
/// Throws ImageReadError.
ImageHeader read_image_header(const std::string& path);

/// Reads PNG (8/16-bit, palettes expanded), OpenEXR (float; R, G, B, A first),
/// JPEG, binary PPM/PGM, Targa, BMP and Radiance HDR. Values as stored:
/// integer codes times 1/max (no decoding of sRGB, alpha not premultiplied),
/// rows from the top. Throws ImageReadError (missing, unknown format,
/// corrupt, more than kMaxImagePixels). `header`, when given, gets what
/// read_image_header says (the format, say), without reading it twice.
ImageBuffer read_image(const std::string& path, ImageHeader* header = nullptr);

/// An image's 8-bit codes, rows from the top, channels interleaved, as the
/// file holds them: read_image's values times 255 (v = code / 255 there),
/// without the float image (a 2048x2048 RGB texture is 48 MiB of floats).
struct ImageCodes {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> codes;
};
/// read_image's codes for an 8-bit PNG or a JPEG; nullopt for every other
/// image (read it with read_image). Throws as read_image; `header` as there.
std::optional<ImageCodes> read_image_codes(const std::string& path, ImageHeader* header = nullptr);

/// The extension of `path`, dot included, in lower case ("a/B.PNG" -> ".png").
std::string lower_extension(const std::string& path);

/// RGB of any image: the first three channels, or a grey channel repeated.
ImageBuffer as_rgb(const ImageBuffer& image);

/// True for the extensions write_image accepts (".png", ".exr", any case).
bool is_supported_output(const std::string& path);

/// The encoding a scene file's 8-bit images get unless told (--encoding
/// auto): srgb for a mesh scene (glTF, OBJ, ...: its colours are linear
/// light, and Blender's and every glTF viewer's images are sRGB-encoded),
/// linear for NFF and Tachyon scenes (Tachyon writes its linear values as
/// codes, and comparisons with tachyon-nox and POV-Ray read them so).
Encoding default_encoding(const std::string& scene_path);

/// `<stem>.<aov>.<ext>` beside `path` (e.g. out.png, depth, exr -> out.depth.exr).
std::string aov_path(const std::string& path, const std::string& aov, const std::string& ext);

}  // namespace holoray
