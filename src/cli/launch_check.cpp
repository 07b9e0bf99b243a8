#include "cli/launch_check.hpp"

#include <fmt/format.h>

#include "cluster/mpi_world.hpp"

namespace holoray::cli {

std::string mpi_launch_error() {
  const auto n = cluster::launcher_world_size();
  if (!n || *n <= 1) return {};
  return fmt::format(
      "launched as one of {} MPI processes, but this holoray is built without MPI: each would render the same "
      "frames into the same files. Run it once, or give each task its own frames with animate --frames A:B",
      *n);
}

}  // namespace holoray::cli
