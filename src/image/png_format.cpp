// PNG through libpng. libpng reports errors by longjmp; every call that can
// fail sits alone in a small function that sets the jump point, so no C++
// object is ever jumped over.
#include <png.h>
#include <zlib.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/formats.hpp"
#include "image/parallel_deflate.hpp"

namespace holoray::formats {

namespace {

// libpng's messages land here; the longjmp follows in png_error's caller.
struct Messages {
  char text[256] = {};
};

void on_error(png_structp png, png_const_charp message) {
  auto* m = static_cast<Messages*>(png_get_error_ptr(png));
  std::snprintf(m->text, sizeof m->text, "%s", message);
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

struct File {
  std::FILE* f = nullptr;
  File(const std::string& path, const char* mode) : f(std::fopen(path.c_str(), mode)) {
    if (!f) throw std::runtime_error(std::strerror(errno));
  }
  ~File() {
    if (f) std::fclose(f);
  }
  // fclose's own failure (disk full on the last block) is a write error.
  void close() {
    const int rc = std::fclose(f);
    f = nullptr;
    if (rc != 0) throw std::runtime_error(std::strerror(errno));
  }
};

bool write_setup(png_structp png, png_infop info, std::FILE* f, int w, int h, int color_type, bool srgb,
                 PngCompression compression) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, f);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8, color_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // The codes' meaning, so viewers show them as intended: sRGB, or linear.
  if (srgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  else png_set_gAMA_fixed(png, info, PNG_FP_1);
  png_set_compression_level(png, compression.level);
  png_set_compression_strategy(png, compression.strategy);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, compression.filters);
  png_write_info(png, info);
  return true;
}

bool write_row(png_structp png, png_const_bytep row) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_write_row(png, row);
  return true;
}

// A chunk of bytes made here (the segmented IDAT data, IEND after it).
bool write_chunk(png_structp png, const char* type, const uint8_t* data, size_t n) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_write_chunk(png, reinterpret_cast<png_const_bytep>(type), data, n);
  return true;
}

bool write_end(png_structp png, png_infop info) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_write_end(png, info);
  return true;
}

class PngOutput final : public ScanlineOutput {
 public:
  PngOutput(const std::string& path, int w, int h, int channels, Encoding encoding, PngCompression compression)
      : file_(path, "wb"), width_(w), channels_(channels), encoding_(encoding) {
    static constexpr int kType[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                     PNG_COLOR_TYPE_RGB_ALPHA};
    if (channels < 1 || channels > 4) throw std::runtime_error("PNG holds 1 to 4 channels");
    if (compression.segment_bytes > 0) {
      if (compression.filters != PNG_FILTER_NONE)
        throw std::invalid_argument("segmented PNG compression writes rows without a filter");
      deflate_ = std::make_unique<ParallelDeflate>(compression.level, compression.strategy, compression.segment_bytes);
    }
    png_ = png_create_write_struct(PNG_LIBPNG_VER_STRING, &messages_, on_error, on_warning);
    if (!png_) throw std::runtime_error("out of memory");
    info_ = png_create_info_struct(png_);
    if (!info_ || !write_setup(png_, info_, file_.f, w, h, kType[channels], encoding == Encoding::srgb, compression)) {
      png_destroy_write_struct(&png_, &info_);  // the destructor does not run for a constructor that throws
      fail();
    }
  }
  ~PngOutput() override { png_destroy_write_struct(&png_, &info_); }

  void write_rows(const float* values, int count) override {
    const size_t n = size_t(width_) * size_t(channels_);
    if (deflate_) {
      // The IDAT data: each row behind its filter-type byte (0: None), made
      // a segment at a time on the deflating threads.
      deflate_->add_rows(
          size_t(count), n + 1,
          [&](size_t first, size_t rows, uint8_t* dst) {
            for (size_t y = 0; y < rows; ++y, dst += n + 1) {
              dst[0] = 0;
              encode_8bit_here(values + n * (first + y), n, dst + 1, encoding_);
            }
          },
          [&](const uint8_t* data, size_t bytes) {
            if (!write_chunk(png_, "IDAT", data, bytes)) fail();
          });
      return;
    }
    reserve_codes(n * size_t(count));
    encode_8bit(values, codes_.size(), codes_.data(), encoding_);
    for (int y = 0; y < count; ++y)
      if (!write_row(png_, codes_.data() + n * size_t(y))) fail();
  }

  void close() override {
    if (deflate_) {
      const std::vector<uint8_t> tail = deflate_->finish();
      if (!write_chunk(png_, "IDAT", tail.data(), tail.size()) || !write_chunk(png_, "IEND", nullptr, 0)) fail();
    } else if (!write_end(png_, info_)) {
      fail();
    }
    file_.close();
  }

 private:
  void reserve_codes(size_t bytes) {
    if (codes_.capacity() < bytes) {
      codes_ = std::vector<uint8_t>();
      codes_.reserve(bytes);
      advise_huge_pages(codes_.data(), bytes);
    }
    codes_.resize(bytes);
  }

