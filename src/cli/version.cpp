#include "cli/version.hpp"

#include <CLI/Version.hpp>
#include <fmt/format.h>

#include "cli/launch_check.hpp"
#include "cluster/mpi_world.hpp"
#include "holoray/holoray.hpp"
#include "holoray_version.hpp"  // generated: HOLORAY_VERSION, HOLORAY_GIT_COMMIT

namespace holoray::cli {

std::string version_text() {
  return fmt::format(
      "holoray {} (git {})\n"
      "built with: MPI {}, {}, CLI11 {}",
      HOLORAY_VERSION, HOLORAY_GIT_COMMIT,
      cluster::built_with_mpi() ? "yes" : !mpi_program().empty() ? "yes (holoray-mpi, under mpirun)" : "no",
      api::built_with(), CLI11_VERSION);
}

}  // namespace holoray::cli
