#include "image/image_io.hpp"

#include "image/formats.hpp"
#include "util/parallel.hpp"
#include "image/srgb_code.hpp"

#include <emmintrin.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace holoray {

namespace fs = std::filesystem;

Encoding default_encoding(const std::string& scene_path) {
  const std::string ext = lower_extension(scene_path);
  return ext == ".nff" || ext == ".dat" ? Encoding::linear : Encoding::srgb;
}

std::string lower_extension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

ImageBuffer as_rgb(const ImageBuffer& image) {
  if (image.channels == 3) return image;
  ImageBuffer rgb(image.width, image.height, 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) rgb.at(x, y)[c] = image.at(x, y)[std::min(c, image.channels - 1)];
  return rgb;
}

uint8_t encode_8bit(float v, Encoding encoding) {
  if (encoding == Encoding::srgb) return srgb_code(v);
  if (std::isnan(v)) return 0;
  const double code = std::floor(255.0 * static_cast<double>(v) + 0.5);
  return static_cast<uint8_t>(std::clamp(code, 0.0, 255.0));
}

namespace {

// floor(clamp(255 v + 0.5, 0, 255)) per value, NaN to 0. Four values per
// SSE2 pass, with the scalar loop's operations and selects (maxpd and minpd
// keep its operand order, so NaN still gives 0): the same codes. GCC leaves
// the scalar loop unvectorised (its selects, under -ftrapping-math).
void encode_linear(const float* v, size_t n, uint8_t* out) {
  const __m128d scale = _mm_set1_pd(255.0), half = _mm_set1_pd(0.5), zero = _mm_setzero_pd(), top = _mm_set1_pd(255.0);
  auto codes = [&](__m128 f2) {  // the low two floats of f2
    __m128d x = _mm_add_pd(_mm_mul_pd(scale, _mm_cvtps_pd(f2)), half);
    x = _mm_min_pd(_mm_max_pd(x, zero), top);
    return _mm_cvttpd_epi32(x);
  };
  size_t k = 0;
  for (; k + 4 <= n; k += 4) {
    const __m128 f = _mm_loadu_ps(v + k);
    const __m128i lo = codes(f), hi = codes(_mm_movehl_ps(f, f));
    const __m128i words = _mm_packs_epi32(_mm_unpacklo_epi64(lo, hi), _mm_setzero_si128());
    const int four = _mm_cvtsi128_si32(_mm_packus_epi16(words, words));
    std::memcpy(out + k, &four, 4);
  }
  for (; k < n; ++k) {
    double x = 255.0 * static_cast<double>(v[k]) + 0.5;  // exact: a float times 255 fits a double's mantissa
    x = x > 0.0 ? x : 0.0;                              // NaN too
    x = x < 255.0 ? x : 255.0;
    out[k] = static_cast<uint8_t>(static_cast<int>(x));  // truncation of a non-negative value: the floor
  }
}

}  // namespace

void encode_8bit_here(const float* values, size_t count, uint8_t* codes, Encoding encoding) {
  if (encoding == Encoding::linear) encode_linear(values, count, codes);
  else
    for (size_t k = 0; k < count; ++k) codes[k] = srgb_code(values[k]);
}

void encode_8bit(const float* values, size_t count, uint8_t* codes, Encoding encoding) {
  constexpr size_t kChunk = size_t{1} << 16;
  parallel_for_n(static_cast<int>((count + kChunk - 1) / kChunk), 0, [&](int slot) {
    const size_t k = static_cast<size_t>(slot);
    const size_t begin = k * kChunk;
    encode_8bit_here(values + begin, std::min(count, begin + kChunk) - begin, codes + begin, encoding);
  });
}

bool is_supported_output(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".png" || e == ".exr";
}

std::string aov_path(const std::string& path, const std::string& aov, const std::string& ext) {
  const fs::path p(path);
  return (p.parent_path() / fmt::format("{}.{}.{}", p.stem().string(), aov, ext)).string();
}

struct ImageWriter::Open {
  std::string path;
  fs::path tmp, dest;
  std::unique_ptr<formats::ScanlineOutput> out;
  int width = 0, height = 0, channels = 0, next_row = 0;

