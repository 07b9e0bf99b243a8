// The light-field page (include/holoray/web.hpp): the page's own files are
// src/web/page, embedded at build time (cmake/embed_text.cmake); the views
// are the preview layer's; the server is a module of its own.
#include "holoray/web.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "display/looking_glass.hpp"
#include "scene/file_text.hpp"
#include "util/module_loader.hpp"
#include "web_page.inc"

namespace holoray::api {
namespace {

const char* grid_name(Grid g) { return g == Grid::hex ? "hex" : g == Grid::lenticular ? "lenticular" : "square"; }

// The page's files, its manifest and its images into `dir`; `eia` empty for a quilt.
void write_page(const std::string& dir, const nlohmann::json& manifest, const Image& views, const Image& eia,
                Encoding encoding) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot make the folder '{}': {}", dir, ec.message()));
  const std::filesystem::path d(dir);
  write_image((d / "views.png").string(), views, encoding);
  if (!eia.empty()) write_image((d / "eia.png").string(), eia, encoding);
  write_text_file((d / "light_field.json").string(), manifest.dump(2) + "\n");
  write_text_file((d / "holoray_web.js").string(), kHolorayWebJs);
  write_text_file((d / "index.html").string(), kIndexHtml);  // last: a page that opens has all it reads
}

}  // namespace

void write_web_eia(const Image& eia, const EiaLayout& layout, const std::string& dir, const std::string& name,
                   Encoding encoding) {
  const Image views = view_grid(eia, layout);  // throws for an EIA that is not whole lenses
  const int p = layout.pixels_per_lens;
  const bool lenticular = layout.grid == Grid::lenticular;
  const int nu = p, nv = lenticular ? 1 : p;
  const int vw = views.width() / nu, vh = views.height() / nv;
  nlohmann::json m;
  m["format"] = "holoray-web 1";
  m["name"] = name;
  m["kind"] = "eia";
  m["grid"] = grid_name(layout.grid);
  m["pixels_per_lens"] = p;
  m["lenses"] = {vw, lenticular ? 1 : vh};
  m["views"] = {nu, nv};
  m["view_size"] = {vw, vh};
  m["tiles"] = {nu, nv};
  m["tile_order"] = "rows";
  m["views_image"] = "views.png";
  m["eia_image"] = "eia.png";
  write_page(dir, m, views, eia, encoding);
}

void write_web_quilt(const Image& quilt, int columns, int rows, const std::string& dir, const std::string& name,
                     Encoding encoding, const std::string& looking_glass) {
  if (columns < 1 || rows < 1 || int64_t{columns} * rows > 4096)
    throw std::invalid_argument(fmt::format("quilt: expected 1 to 4096 views, got {}x{}", columns, rows));
  if (quilt.empty() || quilt.width() % columns || quilt.height() % rows)
    throw std::invalid_argument(
        fmt::format("a {}x{} image is not {}x{} views of whole pixels", quilt.width(), quilt.height(), columns, rows));
  nlohmann::json m;
  m["format"] = "holoray-web 1";
  m["name"] = name;
  m["kind"] = "quilt";
  m["views"] = {columns * rows, 1};
  m["view_size"] = {quilt.width() / columns, quilt.height() / rows};
  m["tiles"] = {columns, rows};
  m["tile_order"] = "quilt";
  m["views_image"] = "views.png";
  m["eia_image"] = nullptr;
  m["looking_glass"] = nullptr;
  std::string calibration;
  if (!looking_glass.empty()) {
    calibration = read_text_file(looking_glass);
    parse_looking_glass(calibration, looking_glass);  // refused here, not in the page
    m["looking_glass"] = "visual.json";
  }
  if (!calibration.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    write_text_file((std::filesystem::path(dir) / "visual.json").string(), calibration);
  }
  write_page(dir, m, quilt, Image(), encoding);
}

void serve_folder(const std::string& dir, const std::string& host, int port,
                  const std::function<void(const std::string& url)>& listening) {
  if (!std::filesystem::is_directory(dir)) throw std::runtime_error(fmt::format("'{}' is not a folder", dir));
  if (!std::filesystem::exists(std::filesystem::path(dir) / "index.html"))
    throw std::runtime_error(fmt::format("'{}' holds no index.html: write a page there with `holoray web RESULT -o {}`", dir, dir));
  using Serve = int (*)(const char*, const char*, int, void (*)(const char*, void*), void*, char*, size_t);
  const auto serve = reinterpret_cast<Serve>(module_symbol("holoray_http.so",
#ifdef HOLORAY_HTTP_MODULE
                                                           HOLORAY_HTTP_MODULE,
#else
                                                           "",
#endif
                                                           "holoray_serve_folder", "holoray's HTTP module"));
  char error[512] = "";
  const auto call = [](const char* url, void* user) { (*static_cast<const std::function<void(const std::string&)>*>(user))(url); };
  if (serve(dir.c_str(), host.c_str(), port, call, const_cast<std::function<void(const std::string&)>*>(&listening), error,
            sizeof error) != 0)
    throw std::runtime_error(error);
}

}  // namespace holoray::api
