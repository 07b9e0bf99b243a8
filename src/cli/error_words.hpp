// holoray/cli: the library's messages in the command line's words. The
// library names what the user set by the API's names, in backquotes
// (`pitch`, `fov_lens_deg`, `LookingGlass`: include/holoray/camera.hpp);
// each front end says them its own way: here the option that sets each.
#pragma once

#include <exception>
#include <string>
#include <string_view>

namespace holoray::cli {

/// `message` with each backquoted API name replaced by its option
/// (`pitch` -> --pitch, `fov_lens_deg` -> --fov-lens, `Pinhole` ->
/// --camera pinhole); a name without an option loses its backquotes only.
std::string in_option_words(std::string_view message);

/// The line a command prints for an error it stops on:
/// "holoray: error: " and what() in the command line's words.
std::string error_line(const std::exception& e);
/// What the CLI prints for an error: a scene file's report as its reader
/// wrote it ("file:line:col: error: ...", the line and a caret), any other
/// error as error_line().
std::string error_report(const std::exception& e);

}  // namespace holoray::cli
