#include "holoray/errors.hpp"

namespace holoray::api {

SceneError::SceneError(std::string file, int line, int column, std::string message, const std::string& report)
    : std::runtime_error(report), file_(std::move(file)), line_(line), column_(column), message_(std::move(message)) {}

}  // namespace holoray::api
