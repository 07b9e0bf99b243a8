#include "cli/error_words.hpp"

#include <array>
#include <string>
#include <utility>

#include "holoray/errors.hpp"

namespace holoray::cli {

namespace {

// The API's names (include/holoray/camera.hpp, render.hpp, animate.hpp) and
// the options that set them.
constexpr std::array<std::pair<std::string_view, std::string_view>, 18> kOptions{{
    {"origin", "--origin"},
    {"normal", "--normal"},
    {"up", "--up"},
    {"pitch", "--pitch"},
    {"gap", "--gap"},
    {"fov_lens_deg", "--fov-lens"},
    {"pixels_per_lens", "--pixels-per-lens"},
    {"method", "--method"},
    {"reuse", "--reuse"},
    {"reference", "--report"},
    {"cache", "--cache"},
    {"device", "--device"},
    {"integrator", "--integrator"},
    {"environment", "--environment"},
    {"Display", "--display"},
    {"LookingGlass", "--looking-glass"},
    {"Quilt", "--quilt"},
    {"Pinhole", "--camera pinhole"},
}};

}  // namespace

std::string in_option_words(std::string_view message) {
  return api::say_names(message, [](std::string_view name) {
    for (const auto& [api, option] : kOptions)
      if (api == name) return std::string(option);
    return std::string(name);
  });
}

std::string error_line(const std::exception& e) { return "holoray: error: " + in_option_words(e.what()); }

std::string error_report(const std::exception& e) {
  const auto* scene = dynamic_cast<const api::SceneError*>(&e);
  if (scene && scene->line() > 0) return e.what();
  return error_line(e);
}

}  // namespace holoray::cli