  [[noreturn]] void fail(const std::string& why) {
    std::string reason = why;
    if (reason.empty()) reason = std::strerror(errno);
    // The user never named the temporary file: speak of the one they did.
    for (size_t at; (at = reason.find(tmp.string())) != std::string::npos;) reason.replace(at, tmp.string().size(), path);
    out.reset();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path, reason));
  }
};

namespace {

// The hidden temporary beside `dest` that a write goes to before the rename.
fs::path temporary_for(const std::string& path, const std::string& ext) {
  const fs::path dest(path);
  const fs::path dir = dest.parent_path().empty() ? fs::path(".") : dest.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw std::runtime_error(fmt::format("cannot write '{}': folder '{}' does not exist", path, dir.string()));
  return dir / fmt::format(".{}.tmp{}{}", dest.stem().string(), static_cast<long>(::getpid()), ext);
}

}  // namespace

ImageWriter::ImageWriter(const std::string& path, int width, int height, int channels, Encoding encoding,
                         ExrCompression exr)
    : open_(std::make_unique<Open>()) {
  Open& o = *open_;
  o.path = path;
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".exr")
    throw std::runtime_error(fmt::format("cannot write '{}': unsupported extension '{}' (use .png or .exr)", path, ext));
  o.dest = fs::path(path);
  o.tmp = temporary_for(path, ext);
  o.width = width, o.height = height, o.channels = channels;
  try {
    o.out = ext == ".png" ? formats::open_png(o.tmp.string(), width, height, channels, encoding)
                          : formats::open_exr(o.tmp.string(), width, height, channels, exr);
  } catch (const std::runtime_error& e) {
    o.fail(e.what());
  }
}

ImageWriter::~ImageWriter() {
  if (!open_) return;
  open_->out.reset();
  std::error_code ec;
  fs::remove(open_->tmp, ec);
}

void ImageWriter::write_rows(const ImageBuffer& rows) {
  Open& o = *open_;
  if (rows.width != o.width || rows.channels != o.channels || o.next_row + rows.height > o.height)
    throw std::logic_error(fmt::format("'{}': rows of {}x{}x{} after row {} do not fit a {}x{}x{} image", o.path, rows.width,
                                       rows.height, rows.channels, o.next_row, o.width, o.height, o.channels));
  try {
    o.out->write_rows(rows.data.data(), rows.height);
  } catch (const std::runtime_error& e) {
    o.fail(e.what());
  }
  o.next_row += rows.height;
}

void ImageWriter::finish() {
  Open& o = *open_;
  if (o.next_row != o.height)
    throw std::logic_error(fmt::format("'{}': {} of {} rows written", o.path, o.next_row, o.height));
  try {
    o.out->close();
  } catch (const std::runtime_error& e) {
    o.fail(e.what());
  }
  o.out.reset();
  std::error_code ec;
  fs::rename(o.tmp, o.dest, ec);
  if (ec) o.fail(ec.message());
  open_.reset();
}

void write_image(const std::string& path, const ImageBuffer& image, Encoding encoding, ExrCompression exr) {
  ImageWriter writer(path, image.width, image.height, image.channels, encoding, exr);
  writer.write_rows(image);
  writer.finish();
}

void write_animation(const std::string& path, const std::vector<ImageBuffer>& frames, int fps, Encoding encoding) {
  if (lower_extension(path) != ".gif")
    throw std::runtime_error(fmt::format("cannot write '{}': an animation is written as .gif", path));
  if (frames.empty()) throw std::runtime_error(fmt::format("cannot write '{}': no frames", path));
  if (fps < 1) throw std::runtime_error(fmt::format("cannot write '{}': expected at least 1 frame per second, got {}", path, fps));
  std::vector<std::vector<uint8_t>> codes;
  for (size_t f = 0; f < frames.size(); ++f) {
    const ImageBuffer& img = frames[f];
    if (img.width != frames[0].width || img.height != frames[0].height || img.channels != 3)
      throw std::runtime_error(fmt::format("cannot write '{}': frame {} is {}x{}x{}, frame 0 {}x{}x3", path, f, img.width,
                                           img.height, img.channels, frames[0].width, frames[0].height));
    std::vector<uint8_t>& bytes = codes.emplace_back(img.data.size());
    encode_8bit(img.data.data(), img.data.size(), bytes.data(), encoding);
  }
  const fs::path tmp = temporary_for(path, ".gif");
  std::error_code ec;
  try {
    formats::write_gif(tmp.string(), frames[0].width, frames[0].height, codes, fps);
    fs::rename(tmp, path, ec);
    if (ec) throw std::runtime_error(ec.message());
  } catch (const std::runtime_error& e) {
    fs::remove(tmp, ec);
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path, e.what()));
  }
}

