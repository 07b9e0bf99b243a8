// holoray/fuzz: the bodies of the libFuzzer targets, one per reader of outside
// input. Each takes arbitrary bytes and must either accept them or throw the
// reader's documented error; anything else (a crash, a sanitizer report, an
// other exception escaping) is a finding. The regression test runs the same
// bodies on every input saved in fuzz/regressions/<target>/, so a finding
// fixed once stays fixed in the ordinary test build too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "display/display_file.hpp"
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
