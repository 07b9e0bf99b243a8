#include <fmt/format.h>

#include <stdexcept>

#include "api/internal.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"

namespace holoray::api {

namespace detail {

Image ImageAccess::wrap(ImageBuffer&& buffer) {
  Image out;
  auto owned = std::make_shared<ImageBuffer>(std::move(buffer));
  out.data_ = owned->data.data();
  out.width_ = owned->width;
  out.height_ = owned->height;
  out.channels_ = owned->channels;
  out.storage_ = std::move(owned);
  return out;
}

const ImageBuffer& ImageAccess::buffer(const Image& image) {
  static const ImageBuffer empty;
  return image.storage_ ? *static_cast<const ImageBuffer*>(image.storage_.get()) : empty;
}

}  // namespace detail

Image::Image(int width, int height, int channels, float fill) {
  if (width < 1 || height < 1 || channels < 1 || channels > 4)
    throw std::invalid_argument(fmt::format("Image: expected a size of at least 1x1 and 1 to 4 channels, got {}x{}x{}",
                                            width, height, channels));
  if (static_cast<int64_t>(width) * height > kMaxImagePixels)
    throw std::length_error(fmt::format("Image: {}x{} is more than {} pixels", width, height, kMaxImagePixels));
  *this = detail::ImageAccess::wrap(ImageBuffer(width, height, channels, fill));
}

Image read_image(const std::string& path) { return detail::ImageAccess::wrap(holoray::read_image(path)); }

void write_image(const std::string& path, const Image& image, Encoding encoding) {
  if (image.empty()) throw std::invalid_argument(fmt::format("write_image: '{}': the image is empty", path));
  holoray::write_image(path, detail::ImageAccess::buffer(image),
                       encoding == Encoding::srgb ? holoray::Encoding::srgb : holoray::Encoding::linear);
}

double psnr(const Image& a, const Image& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("psnr: an image is empty");
  return compare_images(detail::ImageAccess::buffer(a), detail::ImageAccess::buffer(b)).psnr_all();
}

}  // namespace holoray::api
