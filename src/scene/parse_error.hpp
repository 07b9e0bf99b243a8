// holoray/scene: the errors every reader throws for malformed input: one
// type, the public API's SceneError, with a position where the file has one
// (ParseError) and without (malformed_file). I/O errors are not these: a
// file that cannot be opened or read is a std::system_error with the errno.
#pragma once

#include <stdexcept>
#include <string>

#include "holoray/errors.hpp"
#include "scene/scene_desc.hpp"

namespace holoray {

/// A malformed-input error at a file position. what() is the full report:
///
///     file:line:col: error: <message>
///       <the offending line>
///       <caret under the column>
///
/// message() alone is "<what was expected>, found <what was found>". It is
/// the public API's SceneError (holoray/errors.hpp), so every front end
/// catches one type for every malformed file.
class ParseError : public api::SceneError {
 public:
  ParseError(std::string file, SourceLoc loc, std::string message, const std::string& line_text);

  SourceLoc loc() const { return {line(), column()}; }
  /// The first line of what(): "file:line:col: error: message".
  std::string headline() const;
};

/// A malformed file where no position applies (a value out of range, a
/// structure, what a library reading the file reported): line and column
/// 0, what() "cannot read 'PATH': MESSAGE", message() MESSAGE.
api::SceneError malformed_file(const std::string& path, const std::string& message);

}  // namespace holoray
