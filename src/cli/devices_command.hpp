// holoray/cli: the GPU path's devices: `holoray devices` lists the Vulkan
// devices it can use, numbered as `--device gpu:N` counts them, and
// `--device` chooses one for `render` and `animate` (docs/guide/gpu.md).
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace holoray::cli {

CLI::App* add_devices_command(CLI::App& app);
/// Prints one line per device; exit status 1 with the GPU path's message
/// when there is no loader, no device, or no GPU path in this build.
int run_devices();
/// `--device cpu|gpu|gpu:N` on `cmd`, checked by api::check_device; `what`
/// says what the GPU path takes there.
CLI::Option* add_device_option(CLI::App& cmd, std::string& device, const std::string& what);

}  // namespace holoray::cli
