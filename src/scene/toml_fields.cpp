#include "scene/toml_fields.hpp"

#include <fmt/format.h>

#include <cmath>

#include "scene/parse_error.hpp"

namespace holoray {

toml::table TomlFields::parse() const {
  check_code_points();
  try {
    return toml::parse(text_, source_);
  } catch (const toml::parse_error& e) {
    fail(e.source(), std::string(e.description()));
  }
}

// toml++ 3.3.0 (Debian 12) reaches __builtin_unreachable when it tests
// U+00A1..U+0499, U+2C5E..U+3057 (but U+3000) or U+FB26..U+FEFE for whitespace, which its
// scanner does in places that depend on the state it is in (found by
// fuzz_shot). Those code points are refused anywhere, before it sees them,
// with a message naming the character. Other non-ASCII text is passed on.
void TomlFields::check_code_points() const {
  const std::string_view t = text_;
  int line = 1;
  size_t line_start = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const auto b0 = static_cast<unsigned char>(t[i]);
    if (b0 == '\n') {
      ++line, line_start = i + 1;
      continue;
    }
    // Only two- and three-byte UTF-8 sequences can encode the bad ranges.
    char32_t c = 0;
    if ((b0 & 0xE0) == 0xC0 && i + 1 < t.size() && (t[i + 1] & 0xC0) == 0x80) {
      c = (char32_t(b0 & 0x1F) << 6) | char32_t(t[i + 1] & 0x3F);
    } else if ((b0 & 0xF0) == 0xE0 && i + 2 < t.size() && (t[i + 1] & 0xC0) == 0x80 && (t[i + 2] & 0xC0) == 0x80) {
      c = (char32_t(b0 & 0x0F) << 12) | (char32_t(t[i + 1] & 0x3F) << 6) | char32_t(t[i + 2] & 0x3F);
    }
    const bool bad = (c >= 0xA1 && c <= 0x499) || (c >= 0x2C5E && c <= 0x3057 && c != 0x3000) || (c >= 0xFB26 && c <= 0xFEFE);
    if (bad)
      throw ParseError(source_, SourceLoc{line, static_cast<int>(i - line_start) + 1},
                       fmt::format("found the character U+{:04X}, which holoray's TOML files cannot hold (a limitation of the "
                                   "TOML library, toml++ 3.3.0); use ASCII names",
                                   static_cast<uint32_t>(c)),
                       line_text(line));
  }
}

void TomlFields::fail(const toml::source_region& where, const std::string& message) const {
  const int line = static_cast<int>(where.begin.line), col = static_cast<int>(where.begin.column);
  throw ParseError(source_, SourceLoc{line, col}, message, line_text(line));
}

std::string TomlFields::line_text(int line) const {
  size_t pos = 0;
  for (int l = 1; l < line && pos != std::string_view::npos; ++l) {
    pos = text_.find('\n', pos);
    if (pos != std::string_view::npos) ++pos;
  }
  if (pos == std::string_view::npos || pos > text_.size()) return {};
  const size_t end = text_.find('\n', pos);
  std::string s(text_.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos));
  if (!s.empty() && s.back() == '\r') s.pop_back();
  return s;
}

void TomlFields::check_keys(const toml::table& t, std::string_view where, std::initializer_list<std::string_view> known) const {
  for (auto&& [key, value] : t) {
    bool ok = false;
    for (std::string_view k : known) ok = ok || key.str() == k;
    if (!ok) {
      std::string list;
      for (std::string_view k : known) list += fmt::format("{}{}", list.empty() ? "" : ", ", k);
      fail(key.source(), fmt::format("unknown key '{}' in {} (expected one of: {})", key.str(), where, list));
    }
  }
}

const toml::table* TomlFields::table(const toml::table& t, std::string_view key) const {
  const toml::node* n = t.get(key);
  if (!n) return nullptr;
  if (!n->is_table()) fail(n->source(), fmt::format("expected '{}' to be a table", key));
  return n->as_table();
}

std::optional<int64_t> TomlFields::integer(const toml::table& t, std::string_view key, int64_t lo, int64_t hi,
                               bool required) const {
  const toml::node* n = t.get(key);
  if (!n) {
    if (required) fail(t.source(), fmt::format("expected '{}' (an integer from {} to {}), found none", key, lo, hi));
    return std::nullopt;
  }
  const auto v = n->value_exact<int64_t>();
  if (!v) fail(n->source(), fmt::format("expected '{}' to be an integer", key));
  if (*v < lo || *v > hi) fail(n->source(), fmt::format("expected '{}' from {} to {}, found {}", key, lo, hi, *v));
  return v;
}

double TomlFields::as_number(const toml::node& n, std::string_view key) const {
  std::optional<double> v;
  if (n.is_floating_point()) v = n.value_exact<double>();
  else if (n.is_integer()) v = static_cast<double>(*n.value_exact<int64_t>());
  if (!v) fail(n.source(), fmt::format("expected '{}' to be a number", key));
  if (!std::isfinite(*v)) fail(n.source(), fmt::format("expected '{}' to be finite, found {}", key, *v));
  return *v;
}

std::optional<double> TomlFields::number(const toml::table& t, std::string_view key, double lo, double hi) const {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  const double v = as_number(*n, key);
  if (v < lo || v > hi) fail(n->source(), fmt::format("expected '{}' from {} to {}, found {}", key, lo, hi, v));
  return v;
}

std::optional<std::string> TomlFields::string(const toml::table& t, std::string_view key) const {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  if (!n->is_string()) fail(n->source(), fmt::format("expected '{}' to be a string", key));
  return std::string(*n->value_exact<std::string>());
}

std::string TomlFields::choice(const toml::table& t, std::string_view key, std::initializer_list<std::string_view> options,
                   std::string_view fallback) const {
  const auto s = string(t, key);
  if (!s) return std::string(fallback);
  std::string list;
  for (std::string_view o : options) {
    if (*s == o) return *s;
    list += fmt::format("{}{}", list.empty() ? "" : ", ", o);
  }
  fail(t.get(key)->source(), fmt::format("expected '{}' to be one of {}, found '{}'", key, list, *s));
}

std::optional<Vec3> TomlFields::vec3(const toml::table& t, std::string_view key, bool scalar_ok) const {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  if (scalar_ok && (n->is_integer() || n->is_floating_point())) {
    const double v = as_number(*n, key);
    return Vec3{v, v, v};
  }
  const toml::array* a = n->as_array();
  if (!a || a->size() != 3)
    fail(n->source(), fmt::format("expected '{}' to be [x, y, z]{}", key, scalar_ok ? " or one number" : ""));
  return Vec3{as_number((*a)[0], key), as_number((*a)[1], key), as_number((*a)[2], key)};
}

}  // namespace holoray
