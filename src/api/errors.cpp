#include "holoray/errors.hpp"

namespace holoray::api {

SceneError::SceneError(std::string file, int line, int column, std::string message, const std::string& report)
    : std::runtime_error(report), file_(std::move(file)), line_(line), column_(column), message_(std::move(message)) {}

std::string say_names(std::string_view message, const std::function<std::string(std::string_view)>& say) {
  std::string out;
  out.reserve(message.size());
  for (size_t at = 0; at < message.size();) {
    const size_t open = message.find('`', at);
    const size_t close = open == message.npos ? open : message.find('`', open + 1);
    if (close == message.npos) {
      out.append(message.substr(at));
      break;
    }
    out.append(message.substr(at, open - at));
    const std::string_view name = message.substr(open + 1, close - open - 1);
    const bool is_name = !name.empty() && name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_") ==
                                              std::string_view::npos;
    out.append(is_name ? say(name) : std::string(message.substr(open, close + 1 - open)));
    at = close + 1;
  }
  return out;
}

}  // namespace holoray::api
