// holoray public API: images as float arrays, their files and their PSNR.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "holoray/export.hpp"

namespace holoray::api {

namespace detail {
struct ImageAccess;
}

/// A float image: row-major, channels interleaved, row 0 at the top; colour
/// is linear RGB. Copies share the samples (a render's buffers are handed
/// out without copying: storage() keeps them alive for a numpy array).
class HOLORAY_API Image {
 public:
  Image() = default;
  /// width x height x channels samples, all `fill`. Throws
  /// std::invalid_argument for a size below 1 or above 2^30 pixels.
  Image(int width, int height, int channels, float fill = 0.0f);

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  size_t size() const { return static_cast<size_t>(width_) * height_ * channels_; }
  bool empty() const { return size() == 0; }
  float* data() { return data_; }
  const float* data() const { return data_; }
  /// Pixel (x, y)'s first channel.
  float* at(int x, int y) { return data_ + (static_cast<size_t>(y) * width_ + x) * channels_; }
  const float* at(int x, int y) const { return data_ + (static_cast<size_t>(y) * width_ + x) * channels_; }
  /// The owner of the samples: holding it keeps data() valid.
  std::shared_ptr<void> storage() const { return storage_; }

 private:
  friend struct detail::ImageAccess;
  std::shared_ptr<void> storage_;
  float* data_ = nullptr;
  int width_ = 0, height_ = 0, channels_ = 0;
};

/// How linear values become 8-bit PNG codes: as they are, or through the
/// sRGB transfer function (IEC 61966-2-1).
enum class Encoding { linear, srgb };

/// OpenEXR's lossless compressions, by OpenEXR's names. zip (16-row blocks)
/// is the default; none is the largest and the fastest to write and read
/// (for files read once and deleted, such as the Blender add-on's).
enum class ExrCompression { none, rle, zips, zip, piz };

/// The 8-bit code of a linear value v (0..1 nominal): floor(255 e(v) + 1/2)
/// clamped to 0..255, e the identity or the sRGB transfer function; NaN: 0.
HOLORAY_API uint8_t encode_8bit(float v, Encoding encoding);

/// PNG (8/16-bit), OpenEXR, JPEG, PPM/PGM, Targa, BMP, Radiance HDR: values
/// as stored (8-bit codes / 255, EXR floats). Throws std::runtime_error
/// naming the file (missing, unreadable, refused size).
HOLORAY_API Image read_image(const std::string& path);
/// .png (8-bit, `encoding`) or .exr (32-bit float, `exr`). Written to a
/// temporary name in the folder and renamed: a failed write leaves nothing.
/// 1 to 4 channels. Throws std::runtime_error naming the path.
HOLORAY_API void write_image(const std::string& path, const Image& image, Encoding encoding = Encoding::linear,
                             ExrCompression exr = ExrCompression::zip);

/// An image file written band by band, top to bottom, with the same bytes
/// as write_image: a giant EIA gathered from MPI ranks is written as it
/// arrives, never held whole. The file gets its name only when finish()
/// succeeds; until then it is a temporary the destructor removes. Throws as
/// write_image; std::logic_error for rows that do not fit or an early finish().
class HOLORAY_API ImageWriter {
 public:
  ImageWriter(const std::string& path, int width, int height, int channels, Encoding encoding = Encoding::linear,
              ExrCompression exr = ExrCompression::zip);
  ~ImageWriter();
  ImageWriter(const ImageWriter&) = delete;
  ImageWriter& operator=(const ImageWriter&) = delete;
  /// The next rows.height() rows (the image's width and channels).
  void write_rows(const Image& rows);
  /// Closes the file and gives it its name.
  void finish();

 private:
  struct Open;
  std::unique_ptr<Open> open_;
};

/// Image files written on a thread of its own, in the order given, each as
/// write_image writes it (a temporary name, then renamed), so that the caller
/// traces its next frame meanwhile (`holoray animate`). At most `depth` (>= 1)
/// images wait: submit() blocks beyond that, so memory stays bounded. A
/// failed write stops the thread (nothing after it is written) and its error
/// is thrown again by the next submit() or by finish(). The destructor
/// writes the images already given (an interrupted run keeps every frame it
/// finished) and swallows errors: call finish() to see them.
class HOLORAY_API BackgroundWriter {
 public:
  /// Throws std::invalid_argument for depth < 1.
  explicit BackgroundWriter(int depth = 2);
  ~BackgroundWriter();
  BackgroundWriter(const BackgroundWriter&) = delete;
  BackgroundWriter& operator=(const BackgroundWriter&) = delete;
  /// Queues `image` (shared, not copied: leave its samples alone) for `path`.
  void submit(std::string path, Image image, Encoding encoding = Encoding::linear, ExrCompression exr = ExrCompression::zip);
  /// Waits until every image given is written; throws the first write's error.
  void finish();
  /// Seconds the thread has spent writing, encoding included.
  double write_seconds() const;

 private:
  struct Queue;
  std::unique_ptr<Queue> queue_;
};

/// `frames` (one size, RGB) as an animated GIF looping at `fps` frames per
/// second, written as write_image. Throws std::runtime_error naming the path
/// (not .gif, no frames, sizes that differ, folder missing, disk full).
HOLORAY_API void write_animation(const std::string& path, const std::vector<Image>& frames, int fps,
                                 Encoding encoding = Encoding::linear);

/// True for the extensions write_image writes (.png, .exr, any case).
HOLORAY_API bool is_image_output(const std::string& path);
/// The extension of `path`, dot included, in lower case ("a/B.PNG": ".png").
HOLORAY_API std::string lower_extension(const std::string& path);
/// `<stem>.<aov>.<ext>` beside `path` (out.png, depth, exr: out.depth.exr).
HOLORAY_API std::string aov_path(const std::string& path, const std::string& aov, const std::string& ext);
/// The encoding a scene file's 8-bit images get unless told: srgb for a mesh
/// scene (glTF, OBJ, ...: linear light, shown sRGB-encoded by Blender and
/// every glTF viewer), linear for NFF and Tachyon (whose tools write their
/// linear values as codes).
HOLORAY_API Encoding default_encoding(const std::string& scene_path);
/// RGB of any image: its first three channels, or its grey channel thrice.
HOLORAY_API Image as_rgb(const Image& image);

/// An image against another, on the 8-bit scale (values times 255), colour
/// channels only (as `holoray compare`).
struct HOLORAY_API Difference {
  std::array<double, 3> mse{};  ///< per channel (R, G, B)
  double mse_all = 0;           ///< over the three channels
  int64_t pixels = 0;
  /// Samples NaN in one image only, left out of the MSE (NaN against NaN
  /// is equal: the depth AOV's background).
  int64_t nan_mismatches = 0;
  double psnr() const;             ///< dB over the three channels; +infinity when equal
  double psnr(int channel) const;  ///< dB of channel 0..2
};
/// MSE per channel and over all; throws std::invalid_argument when the
/// sizes differ or an image is empty.
HOLORAY_API Difference compare_images(const Image& a, const Image& b);
/// PSNR in dB of an MSE on the 8-bit scale (255^2 / MSE); +infinity for 0.
HOLORAY_API double psnr_from_mse(double mse);
/// PSNR in dB of two images of values in 0..1 nominal, on the 8-bit scale
/// (every colour channel; alpha ignored), as `holoray compare`; +infinity
/// when equal. Throws std::invalid_argument when sizes differ.
HOLORAY_API double psnr(const Image& a, const Image& b);

}  // namespace holoray::api
