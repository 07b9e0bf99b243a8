// holoray/scene: the error every reader throws for malformed input.
#pragma once

#include <stdexcept>
#include <string>

#include "scene/scene_desc.hpp"

namespace holoray {

/// A malformed-input error at a file position. what() is the full report:
///
///     file:line:col: error: <message>
///       <the offending line>
///       <caret under the column>
///
/// message() alone is "<what was expected>, found <what was found>".
class ParseError : public std::runtime_error {
 public:
  ParseError(std::string file, SourceLoc loc, std::string message, const std::string& line_text);

  const std::string& file() const { return file_; }
  SourceLoc loc() const { return loc_; }
  const std::string& message() const { return message_; }
  /// The first line of what(): "file:line:col: error: message".
  std::string headline() const;

 private:
  std::string file_;
  SourceLoc loc_;
  std::string message_;
};

}  // namespace holoray
