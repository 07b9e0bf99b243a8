// holoray/scene: the error every reader throws for malformed input.
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

}  // namespace holoray
