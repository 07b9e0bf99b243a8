#include "cli/devices_command.hpp"

#include <fmt/format.h>

#include "cli/error_words.hpp"
#include "cli/validators.hpp"
#include "holoray/render.hpp"

namespace holoray::cli {

CLI::App* add_devices_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("devices", "List the Vulkan devices the GPU path can use, numbered as --device gpu:N counts them");
  lay_out_help(*cmd, {}, {"holoray devices"}, "docs/guide/gpu.md");
  return cmd;
}

CLI::Option* add_device_option(CLI::App& cmd, std::string& device, const std::string& what) {
  return cmd
      .add_option("--device", device,
                  "Where rays are traced: cpu (Embree), gpu (the first Vulkan GPU, else the first Vulkan device: lavapipe on a "
                  "machine without one) or gpu:N (the Nth Vulkan device, as `holoray devices` lists them); " + what +
                      " (docs/guide/gpu.md)")
      ->check(parsed_by([](const std::string& t) { api::check_device(t); }, "DEVICE"))
      ->capture_default_str();
}

int run_devices() {
  try {
    for (const std::string& d : api::gpu_devices()) fmt::print("{}\n", d);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", error_line(e));
  }
  return 1;
}

}  // namespace holoray::cli
