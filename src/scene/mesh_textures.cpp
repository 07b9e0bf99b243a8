// holoray/scene: a mesh file's image maps, from files or embedded (mesh_import.hpp).
#include "scene/mesh_import.hpp"

#include <filesystem>
#include <fstream>

#include "scene/texture_search.hpp"

namespace holoray::mesh_import {

int MeshReader::image_of(const std::string& material, const std::string& path, bool colour) {
  return cached_image(colour ? path : path + "\n(data)", [&] { return read_image_map(material, path, colour); });
}

int MeshReader::cached_image(const std::string& key, const std::function<ImageMap()>& make) {
  if (const auto it = image_index_.find(key); it != image_index_.end()) return it->second;
  out_.images.push_back(make());
  const int index = static_cast<int>(out_.images.size()) - 1;
  image_index_[key] = index;
  return index;
}

ImageMap MeshReader::read_image_map(const std::string& material, const std::string& path, bool colour) {
  ImageMap img;
  img.path = path;
  try {
    ImageHeader header;
    if (const aiTexture* e = s_.GetEmbeddedTexture(path.c_str())) {
      read_embedded(*e, header, img);
    } else {
      const TextureLookup where = find_texture(path, out_.source, options_.texture_paths);
      if (!where.found) {
        std::string tried;
        for (const std::string& t : where.tried) tried += fmt::format("{}{}", tried.empty() ? "" : ", ", t);
        throw std::runtime_error(fmt::format("not found; looked for {}", tried));
      }
      read_texture_file(*where.found, header, img);
    }
    img.srgb = colour && header.format != "openexr" && header.format != "hdr";
  } catch (const std::exception& e) {
    const auto* read_error = dynamic_cast<const ImageReadError*>(&e);
    warn(fmt::format("material '{}': cannot read texture '{}' ({}): a checker shows where it goes", material, path,
                     read_error ? read_error->reason() : std::string(e.what())));
    checker(img);
    img.srgb = true;
  }
  return img;
}

void MeshReader::read_texture_file(const std::string& file, ImageHeader& header, ImageMap& img) {
  if (auto codes = read_image_codes(file, &header)) codes_to_image_map(*codes, img);
  else to_image_map(read_image(file, &header), img);
}

void MeshReader::read_embedded(const aiTexture& t, ImageHeader& header, ImageMap& img) {
  if (t.mHeight > 0) {
    if (int64_t{t.mWidth} * t.mHeight > kMaxImagePixels)
      throw std::runtime_error(fmt::format("{}x{} texels (at most {})", t.mWidth, t.mHeight, kMaxImagePixels));
    ImageCodes raw{static_cast<int>(t.mWidth), static_cast<int>(t.mHeight), 4,
                   std::vector<uint8_t>(size_t{t.mWidth} * t.mHeight * 4)};
    for (size_t k = 0; k < size_t{t.mWidth} * t.mHeight; ++k) {
      const aiTexel& c = t.pcData[k];
      uint8_t* o = &raw.codes[4 * k];
      o[0] = c.r, o[1] = c.g, o[2] = c.b, o[3] = c.a;
    }
    header = {raw.width, raw.height, 4, "raw"};
    codes_to_image_map(raw, img);
    return;
  }
  const std::filesystem::path tmp =
      std::filesystem::temp_directory_path() /
      fmt::format("holoray-texture-{}-{}.{}", ::getpid(), static_cast<const void*>(&t), t.achFormatHint[0] ? t.achFormatHint : "img");
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(t.pcData), static_cast<std::streamsize>(t.mWidth));
    if (!out) throw std::runtime_error("cannot copy the embedded image to a temporary file");
  }
  struct Remove {
    std::filesystem::path p;
    ~Remove() {
      std::error_code ec;
      std::filesystem::remove(p, ec);
    }
  } remove{tmp};
  try {
    read_texture_file(tmp.string(), header, img);
  } catch (const ImageReadError& e) {
    throw std::runtime_error(e.reason());
  }
}

template <class Texel, class Code>
void MeshReader::fill_image_map(int width, int height, int channels, Texel texel, Code code, ImageMap& img) {
  img.width = width;
  img.height = height;
  img.rgb.resize(size_t(width) * height * 3);
  const bool alpha = channels == 2 || channels == 4;
  if (alpha) img.alpha.resize(size_t(width) * height);
  const int last = channels - 1;
  const int ch[3] = {0, std::min(1, last), std::min(2, last)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t at = size_t(y) * width + x;
      const auto* p = texel(x, height - 1 - y);
      for (int c = 0; c < 3; ++c) img.rgb[at * 3 + c] = code(p[ch[c]]);
      if (alpha) img.alpha[at] = code(p[last]);
    }
}

void MeshReader::to_image_map(const ImageBuffer& raw, ImageMap& img) {
  fill_image_map(
      raw.width, raw.height, raw.channels, [&](int x, int y) { return raw.at(x, y); },
      [](float v) {
        const float x = std::clamp(v, 0.0f, 1.0f) * 255.0f;
        return static_cast<unsigned char>(x >= 0 ? static_cast<int>(static_cast<double>(x) + 0.5) : 0);
      },
      img);
}

void MeshReader::codes_to_image_map(const ImageCodes& raw, ImageMap& img) {
  fill_image_map(
      raw.width, raw.height, raw.channels,
      [&](int x, int y) { return raw.codes.data() + (size_t(y) * raw.width + x) * raw.channels; },
      [](uint8_t v) { return v; }, img);
}

void MeshReader::checker(ImageMap& img) {
  img.width = img.height = 8;
  img.rgb.resize(8 * 8 * 3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool on = (x + y) % 2 == 0;
      unsigned char* p = &img.rgb[(size_t(y) * 8 + x) * 3];
      p[0] = on ? 255 : 40, p[1] = on ? 0 : 40, p[2] = on ? 255 : 40;
    }
}

}  // namespace holoray::mesh_import
