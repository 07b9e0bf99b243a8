// holoray/fuzz: the bodies of the libFuzzer targets, one per reader of outside
// input. Each takes arbitrary bytes and must either accept them or throw the
// reader's documented error; anything else (a crash, a sanitizer report, an
// other exception escaping) is a finding. The regression test runs the same
// bodies on every input saved in fuzz/regressions/<target>/, so a finding
// fixed once stays fixed in the ordinary test build too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include <unistd.h>

#include "display/display_file.hpp"
#include "scene/mesh_reader.hpp"
#include "scene/nff_reader.hpp"
#include "scene/parse_error.hpp"
#include "scene/tachyon_reader.hpp"
#include "scene/tessellate.hpp"
#include "shot/camera_path.hpp"
#include "shot/shot_reader.hpp"

namespace holoray::fuzz {

inline std::string_view as_text(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// NFF: parse, then tessellate every polygon as the renderer does. Allowed
/// error: ParseError.
inline void nff(const uint8_t* data, size_t size) {
  try {
    const SceneDesc scene = parse_nff(as_text(data, size), "fuzz.nff");
    for (const ObjectDesc& o : scene.objects)
      if (const auto* poly = std::get_if<PolygonDesc>(&o.shape)) (void)tessellate_polygon(poly->vertices);
  } catch (const ParseError&) {
  }
}

/// Shot files (TOML). Allowed errors: ParseError, and std::runtime_error
/// for a camera path file it names that cannot be read. Relative names
/// resolve under a folder that does not exist, so the fuzzer cannot reach
/// the checkout's files by accident.
inline void shot(const uint8_t* data, size_t size) {
  try {
    (void)parse_shot(as_text(data, size), "/nonexistent-holoray-fuzz/shot.toml");
  } catch (const std::runtime_error&) {  // ParseError is one
  }
}

/// glTF 2.0 (.gltf text) through assimp and holoray's mesh reader, its
/// node animation, skins and morph targets posed halfway through, and its
/// textures: the bytes go to a temporary file beside a 4x4 PNG that it may
/// name ("t.png"; data URIs and missing images are the input's own).
/// Allowed error: std::runtime_error ("cannot read 'FILE': ...").
inline void gltf(const uint8_t* data, size_t size) {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("holoray-fuzz-gltf-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    // 4x4 RGB PNG, grey: a valid image for inputs that name "t.png".
    static const unsigned char png[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
        0x00, 0x04, 0x00, 0x00, 0x00, 0x04, 0x08, 0x02, 0x00, 0x00, 0x00, 0x26, 0x93, 0x09, 0x29, 0x00, 0x00, 0x00,
        0x0e, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0x68, 0x40, 0x02, 0x0c, 0xc4, 0x71, 0x00, 0x70, 0x52, 0x18,
        0x01, 0x9e, 0xae, 0xbe, 0x6f, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    std::ofstream(d / "t.png", std::ios::binary).write(reinterpret_cast<const char*>(png), sizeof png);
    return d;
  }();
  const std::string path = (dir / "f.gltf").string();
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    MeshLimits limits;
    limits.max_triangles = 100'000;
    MeshAnimation anim;
    (void)read_mesh_file(path, limits, &anim);
    std::vector<Vec3> vertices, normals;
    for (size_t k = 0; k < anim.deforming.size(); ++k) anim.pose(k, 0.5 * anim.duration_s, vertices, normals);
    for (size_t k = 0; k < anim.parts.size(); ++k) (void)anim.transform(k, 0.5 * anim.duration_s);
  } catch (const std::runtime_error&) {
  }
}

/// Tachyon scenes (.dat). Allowed error: ParseError (a file it names that
/// cannot be read is one too). Relative names resolve under a folder that
/// does not exist; absolute ones that are not regular files are refused.
inline void tachyon(const uint8_t* data, size_t size) {
  try {
    TachyonLimits limits;
    limits.max_objects = 100'000;  // the fuzzer's inputs are short; keep its memory small
    (void)parse_tachyon(as_text(data, size), "/nonexistent-holoray-fuzz/fuzz.dat", limits);
  } catch (const ParseError&) {
  }
}

/// Tachyon camera paths (.cam). Allowed error: ParseError.
inline void camera_path(const uint8_t* data, size_t size) {
  try {
    (void)parse_camera_path(as_text(data, size), "fuzz.cam");
  } catch (const ParseError&) {
  }
}

/// Display files (TOML). Allowed error: ParseError.
inline void display(const uint8_t* data, size_t size) {
  try {
    (void)parse_display(as_text(data, size), "fuzz.toml");
  } catch (const ParseError&) {
  }
}

}  // namespace holoray::fuzz
