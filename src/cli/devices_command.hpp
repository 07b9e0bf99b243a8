// holoray/cli: `holoray devices`: the Vulkan devices the GPU path can use,
// numbered as `--device gpu:N` counts them (docs/guide/gpu.md).
#pragma once

#include <CLI/CLI.hpp>

namespace holoray::cli {

CLI::App* add_devices_command(CLI::App& app);
/// Prints one line per device; exit status 1 with the GPU path's message
/// when there is no loader, no device, or no GPU path in this build.
int run_devices();

}  // namespace holoray::cli
