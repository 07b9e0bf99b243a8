#include "scene/tokenizer.hpp"

#include <charconv>
#include <cmath>
#include <fmt/format.h>

namespace holoray {

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

// A finite number, the whole token; from_chars also accepts "nan"/"inf",
// which we refuse separately so the message can say so.
bool parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}
}  // namespace

std::string describe_token(const Token& tok) {
  if (tok.text.empty()) return "end of file";
  std::string shown;
  for (char c : tok.text.substr(0, 40)) shown += (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) ? '?' : c;
  if (tok.text.size() > 40) shown += "...";
  return fmt::format("'{}'", shown);
}

Tokenizer::Tokenizer(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

Token Tokenizer::scan() {
  for (;;) {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') {
        ++line_;
        line_start_ = pos_ + 1;
        line_starts_.push_back(line_start_);
      }
      ++pos_;
    }
    if (pos_ < text_.size() && text_[pos_] == '#') {  // comment to end of line, anywhere (nff-notes §1)
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      continue;
    }
    break;
  }
  Token tok;
  tok.loc = {line_, static_cast<int>(pos_ - line_start_) + 1};
  const size_t start = pos_;
  while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != '#') ++pos_;
  tok.text = text_.substr(start, pos_ - start);
  if (!tok.text.empty()) last_end_ = {tok.loc.line, tok.loc.col + static_cast<int>(tok.text.size())};
  return tok;
}

const Token& Tokenizer::peek() {
  if (!has_peek_) {
    peeked_ = scan();
    has_peek_ = true;
  }
  return peeked_;
}

Token Tokenizer::next() {
  peek();
  has_peek_ = false;
  return peeked_;
}

bool Tokenizer::next_is_number() {
  double v;
  return parse_double(peek().text, v);
}

double Tokenizer::number(std::string_view what) {
  const Token tok = next();
  double v;
  if (!parse_double(tok.text, v)) {
    std::string_view t = tok.text;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec == std::errc::result_out_of_range && r.ptr == t.data() + t.size())
      fail(tok.loc, fmt::format("expected a finite number for {}, found {} (beyond the range of a double)", what,
                                describe_token(tok)));
    fail_expected(tok, what);
  }
  if (!std::isfinite(v)) fail(tok.loc, fmt::format("expected a finite number for {}, found {}", what, describe_token(tok)));
  return v;
}

long Tokenizer::integer(std::string_view what) {
  const Token tok = next();
  long v = 0;
  const auto r = std::from_chars(tok.text.data(), tok.text.data() + tok.text.size(), v);
  if (tok.text.empty() || r.ec != std::errc() || r.ptr != tok.text.data() + tok.text.size() || v < 0)
    fail_expected(tok, what);
  return v;
}

void Tokenizer::expect(std::string_view keyword) {
  const Token tok = next();
  if (tok.text != keyword) fail_expected(tok, fmt::format("'{}'", keyword));
}


std::string Tokenizer::line_text(int line) const {
  if (line < 1 || line > static_cast<int>(line_starts_.size())) return {};
  const size_t b = line_starts_[line - 1];
  size_t e = b;
  while (e < text_.size() && text_[e] != '\n' && e - b < 200) ++e;
  std::string s(text_.substr(b, e - b));
  if (!s.empty() && s.back() == '\r') s.pop_back();
  for (char& c : s)
    if ((static_cast<unsigned char>(c) < 32 && c != '\t') || static_cast<unsigned char>(c) > 126) c = '?';
  return s;
}

void Tokenizer::fail(SourceLoc loc, const std::string& message) const {
  throw ParseError(source_, loc, message, line_text(loc.line));
}

void Tokenizer::fail_expected(const Token& tok, std::string_view what) const {
  // A missing token is reported where the file ends, not on a blank line after it.
  const SourceLoc loc = tok.text.empty() ? end_loc() : tok.loc;
  fail(loc, fmt::format("expected {}, found {}", what, describe_token(tok)));
}

}  // namespace holoray
