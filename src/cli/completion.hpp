// holoray/cli: bash completion made from the CLI11 definition itself (the
// subcommands and each one's options), so that it cannot fall behind the
// options: the build writes it to holoray.bash-completion with the hidden
// `holoray --completion bash`, and installs that.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace holoray::cli {

/// Adds the hidden option `--completion bash` to `app` (call it after the
/// subcommands are added): it prints bash_completion(app) and ends parsing
/// with CLI::Success, before any subcommand is required.
void add_completion_option(CLI::App& app);

/// A bash completion script for `app`: its subcommand names as the first
/// word, then that subcommand's options after a '-', file names otherwise.
/// Hidden subcommands and options (empty group) are left out.
std::string bash_completion(const CLI::App& app);

}  // namespace holoray::cli
