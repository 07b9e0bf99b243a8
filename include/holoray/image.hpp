// holoray public API: images as float arrays, their files and their PSNR.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

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

/// PNG (8/16-bit), OpenEXR, JPEG, PPM/PGM, Targa, BMP, Radiance HDR: values
/// as stored (8-bit codes / 255, EXR floats). Throws std::runtime_error
/// naming the file (missing, unreadable, refused size).
HOLORAY_API Image read_image(const std::string& path);
/// .png (8-bit, `encoding`) or .exr (32-bit float). Written to a temporary
/// name in the folder and renamed: a failed write leaves nothing. 1 to 4
/// channels. Throws std::runtime_error naming the path.
HOLORAY_API void write_image(const std::string& path, const Image& image, Encoding encoding = Encoding::linear);
/// PSNR in dB of two images of values in 0..1 nominal, on the 8-bit scale
/// (255^2 / MSE, every colour channel; alpha ignored), as `holoray compare`;
/// +infinity when equal. Throws std::invalid_argument when sizes differ.
HOLORAY_API double psnr(const Image& a, const Image& b);

}  // namespace holoray::api
