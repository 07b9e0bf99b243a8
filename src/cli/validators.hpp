// holoray/cli: CLI11 validators whose messages read as holoray's own.
// CLI11 puts the option's name first ("--grid: expected square, hex or
// lenticular, got 'round'"), stops with status 2 (a usage error) before
// anything is read, and shows what each option accepts in --help.
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace holoray::cli {

/// One of `names`: "expected A, B or C, got 'X'".
CLI::Validator one_of(std::vector<std::string> names);

/// A number in [lo, hi] ([lo, hi) when `hi_open`): "must be from LO to HI,
/// got X", or "must be at least LO, got X" when hi is infinite. `unit`
/// follows the bounds in the message ("degrees").
CLI::Validator in_range(double lo, double hi = INFINITY, bool hi_open = false, std::string unit = "");

/// A value `parse` accepts: its std::invalid_argument message is the error,
/// less the "OPTION: " it starts with. `description` is what --help shows.
CLI::Validator parsed_by(std::function<void(const std::string&)> parse, std::string description);

/// A file that exists: "cannot read 'X': no such file" (or "... is a folder").
CLI::Validator existing_file();

/// An image to write: .png or .exr, in a folder that exists.
CLI::Validator output_image();

/// Puts each named option of `cmd` under its heading in --help (the
/// guide's grouping), and ends the help with `examples` (one command a line).
void lay_out_help(CLI::App& cmd, const std::vector<std::pair<std::string, std::vector<std::string>>>& groups,
                  const std::vector<std::string>& examples, const std::string& guide_page);

}  // namespace holoray::cli
