#include "scene/texture_search.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

namespace holoray {

namespace fs = std::filesystem;

namespace {

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// `name` in `dir`, or a file there whose name differs only in case.
std::optional<fs::path> in_folder(const fs::path& dir, const std::string& name) {
  if (is_file(dir / name)) return dir / name;
  std::error_code ec;
  const std::string wanted = lower(name);
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (lower(it->path().filename().string()) == wanted && is_file(it->path())) return it->path();
  return std::nullopt;
}

}  // namespace

std::string texture_base_name(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

TextureLookup find_texture(const std::string& named, const std::string& scene_file, const std::vector<std::string>& search) {
  TextureLookup out;
  const fs::path folder = fs::path(scene_file).parent_path();
  auto try_path = [&](const fs::path& p) {
    out.tried.push_back(p.string());
    if (is_file(p)) out.found = p.string();
    return out.found.has_value();
  };
  if (named.empty()) return out;
  // A Windows drive ("D:\\x", "D:/x") or network path ("\\\\host\\x") names
  // another machine's file: only its base name can be found here.
  const bool windows_absolute = (named.size() > 2 && std::isalpha(static_cast<unsigned char>(named[0])) &&
                                 named[1] == ':' && (named[2] == '\\' || named[2] == '/')) ||
                                named.rfind("\\\\", 0) == 0;
  if (!windows_absolute) {
    if (try_path(folder / named)) return out;  // an absolute `named` replaces the folder
    std::string slashed = named;
    std::replace(slashed.begin(), slashed.end(), '\\', '/');
    if (slashed != named && try_path(folder / slashed)) return out;
  }
  const std::string base = texture_base_name(named);
  if (base.empty()) return out;
  auto try_folder = [&](const fs::path& dir) {
    out.tried.push_back((dir / base).string());
    if (const auto p = in_folder(dir, base)) out.found = p->string();
    return out.found.has_value();
  };
  if (base != named && try_folder(folder)) return out;
  for (const std::string& dir : search)
    if (try_folder(dir)) return out;
  return out;
}

}  // namespace holoray
