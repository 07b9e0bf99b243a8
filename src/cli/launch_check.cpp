#include "cli/launch_check.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdlib>
#include <string_view>

namespace holoray::cli {

std::optional<int> mpi_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    const char* v = std::getenv(name);
    if (!v) continue;
    int n = 0;
    const std::string_view s(v);
    if (std::from_chars(s.data(), s.data() + s.size(), n).ec == std::errc() && n >= 1) return n;
  }
  return std::nullopt;
}

std::string mpi_launch_error() {
  const auto n = mpi_world_size();
  if (!n || *n <= 1) return {};
  return fmt::format(
      "launched as one of {} MPI processes, but this holoray is built without MPI: each would render the same "
      "frames into the same files. Run it once, or give each task its own frames with animate --frames A:B",
      *n);
}

}  // namespace holoray::cli
