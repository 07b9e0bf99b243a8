// holoray/cli: refusing to run as one of several MPI ranks (issue 15, item 5).
// This holoray is built without MPI: under `mpirun -np N` each of the N
// processes would render the same frames into the same folder, N times the
// work for one result, racing on every file. It says so and stops instead.
#pragma once

#include <string>

namespace holoray::cli {

/// The error to print when launched as one of several ranks, else empty.
std::string mpi_launch_error();

}  // namespace holoray::cli
