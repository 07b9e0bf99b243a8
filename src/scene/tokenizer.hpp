// holoray/scene: whitespace tokenizer with `#` comments and source positions,
// shared by the text scene readers. Errors it raises are ParseErrors that show
// the offending line and a caret.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/parse_error.hpp"

namespace holoray {

struct Token {
  std::string_view text;  // empty at end of file
  SourceLoc loc;
};

class Tokenizer {
 public:
  /// `text` must outlive the tokenizer. `source` names the file in messages.
  Tokenizer(std::string_view text, std::string source);

  /// The next token without consuming it; an empty token at end of file.
  const Token& peek();
  Token next();
  bool at_end() { return peek().text.empty(); }

  /// Consumes a number; throws "expected <what>, found '<token>'" when the
  /// token is not a finite decimal number ("end of file" when there is none).
  double number(std::string_view what);
  /// Consumes a non-negative integer that fits in a long.
  long integer(std::string_view what);
  /// True when the next token reads as a number (used for NFF's optional light colour).
  bool next_is_number();
  /// Consumes `keyword` or throws "expected '<keyword>', found '<token>'".
  void expect(std::string_view keyword);

  [[noreturn]] void fail(SourceLoc loc, const std::string& message) const;
  /// Fails at `tok` with "expected <what>, found <tok>".
  [[noreturn]] void fail_expected(const Token& tok, std::string_view what) const;

  const std::string& source() const { return source_; }
  /// Position just past the last token read (where a truncated file is reported).
  SourceLoc end_loc() const { return last_end_; }

 private:
  Token scan();
  std::string line_text(int line) const;

  std::string_view text_;
  std::string source_;
  size_t pos_ = 0;
  int line_ = 1;
  size_t line_start_ = 0;
  std::vector<size_t> line_starts_{0};
  SourceLoc last_end_{1, 1};
  bool has_peek_ = false;
  Token peeked_;
};

/// How a token reads in a message: 'abc', or "end of file".
std::string describe_token(const Token& tok);

}  // namespace holoray
