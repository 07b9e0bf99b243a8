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

namespace {

holoray::Encoding internal(Encoding e) { return e == Encoding::srgb ? holoray::Encoding::srgb : holoray::Encoding::linear; }

holoray::ExrCompression internal(ExrCompression c) {
  switch (c) {
    case ExrCompression::none: return holoray::ExrCompression::none;
    case ExrCompression::rle: return holoray::ExrCompression::rle;
    case ExrCompression::zips: return holoray::ExrCompression::zips;
    case ExrCompression::piz: return holoray::ExrCompression::piz;
    case ExrCompression::zip: break;
  }
  return holoray::ExrCompression::zip;
}

const ImageBuffer& buffer_of(const Image& image) { return detail::ImageAccess::buffer(image); }

}  // namespace

uint8_t encode_8bit(float v, Encoding encoding) { return holoray::encode_8bit(v, internal(encoding)); }

Image read_image(const std::string& path) { return detail::ImageAccess::wrap(holoray::read_image(path)); }

void write_image(const std::string& path, const Image& image, Encoding encoding, ExrCompression exr) {
  if (image.empty()) throw std::invalid_argument(fmt::format("write_image: '{}': the image is empty", path));
  holoray::write_image(path, buffer_of(image), internal(encoding), internal(exr));
}

struct ImageWriter::Open {
  holoray::ImageWriter writer;
};

ImageWriter::ImageWriter(const std::string& path, int width, int height, int channels, Encoding encoding,
                         ExrCompression exr)
    : open_(new Open{holoray::ImageWriter(path, width, height, channels, internal(encoding), internal(exr))}) {}

ImageWriter::~ImageWriter() = default;

void ImageWriter::write_rows(const Image& rows) { open_->writer.write_rows(buffer_of(rows)); }

void ImageWriter::finish() { open_->writer.finish(); }

void write_animation(const std::string& path, const std::vector<Image>& frames, int fps, Encoding encoding) {
  std::vector<ImageBuffer> buffers;
  buffers.reserve(frames.size());
  for (const Image& f : frames) buffers.push_back(buffer_of(f));
  holoray::write_animation(path, buffers, fps, internal(encoding));
}

bool is_image_output(const std::string& path) { return is_supported_output(path); }

std::string lower_extension(const std::string& path) { return holoray::lower_extension(path); }

std::string aov_path(const std::string& path, const std::string& aov, const std::string& ext) {
  return holoray::aov_path(path, aov, ext);
}

Encoding default_encoding(const std::string& scene_path) {
  return holoray::default_encoding(scene_path) == holoray::Encoding::srgb ? Encoding::srgb : Encoding::linear;
}

Image as_rgb(const Image& image) { return detail::ImageAccess::wrap(holoray::as_rgb(buffer_of(image))); }

Difference compare_images(const Image& a, const Image& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("compare_images: an image is empty");
  const holoray::ImageDifference d = holoray::compare_images(buffer_of(a), buffer_of(b));
  return {d.mse, d.mse_all, d.pixels, d.nan_mismatches};
}

double psnr_from_mse(double mse) { return holoray::psnr_from_mse(mse); }

double Difference::psnr() const { return psnr_from_mse(mse_all); }

double Difference::psnr(int channel) const { return psnr_from_mse(mse.at(static_cast<size_t>(channel))); }

double psnr(const Image& a, const Image& b) { return compare_images(a, b).psnr(); }

}  // namespace holoray::api
