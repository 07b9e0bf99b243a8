#include "cli/launch_check.hpp"

#include <unistd.h>

#include <fmt/format.h>

#include <filesystem>
#include <system_error>

#include "cluster/mpi_world.hpp"

namespace holoray::cli {

namespace {
bool launched_as_several() {
  const auto n = cluster::launcher_world_size();
  return n && *n > 1;
}
}  // namespace

std::string mpi_program() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = exe.parent_path().parent_path() / "lib/holoray/holoray-mpi";
    if (std::filesystem::is_regular_file(installed, ec)) return installed.string();
  }
#ifdef HOLORAY_MPI_PROGRAM
  if (std::filesystem::is_regular_file(HOLORAY_MPI_PROGRAM, ec)) return HOLORAY_MPI_PROGRAM;
#endif
  return {};
}

void become_mpi_program_if_launched(char** argv) {
  if (cluster::built_with_mpi() || !launched_as_several()) return;
  const std::string program = mpi_program();
  if (!program.empty()) ::execv(program.c_str(), argv);
}

std::string mpi_launch_error() {
  if (!launched_as_several()) return {};
  return fmt::format(
      "launched as one of {} MPI processes, but this holoray is built without MPI: each would render the same "
      "frames into the same files. Run it once, or give each task its own frames with animate --frames A:B",
      *cluster::launcher_world_size());
}

}  // namespace holoray::cli
