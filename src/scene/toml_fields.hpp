// holoray/scene: reading a TOML file (shot files, display files) into plain
// structs with every error at its file:line:col. toml++ does the parsing;
// this adds the checks every such reader wants: unknown keys refused, numbers
// finite and in range, choices named, and the characters toml++ 3.3.0
// cannot scan safely refused before it sees them.
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "math/vec.hpp"

namespace holoray {

/// One TOML file being read. Every accessor throws ParseError at the
/// offending node ("file:line:col: error: expected ..., found ...").
class TomlFields {
 public:
  /// `text` must outlive the reader; `source` names the file in messages.
  TomlFields(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  /// The whole file; syntax errors become ParseError.
  toml::table parse() const;
  const std::string& source() const { return source_; }

  [[noreturn]] void fail(const toml::source_region& where, const std::string& message) const;
  /// Typos must not pass silently: every key of `t` has to be in `known`.
  void check_keys(const toml::table& t, std::string_view where, std::initializer_list<std::string_view> known) const;
  /// The sub-table `key`, or null when absent (an error when not a table).
  const toml::table* table(const toml::table& t, std::string_view key) const;
  std::optional<int64_t> integer(const toml::table& t, std::string_view key, int64_t lo, int64_t hi,
                                 bool required = false) const;
  /// A finite number (an integer is taken as one).
  double as_number(const toml::node& n, std::string_view key) const;
  std::optional<double> number(const toml::table& t, std::string_view key, double lo, double hi) const;
  std::optional<std::string> string(const toml::table& t, std::string_view key) const;
  /// One of `options`; `fallback` when absent.
  std::string choice(const toml::table& t, std::string_view key, std::initializer_list<std::string_view> options,
                     std::string_view fallback) const;
  /// [x, y, z], or one number for all three when `scalar_ok`.
  std::optional<Vec3> vec3(const toml::table& t, std::string_view key, bool scalar_ok = false) const;

 private:
  void check_code_points() const;
  std::string line_text(int line) const;

  std::string_view text_;
  std::string source_;
};

}  // namespace holoray
