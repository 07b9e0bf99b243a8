#include "scene/parse_error.hpp"

#include <fmt/format.h>

namespace holoray {
namespace {

std::string format_report(const std::string& file, SourceLoc loc, const std::string& message,
                          const std::string& line_text) {
  std::string out = fmt::format("{}:{}:{}: error: {}", file, loc.line, loc.col, message);
  if (!line_text.empty()) {
    // Tabs are kept so the caret lines up under the same characters.
    std::string pad;
    for (int i = 0; i + 1 < loc.col && i < static_cast<int>(line_text.size()); ++i)
      pad += line_text[i] == '\t' ? '\t' : ' ';
    out += fmt::format("\n  {}\n  {}^", line_text, pad);
  }
  return out;
}

}  // namespace

ParseError::ParseError(std::string file, SourceLoc loc, std::string message, const std::string& line_text)
    : api::SceneError(file, loc.line, loc.col, message, format_report(file, loc, message, line_text)) {}

std::string ParseError::headline() const {
  return fmt::format("{}:{}:{}: error: {}", file(), line(), column(), message());
}

api::SceneError malformed_file(const std::string& path, const std::string& message) {
  return api::SceneError(path, 0, 0, message, fmt::format("cannot read '{}': {}", path, message));
}

}  // namespace holoray
