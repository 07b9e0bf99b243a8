// holoray/cli: what a holoray built without MPI does as one of several MPI
// ranks (issue 15, item 5). The program users run, `holoray`, links no MPI:
// linking it costs every command its start-up, mpirun or not (OpenMPI 5's
// UCX times the CPU clock in a library constructor: 146 ms a command on
// Debian 13; 12 ms on Debian 12). Where the build made `holoray-mpi` (the same
// program with MPI), a launched `holoray` becomes it; elsewhere (the
// sanitizer builds, a machine without MPI) each of the N processes would
// render the same frames into the same folder, N times the work for one
// result, racing on every file: it says so and stops instead.
#pragma once

#include <string>

namespace holoray::cli {

/// The MPI build of this program: `holoray-mpi` in ../lib/holoray beside
/// the running program (installed), else where the build put it; empty when
/// this build has none.
std::string mpi_program();

/// Launched as one of several ranks by a launcher (mpirun, srun): replaces
/// this process by mpi_program() with the same arguments (execv keeps the
/// process id and environment the launcher knows it by). Returns when not
/// launched, when there is no MPI program, or when exec fails.
void become_mpi_program_if_launched(char** argv);

/// The error to print when launched as one of several ranks, else empty.
std::string mpi_launch_error();

}  // namespace holoray::cli
