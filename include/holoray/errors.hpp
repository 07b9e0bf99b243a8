// holoray public API: the exceptions every call may throw.
//
//   std::invalid_argument  a bad argument; the message names it ("lenses: ...")
//   std::length_error      an absurd size, refused before anything is allocated
//   holoray::api::SceneError  a malformed scene, shot, display or calibration file
//   holoray::api::Cancelled   a render stopped through its std::stop_token
//   std::system_error      I/O: a file that cannot be read or written; code()
//                          is its errno (std::generic_category)
//
// Every malformed input file is a SceneError naming the file, whichever
// reader found it; a file that is missing, unreadable or a folder is not.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "holoray/export.hpp"

namespace holoray::api {

/// A malformed input file at a position. what() is the whole report, as
/// the CLI prints it (Tungsten's layout):
///
///     file:line:col: error: <what was expected>, found <what was found>
///       <the offending line>
///       <a caret under the column>
///
/// line() and column() are 1-based; 0 where the file gives no position.
class HOLORAY_API SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, int line, int column, std::string message, const std::string& report);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  /// What was expected and found, without the position or the caret.
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_, column_;
  std::string message_;
};

/// Thrown by render() and Animation::run() when their stop token was
/// triggered: the work stopped between tiles (or frames), every thread joined.
class HOLORAY_API Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("holoray: cancelled") {}
};

/// Messages name what the caller set by this API's names in backquotes
/// (`pitch`, `fov_lens_deg`, `LookingGlass`: camera.hpp). Returns `message`
/// with each such name replaced by say(name), a front end's own word for it
/// (the CLI's --pitch, Python's pitch); backquoted text that is not a name
/// (letters and '_') is kept as it is.
HOLORAY_API std::string say_names(std::string_view message, const std::function<std::string(std::string_view)>& say);

}  // namespace holoray::api