namespace formats {

std::string detect(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(std::strerror(errno));
  unsigned char m[10] = {};
  in.read(reinterpret_cast<char*>(m), sizeof m);
  const auto n = in.gcount();
  if (n >= 8 && !std::memcmp(m, "\x89PNG\r\n\x1a\n", 8)) return "png";
  if (n >= 4 && m[0] == 0x76 && m[1] == 0x2f && m[2] == 0x31 && m[3] == 0x01) return "openexr";
  if (n >= 3 && m[0] == 0xff && m[1] == 0xd8 && m[2] == 0xff) return "jpeg";
  if (n >= 2 && m[0] == 'P' && m[1] >= '1' && m[1] <= '6') return "pnm";
  if (n >= 2 && m[0] == 'B' && m[1] == 'M') return "bmp";
  if (n >= 2 && m[0] == '#' && m[1] == '?') return "hdr";
  if (lower_extension(file) == ".tga") return "targa";
  throw std::runtime_error("not an image holoray reads (PNG, OpenEXR, JPEG, PPM/PGM, Targa, BMP, Radiance HDR)");
}

}  // namespace formats

namespace {

// Which reader a format goes to.
formats::Header header_by_format(const std::string& path, const std::string& format) {
  if (format == "png") return formats::png_header(path);
  if (format == "openexr") return formats::exr_header(path);
  if (format == "jpeg") return formats::jpeg_header(path);
  return formats::stb_header(path, format);
}

}  // namespace

ImageReadError::ImageReadError(const std::string& path, const std::string& reason)
    : std::runtime_error(fmt::format("cannot read image '{}': {}", path, reason)), reason_(reason) {}

namespace {
// Absurd sizes are refused before anything is allocated.
void refuse_absurd(const std::string& path, const ImageHeader& h) {
  if (h.width < 1 || h.height < 1 || h.channels < 1 || int64_t{h.width} * h.height > kMaxImagePixels)
    throw ImageReadError(path, fmt::format("{}x{} pixels, {} channels (at most {} pixels)", h.width, h.height, h.channels,
                                           kMaxImagePixels));
}
}  // namespace

ImageHeader read_image_header(const std::string& path) {
  try {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw std::runtime_error(fs::exists(path, ec) ? "not a regular file" : "no such file");
    const std::string format = formats::detect(path);
    const formats::Header h = header_by_format(path, format);
    return {h.width, h.height, h.channels, h.format};
  } catch (const std::runtime_error& e) {
    throw ImageReadError(path, e.what());
  }
}

ImageBuffer read_image(const std::string& path, ImageHeader* header) {
  const ImageHeader h = read_image_header(path);
  if (header) *header = h;
  refuse_absurd(path, h);
  try {
    if (h.format == "png") return formats::read_png(path);
    if (h.format == "openexr") return formats::read_exr(path);
    if (h.format == "jpeg") return formats::read_jpeg(path);
    return formats::read_stb(path, h.format);
  } catch (const std::runtime_error& e) {
    throw ImageReadError(path, e.what());
  }
}

std::optional<ImageCodes> read_image_codes(const std::string& path, ImageHeader* header) {
  const ImageHeader h = read_image_header(path);
  if (header) *header = h;
  if (h.format != "png" && h.format != "jpeg") return std::nullopt;
  refuse_absurd(path, h);
  try {
    if (h.format == "png") return formats::read_png_codes(path);
    return formats::read_jpeg_codes(path);
  } catch (const std::runtime_error& e) {
    throw ImageReadError(path, e.what());
  }
}

}  // namespace holoray
