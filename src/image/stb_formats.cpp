// The simple raster formats through stb_image (Debian's libstb): binary PNM
// (PGM, PPM), Targa, BMP and Radiance HDR. Rows come from the top whatever
// order the file stores them in (stb_image honours Targa's origin bit).
#include <stb_image.h>

#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

#include "image/formats.hpp"

namespace holoray::formats {

namespace {

struct Pixels {
  void* p;
  ~Pixels() { stbi_image_free(p); }
};

std::string reason() {
  const char* r = stbi_failure_reason();
  return r ? r : "unreadable image";
}

}  // namespace

Header stb_header(const std::string& file, const std::string& format) {
  int w = 0, h = 0, c = 0;
  if (!stbi_info(file.c_str(), &w, &h, &c)) throw std::runtime_error(reason());
  return {w, h, c, format};
}

ImageBuffer read_stb(const std::string& file, const std::string& format) {
  int w = 0, h = 0, c = 0;
  // stb_image's pixels as floats: HDR as stored, codes times the reciprocal
  // of the largest, as OpenImageIO converts.
  auto take = [&](void* pixels, auto tag, float scale) {
    const Pixels px{pixels};
    if (!px.p) throw std::runtime_error(reason());
    ImageBuffer img(w, h, c);
    const auto* v = static_cast<const decltype(tag)*>(px.p);
    for (size_t k = 0; k < img.data.size(); ++k) img.data[k] = static_cast<float>(v[k]) * scale;
    return img;
  };
  if (format == "hdr") return take(stbi_loadf(file.c_str(), &w, &h, &c, 0), float{}, 1.0f);
  if (stbi_is_16_bit(file.c_str())) return take(stbi_load_16(file.c_str(), &w, &h, &c, 0), stbi_us{}, 1.0f / 65535.0f);
  return take(stbi_load(file.c_str(), &w, &h, &c, 0), stbi_uc{}, 1.0f / 255.0f);
}

}  // namespace holoray::formats
