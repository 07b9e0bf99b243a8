// holoray public API: a named choice among a few, for every front end's
// option values (the CLI's --method, the API's and Python's method="...").
#pragma once

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

namespace holoray {

/// The value of `choices` named `value`; else std::invalid_argument
/// "OPTION: expected one of A, B, got 'VALUE'" (Python: ValueError).
template <class T>
T pick(const std::string& option, const std::string& value, std::initializer_list<std::pair<const char*, T>> choices) {
  std::string names;
  for (const auto& [name, v] : choices) {
    if (value == name) return v;
    if (!names.empty()) names.append(", ");
    names.append(name);
  }
  std::string message = option;
  message.append(": expected one of ").append(names).append(", got '").append(value).append("'");
  throw std::invalid_argument(message);
}

}  // namespace holoray
