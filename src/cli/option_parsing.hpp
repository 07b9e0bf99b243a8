// holoray/cli: parsers for option values that CLI11 has no type for. Each
// throws std::invalid_argument with a message naming the option and value.
#pragma once

#include <fmt/format.h>

#include <initializer_list>
#include <stdexcept>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include <array>

#include "holoray/camera.hpp"
#include "holoray/image.hpp"
#include "holoray/pick.hpp"  // pick(), the choice among named values
#include "holoray/render.hpp"

namespace holoray::cli {

/// "NXxNY" (e.g. "64x64") or a single "N" meaning NxN; `option` names the
/// option in messages (--lenses, --quilt).
void parse_lens_count(const std::string& text, int& nx, int& ny, std::string_view option = "--lenses");
/// "WxH" (e.g. 512x512) for --resolution; sizes from 1 to 65536 each.
void parse_resolution(const std::string& text, int& width, int& height);
/// Whether `path`'s file name holds a quilt layout (_qsCxR), as Looking
/// Glass tools name quilts.
bool names_quilt(const std::string& path);
/// A quilt's columns and rows: `option_text` ("CxR", --quilt) where given,
/// else the _qsCxR in the file name of `path`, as Looking Glass tools name
/// quilts. Throws std::invalid_argument saying to give --quilt when neither
/// tells.
void parse_quilt_layout(const std::string& option_text, const std::string& path, int& columns, int& rows);
/// "X,Y,Z" with finite numbers.
std::array<double, 3> parse_vec3(const std::string& option, const std::string& text);
/// "square", "hex" or "lenticular" (--grid).
api::Grid parse_grid(const std::string& text);
/// "linear" or "srgb" (--encoding).
api::Encoding parse_encoding(const std::string& text);
/// --encoding of render and animate: "linear", "srgb" or "auto", which is
/// api::default_encoding(scene). Throws std::invalid_argument for other text.
api::Encoding parse_encoding(const std::string& text, const std::string& scene);
/// "zip", "zips", "piz", "rle" or "none" (--exr-compression).
api::ExrCompression parse_exr_compression(const std::string& text);
/// "auto", "subaperture", "packet", "horizontal" or "vertical" (--style).
api::Style parse_style(const std::string& text);
/// Comma-separated subset of albedo,depth,normal,id.
api::Aovs parse_aovs(const std::string& text);

}  // namespace holoray::cli