  [[noreturn]] void fail() {
    // A write error inside libpng is errno's (disk full, ...); say that.
    throw std::runtime_error(errno ? std::string(std::strerror(errno)) : std::string(messages_.text));
  }
  File file_;
  Messages messages_;
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
  int width_, channels_;
  Encoding encoding_;
  std::vector<uint8_t> codes_;  // the band being written, as 8-bit codes
  std::unique_ptr<ParallelDeflate> deflate_;  // null: libpng compresses the rows
};

// Reading: the header first (for size limits), then the rows.
struct Reader {
  File file;
  Messages messages;
  png_structp png = nullptr;
  png_infop info = nullptr;
  explicit Reader(const std::string& path) : file(path, "rb") {
    png_byte sig[8] = {};
    if (std::fread(sig, 1, 8, file.f) != 8 || png_sig_cmp(sig, 0, 8)) throw std::runtime_error("not a PNG file");
    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &messages, on_error, on_warning);
    if (!png) throw std::runtime_error("out of memory");
    info = png_create_info_struct(png);
    if (!info) throw std::runtime_error("out of memory");
  }
  ~Reader() { png_destroy_read_struct(&png, &info, nullptr); }
  [[noreturn]] void fail() const { throw std::runtime_error(messages.text[0] ? messages.text : "corrupt PNG"); }
};

// Expands palettes and low bit depths to 8 bits, tRNS to alpha; 16-bit stays
// 16-bit (big-endian as stored). Returns the channels after expansion.
bool read_setup(png_structp png, png_infop info, std::FILE* f, int* channels) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, f);
  png_set_sig_bytes(png, 8);
  png_set_user_limits(png, 0x7fffffff, 0x7fffffff);
  png_read_info(png, info);
  png_set_expand(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  *channels = png_get_channels(png, info);
  return true;
}

bool read_rows(png_structp png, png_infop info, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, info);
  return true;
}

}  // namespace

PngCompression default_png_compression() {
  // zlib level 1, default strategy, no row filter: an EIA's rows are
  // hundreds of small elemental images, which the PNG filters predict badly.
  // Deflated on every core in 256 KiB segments (parallel_deflate.hpp): on 2
  // cores a teapot_s6 2048x2048 EIA in 37.6 ms against 64.2 ms on one
  // thread, gears_s4 in 55.1 against 97.8, file sizes within 0.1 %
  // (bench/png_results.md).
  return {1, Z_DEFAULT_STRATEGY, PNG_FILTER_NONE, size_t{256} << 10};
}

std::unique_ptr<ScanlineOutput> open_png(const std::string& file, int width, int height, int channels, Encoding encoding,
                                         PngCompression compression) {
  errno = 0;
  return std::make_unique<PngOutput>(file, width, height, channels, encoding, compression);
}

Header png_header(const std::string& file) {
  Reader r(file);
  int channels = 0;
  if (!read_setup(r.png, r.info, r.file.f, &channels)) r.fail();
  return {static_cast<int>(png_get_image_width(r.png, r.info)), static_cast<int>(png_get_image_height(r.png, r.info)),
          channels, "png"};
}

namespace {

// The rows as libpng expands them (read_setup): 8- or 16-bit codes.
struct PngRows {
  int width = 0, height = 0, channels = 0;
  bool wide = false;  // 16-bit, big-endian
  std::vector<png_byte> bytes;
};

PngRows decode_png(const std::string& file) {
  Reader r(file);
  PngRows out;
  if (!read_setup(r.png, r.info, r.file.f, &out.channels)) r.fail();
  out.width = static_cast<int>(png_get_image_width(r.png, r.info));
  out.height = static_cast<int>(png_get_image_height(r.png, r.info));
  out.wide = png_get_bit_depth(r.png, r.info) == 16;
  const size_t row_bytes = png_get_rowbytes(r.png, r.info);
  out.bytes.resize(row_bytes * size_t(out.height));
  std::vector<png_bytep> rows(static_cast<size_t>(out.height));
  for (int y = 0; y < out.height; ++y) rows[size_t(y)] = out.bytes.data() + row_bytes * size_t(y);
  if (!read_rows(r.png, r.info, rows.data())) r.fail();
  return out;
}

}  // namespace

ImageBuffer read_png(const std::string& file) {
  const PngRows p = decode_png(file);
  // Codes times the reciprocal, as OpenImageIO converts: images read before
  // and after the change hold the same floats.
  ImageBuffer img(p.width, p.height, p.channels);
  const size_t n = img.data.size();
  const std::vector<png_byte>& bytes = p.bytes;
  if (p.wide)
    for (size_t k = 0; k < n; ++k) img.data[k] = static_cast<float>((bytes[2 * k] << 8) | bytes[2 * k + 1]) * (1.0f / 65535.0f);
  else
    for (size_t k = 0; k < n; ++k) img.data[k] = static_cast<float>(bytes[k]) * (1.0f / 255.0f);
  return img;
}

std::optional<ImageCodes> read_png_codes(const std::string& file) {
  PngRows p = decode_png(file);
  if (p.wide) return std::nullopt;
  return ImageCodes{p.width, p.height, p.channels, std::move(p.bytes)};
}

}  // namespace holoray::formats
