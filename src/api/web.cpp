// The light-field page (include/holoray/web.hpp): the page's own files are
// src/web/page, embedded at build time (cmake/embed_text.cmake); the views
// are the preview layer's; the server is a module of its own.
#include "holoray/web.hpp"

#include <fmt/format.h>

#include <cmath>
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

std::string in(const std::string& dir, const std::string& file) { return (std::filesystem::path(dir) / file).string(); }

}  // namespace

struct WebAnimation::State {
  std::string dir, name;
  Encoding encoding;
  double fps;
  nlohmann::json layout;  // the manifest's fields every frame shares
  nlohmann::json frames = nlohmann::json::array();
  bool finished = false;

  // Frame k's files, its fields checked against the first frame's.
  void add(const nlohmann::json& fields, const Image& views, const Image& eia) {
    if (finished) throw std::logic_error("WebAnimation: a frame added after finish()");
    const size_t k = frames.size();
    if (k == 0) {
      std::error_code ec;
      std::filesystem::create_directories(dir, ec);
      if (ec) throw std::runtime_error(fmt::format("cannot make the folder '{}': {}", dir, ec.message()));
      layout = fields;
    } else if (fields != layout) {
      throw std::invalid_argument(fmt::format("frame {}: {} of {}x{} views of {}x{} pixels, but frame 0 is {} of {}x{} views of {}x{}",
                                              k, fields["kind"].get<std::string>(), fields["views"][0].get<int>(),
                                              fields["views"][1].get<int>(), fields["view_size"][0].get<int>(),
                                              fields["view_size"][1].get<int>(), layout["kind"].get<std::string>(),
                                              layout["views"][0].get<int>(), layout["views"][1].get<int>(),
                                              layout["view_size"][0].get<int>(), layout["view_size"][1].get<int>()));
    }
    nlohmann::json frame;
    frame["views"] = fmt::format("views_{:04d}.png", k);
    write_image(in(dir, frame["views"]), views, encoding);
    frame["eia"] = nullptr;
    if (!eia.empty()) {
      frame["eia"] = fmt::format("eia_{:04d}.png", k);
      write_image(in(dir, frame["eia"]), eia, encoding);
    }
    frames.push_back(frame);
  }
};

WebAnimation::WebAnimation(const std::string& dir, const std::string& name, Encoding encoding, double fps)
    : state_(std::make_unique<State>(State{dir, name, encoding, fps, {}})) {
  if (!(fps > 0 && fps <= 1000)) throw std::invalid_argument(fmt::format("fps: expected 0 to 1000 frames a second, got {}", fps));
}

WebAnimation::~WebAnimation() = default;

void WebAnimation::add_eia(const Image& eia, const EiaLayout& layout) {
  const Image views = view_grid(eia, layout);  // throws for an EIA that is not whole lenses
  const int p = layout.pixels_per_lens;
  const bool lenticular = layout.grid == Grid::lenticular;
  const int nu = p, nv = lenticular ? 1 : p;
  const int vw = views.width() / nu, vh = views.height() / nv;
  nlohmann::json m;
  m["kind"] = "eia";
  m["grid"] = grid_name(layout.grid);
  m["pixels_per_lens"] = p;
  m["lenses"] = {vw, lenticular ? 1 : vh};
  m["views"] = {nu, nv};
  m["view_size"] = {vw, vh};
  m["tiles"] = {nu, nv};
  m["tile_order"] = "rows";
  m["looking_glass"] = nullptr;
  state_->add(m, views, eia);
}

void WebAnimation::add_quilt(const Image& quilt, int columns, int rows, const std::string& looking_glass) {
  if (columns < 1 || rows < 1 || int64_t{columns} * rows > 4096)
    throw std::invalid_argument(fmt::format("quilt: expected 1 to 4096 views, got {}x{}", columns, rows));
  if (quilt.empty() || quilt.width() % columns || quilt.height() % rows)
    throw std::invalid_argument(
        fmt::format("a {}x{} image is not {}x{} views of whole pixels", quilt.width(), quilt.height(), columns, rows));
  nlohmann::json m;
  m["kind"] = "quilt";
  m["views"] = {columns * rows, 1};
  m["view_size"] = {quilt.width() / columns, quilt.height() / rows};
  m["tiles"] = {columns, rows};
  m["tile_order"] = "quilt";
  m["looking_glass"] = nullptr;
  if (!looking_glass.empty()) {
    const std::string calibration = read_text_file(looking_glass);
    parse_looking_glass(calibration, looking_glass);  // refused here, not in the page
    if (state_->frames.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(state_->dir, ec);
      write_text_file(in(state_->dir, "visual.json"), calibration);
    }
    m["looking_glass"] = "visual.json";
  }
  state_->add(m, quilt, Image());
}

void WebAnimation::finish() {
  State& s = *state_;
  if (s.frames.empty()) throw std::invalid_argument("WebAnimation: no frames to write a page of");
  if (s.finished) return;
  if (s.frames.size() == 1) {  // a still: views.png and eia.png
    for (const char* key : {"views", "eia"}) {
      if (s.frames[0][key].is_null()) continue;
      const std::string still = std::string(key) + ".png";
      std::filesystem::rename(in(s.dir, s.frames[0][key]), in(s.dir, still));
      s.frames[0][key] = still;
    }
  }
  nlohmann::json m = s.layout;
  m["format"] = "holoray-web 1";
  m["name"] = s.name;
  m["frames"] = s.frames;
  m["fps"] = s.fps;
  write_text_file(in(s.dir, "light_field.json"), m.dump(2) + "\n");
  write_text_file(in(s.dir, "holoray_web.js"), kHolorayWebJs);
  write_text_file(in(s.dir, "index.html"), kIndexHtml);  // last: a page that opens has all it reads
  s.finished = true;
}

void write_web_eia(const Image& eia, const EiaLayout& layout, const std::string& dir, const std::string& name,
                   Encoding encoding) {
  WebAnimation page(dir, name, encoding);
  page.add_eia(eia, layout);
  page.finish();
}

void write_web_quilt(const Image& quilt, int columns, int rows, const std::string& dir, const std::string& name,
                     Encoding encoding, const std::string& looking_glass) {
  WebAnimation page(dir, name, encoding);
  page.add_quilt(quilt, columns, rows, looking_glass);
  page.finish();
}

void serve_folder(const std::string& dir, const std::string& host, int port,
                  const std::function<void(const std::string& url)>& listening) {
  if (!std::filesystem::is_directory(dir)) throw std::runtime_error(fmt::format("'{}' is not a folder", dir));
  if (!std::filesystem::exists(std::filesystem::path(dir) / "index.html"))
    throw std::runtime_error(fmt::format("'{}' holds no index.html: write a page there with `holoray web RESULT -o {}`", dir, dir));
  using Serve = int (*)(const char*, const char*, int, void (*)(const char*, void*), void*, char*, size_t);
  const auto serve = reinterpret_cast<Serve>(module_symbol("holoray_http.so", HOLORAY_HTTP_MODULE, "holoray_serve_folder",
                                                           "holoray's HTTP module is not installed"));
  char error[512] = "";
  const auto call = [](const char* url, void* user) { (*static_cast<const std::function<void(const std::string&)>*>(user))(url); };
  if (serve(dir.c_str(), host.c_str(), port, call, const_cast<std::function<void(const std::string&)>*>(&listening), error,
            sizeof error) != 0)
    throw std::runtime_error(error);
}

}  // namespace holoray::api
