#include "cli/compare_command.hpp"

#include <fmt/format.h>

#include <cmath>

#include "cli/error_words.hpp"
#include "cli/validators.hpp"
#include "holoray/image.hpp"

namespace holoray::cli {

CLI::App* add_compare_command(CLI::App& app, CompareCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("compare", "Compare two images: MSE, RMSE and PSNR on the 8-bit scale");
  cmd->add_option("a", o.a, "First image (PNG, EXR, ...)")->required();
  cmd->add_option("b", o.b, "Second image, same size")->required();
  lay_out_help(*cmd, {},
               {"holoray compare frames/frame_0005.png reference/frame_0005.png",
                "holoray compare a.exr b.exr"},
               "docs/guide/animation.md");
  return cmd;
}

int run_compare(const CompareCommandOptions& o) {
  try {
    const api::Image a = api::read_image(o.a);
    const api::Difference d = api::compare_images(a, api::read_image(o.b));
    auto db = [](double v) { return std::isinf(v) ? std::string("inf") : fmt::format("{:.3f}", v); };
    fmt::print("{} x {} pixels\n", a.width(), a.height());
    fmt::print("channel        MSE       RMSE   PSNR dB\n");
    static constexpr const char* kName[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
      fmt::print("{:<7} {:>10.4f} {:>10.4f} {:>9}\n", kName[c], d.mse[static_cast<size_t>(c)], std::sqrt(d.mse[static_cast<size_t>(c)]), db(d.psnr(c)));
    fmt::print("{:<7} {:>10.4f} {:>10.4f} {:>9}\n", "all", d.mse_all, std::sqrt(d.mse_all), db(d.psnr()));
    if (d.nan_mismatches > 0)
      fmt::print("NaN     {} samples have a value in one image and NaN in the other; left out above\n", d.nan_mismatches);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", error_line(e));
  }
  return 1;
}

}  // namespace holoray::cli
