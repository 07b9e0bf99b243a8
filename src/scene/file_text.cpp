#include "scene/file_text.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace holoray {
namespace {

// I/O errors keep their errno, so that each front end can say them in its
// own words (Python: FileNotFoundError, PermissionError, IsADirectoryError).
// what() is "WHAT: <strerror>".
std::system_error io_error(int code, fmt::format_string<const std::string&> what, const std::string& path) {
  return std::system_error(code, std::generic_category(), fmt::format(what, path));
}

}  // namespace

std::ifstream open_for_reading(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw io_error(EISDIR, "cannot read '{}'", path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io_error(errno, "cannot read '{}'", path);
  return in;
}

std::string read_text_file(const std::string& path) {
  std::ifstream in = open_for_reading(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw io_error(errno ? errno : EIO, "cannot read '{}'", path);
  return ss.str();
}

void write_text_file(const std::string& path, const std::string& text) {
  const std::filesystem::path target(path);
  const std::filesystem::path tmp =
      target.parent_path() / fmt::format(".{}.tmp{}{}", target.stem().string(), ::getpid(), target.extension().string());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw io_error(errno, "cannot write '{}'", path);
    out << text;
    out.flush();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw io_error(errno ? errno : EIO, "cannot write '{}'", path);
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::system_error(ec, fmt::format("cannot write '{}'", path));
  }
}

}  // namespace holoray
