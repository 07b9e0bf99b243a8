// holoray/cli: refusing to run as one of several MPI ranks (issue 15, item 5).
// This holoray is built without MPI: under `mpirun -np N` each of the N
// processes would render the same frames into the same folder, N times the
// work for one result, racing on every file. It says so and stops instead.
#pragma once

#include <optional>
#include <string>

namespace holoray::cli {

/// The number of processes an MPI launcher started this one among, read from
/// the launchers' environment (OpenMPI's OMPI_COMM_WORLD_SIZE, MPICH and
/// Slurm's PMI_SIZE); std::nullopt when not launched by one.
std::optional<int> mpi_world_size();

/// The error to print when launched as one of several ranks, else empty.
std::string mpi_launch_error();

}  // namespace holoray::cli
