#include "cli/option_parsing.hpp"

#include <fmt/format.h>

#include <charconv>
#include <filesystem>
#include <regex>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace holoray::cli {

namespace {
bool to_int(std::string_view s, int& out) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
}
}  // namespace

void parse_lens_count(const std::string& text, int& nx, int& ny, std::string_view option) {
  const auto x = text.find_first_of("xX");
  const bool ok = x == std::string::npos ? (to_int(text, nx) && (ny = nx, true))
                                         : (to_int(std::string_view(text).substr(0, x), nx) &&
                                            to_int(std::string_view(text).substr(x + 1), ny));
  if (!ok) throw std::invalid_argument(fmt::format("{}: expected NXxNY (e.g. 64x64), got '{}'", option, text));
  if (nx < 1 || ny < 1)
    throw std::invalid_argument(fmt::format("{}: {} counts must be at least 1, got '{}'", option,
                                            option == "--lenses" ? "lens" : "view", text));
}

void parse_resolution(const std::string& text, int& width, int& height) {
  const auto x = text.find_first_of("xX");
  if (x == std::string::npos || !to_int(std::string_view(text).substr(0, x), width) ||
      !to_int(std::string_view(text).substr(x + 1), height))
    throw std::invalid_argument(fmt::format("--resolution: expected WxH (e.g. 512x512), got '{}'", text));
  if (width < 1 || height < 1 || width > 65536 || height > 65536)
    throw std::invalid_argument(fmt::format("--resolution: width and height must be from 1 to 65536, got '{}'", text));
}

std::array<double, 3> parse_vec3(const std::string& option, const std::string& text) {
  double v[3];
  std::string_view rest(text);
  for (int k = 0; k < 3; ++k) {
    const auto comma = rest.find(',');
    const std::string_view part = rest.substr(0, comma);
    const auto r = std::from_chars(part.data(), part.data() + part.size(), v[k]);
    const bool last = k == 2;
    if (part.empty() || r.ec != std::errc() || r.ptr != part.data() + part.size() || !std::isfinite(v[k]) ||
        (last != (comma == std::string_view::npos)))
      throw std::invalid_argument(fmt::format("{}: expected X,Y,Z (three finite numbers), got '{}'", option, text));
    if (!last) rest.remove_prefix(comma + 1);
  }
  return {v[0], v[1], v[2]};
}

api::Grid parse_grid(const std::string& text) {
  if (text == "square") return api::Grid::square;
  if (text == "hex") return api::Grid::hex;
  if (text == "lenticular") return api::Grid::lenticular;
  throw std::invalid_argument(fmt::format("--grid: expected square, hex or lenticular, got '{}'", text));
}

api::Encoding parse_encoding(const std::string& text) {
  if (text == "linear") return api::Encoding::linear;
  if (text == "srgb") return api::Encoding::srgb;
  throw std::invalid_argument(fmt::format("--encoding: expected linear or srgb, got '{}'", text));
}

api::ExrCompression parse_exr_compression(const std::string& text) {
  using C = api::ExrCompression;
  return pick<C>("--exr-compression", text, {{"zip", C::zip}, {"zips", C::zips}, {"piz", C::piz}, {"rle", C::rle}, {"none", C::none}});
}

api::Encoding parse_encoding(const std::string& text, const std::string& scene) {
  if (text != "auto") {
    if (text == "linear" || text == "srgb") return parse_encoding(text);
    throw std::invalid_argument(fmt::format("--encoding: expected auto, linear or srgb, got '{}'", text));
  }
  return api::default_encoding(scene);
}

api::Style parse_style(const std::string& text) {
  if (text == "auto") return api::Style::automatic;
  if (text == "packet") return api::Style::packet;
  if (text == "subaperture") return api::Style::subaperture;
  if (text == "horizontal") return api::Style::horizontal;
  if (text == "vertical") return api::Style::vertical;
  throw std::invalid_argument(fmt::format("--style: expected auto, subaperture, packet, horizontal or vertical, got '{}'", text));
}

api::Aovs parse_aovs(const std::string& text) {
  api::Aovs a;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item == "albedo") a.albedo = true;
    else if (item == "depth") a.depth = true;
    else if (item == "normal") a.normal = true;
    else if (item == "id") a.id = true;
    else throw std::invalid_argument(fmt::format("--aov: unknown AOV '{}' (expected albedo, depth, normal, id)", item));
  }
  return a;
}

namespace {
const std::regex kQuiltName("_qs([0-9]{1,4})x([0-9]{1,4})");
}  // namespace

bool names_quilt(const std::string& path) {
  return std::regex_search(std::filesystem::path(path).filename().string(), kQuiltName);
}

void parse_quilt_layout(const std::string& option_text, const std::string& path, int& columns, int& rows) {
  if (!option_text.empty()) return parse_lens_count(option_text, columns, rows, "--quilt");
  std::smatch m;
  const std::string name = std::filesystem::path(path).filename().string();
  if (!std::regex_search(name, m, kQuiltName))
    throw std::invalid_argument(fmt::format("'{}' names no quilt layout (_qsCxR); give --quilt CxR", name));
  parse_lens_count(m[1].str() + "x" + m[2].str(), columns, rows, "--quilt");
}

}  // namespace holoray::cli
