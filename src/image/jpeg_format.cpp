// JPEG input through libjpeg-turbo, decoded with the library's defaults
// (accurate integer IDCT, fancy upsampling), as OpenImageIO decoded it.
// libjpeg reports errors by longjmp; each call that can fail sits alone in a
// small function that sets the jump point, so no C++ object is jumped over.
#include <cerrno>
#include <csetjmp>
#include <cstdio>  // before jpeglib.h, which needs FILE and size_t
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <jpeglib.h>

#include "image/formats.hpp"

namespace holoray::formats {

namespace {

struct ErrorManager {
  jpeg_error_mgr base;  // first: libjpeg sees an ErrorManager* as a jpeg_error_mgr*
  std::jmp_buf jump;
  char text[JMSG_LENGTH_MAX] = {};
};

void on_error(j_common_ptr info) {
  auto* e = reinterpret_cast<ErrorManager*>(info->err);
  (*info->err->format_message)(info, e->text);
  std::longjmp(e->jump, 1);
}

void on_message(j_common_ptr, int) {}  // corrupt-data warnings: decode what is there, as OpenImageIO did

struct Decoder {
  std::FILE* f = nullptr;
  jpeg_decompress_struct info{};
  ErrorManager error{};
  explicit Decoder(const std::string& path) : f(std::fopen(path.c_str(), "rb")) {
    if (!f) throw std::runtime_error(std::strerror(errno));
    info.err = jpeg_std_error(&error.base);
    error.base.error_exit = on_error;
    error.base.emit_message = on_message;
    jpeg_create_decompress(&info);
    jpeg_stdio_src(&info, f);
  }
  ~Decoder() {
    jpeg_destroy_decompress(&info);
    std::fclose(f);
  }
  [[noreturn]] void fail() const { throw std::runtime_error(error.text); }
};

bool read_header(Decoder* d) {
  if (setjmp(d->error.jump)) return false;
  jpeg_read_header(&d->info, TRUE);
  // Colour as RGB, grey as grey; CMYK is left as the file has it and refused.
  if (d->info.jpeg_color_space != JCS_GRAYSCALE && d->info.jpeg_color_space != JCS_CMYK &&
      d->info.jpeg_color_space != JCS_YCCK)
    d->info.out_color_space = JCS_RGB;
  jpeg_calc_output_dimensions(&d->info);
  return true;
}

bool decode(Decoder* d, JSAMPLE* pixels, size_t row_bytes) {
  if (setjmp(d->error.jump)) return false;
  jpeg_start_decompress(&d->info);
  while (d->info.output_scanline < d->info.output_height) {
    JSAMPROW row = pixels + row_bytes * d->info.output_scanline;
    jpeg_read_scanlines(&d->info, &row, 1);
  }
  jpeg_finish_decompress(&d->info);
  return true;
}

Header header_of(Decoder& d) {
  if (!read_header(&d)) d.fail();
  if (d.info.out_color_space == JCS_CMYK || d.info.out_color_space == JCS_YCCK)
    throw std::runtime_error("a CMYK JPEG (holoray reads grey and RGB JPEGs)");
  return {static_cast<int>(d.info.output_width), static_cast<int>(d.info.output_height), d.info.output_components, "jpeg"};
}

}  // namespace

Header jpeg_header(const std::string& file) {
  Decoder d(file);
  return header_of(d);
}

ImageCodes read_jpeg_codes(const std::string& file) {
  Decoder d(file);
  const Header h = header_of(d);
  const size_t row_bytes = size_t(h.width) * size_t(h.channels);
  ImageCodes out{h.width, h.height, h.channels, std::vector<uint8_t>(row_bytes * size_t(h.height))};
  static_assert(sizeof(JSAMPLE) == 1);
  if (!decode(&d, reinterpret_cast<JSAMPLE*>(out.codes.data()), row_bytes)) d.fail();
  return out;
}

ImageBuffer read_jpeg(const std::string& file) {
  const ImageCodes c = read_jpeg_codes(file);
  ImageBuffer img(c.width, c.height, c.channels);
  for (size_t k = 0; k < c.codes.size(); ++k) img.data[k] = static_cast<float>(c.codes[k]) * (1.0f / 255.0f);
  return img;
}

}  // namespace holoray::formats
