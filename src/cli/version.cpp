#include "cli/version.hpp"

#include <CLI/Version.hpp>
#include <OpenEXR/OpenEXRConfig.h>
#include <assimp/version.h>
#include <fmt/format.h>
#include <oneapi/tbb/version.h>
#include <png.h>

#include "accel/embree_api.hpp"  // RTC_VERSION_STRING of the Embree built against
#include "cli/launch_check.hpp"
#include "cluster/mpi_world.hpp"
#include "holoray_version.hpp"  // generated: HOLORAY_VERSION, HOLORAY_GIT_COMMIT

namespace holoray::cli {

std::string version_text() {
  return fmt::format(
      "holoray {} (git {})\n"
      "built with: MPI {}, Embree {}, oneTBB {}, libpng {}, OpenEXR {}, assimp {}.{}.{}, FFmpeg (loaded for video "
      "only), fmt {}.{}.{}, CLI11 {}",
      HOLORAY_VERSION, HOLORAY_GIT_COMMIT, cluster::built_with_mpi() ? "yes" : !mpi_program().empty() ? "yes (holoray-mpi, under mpirun)" : "no", RTC_VERSION_STRING,
      TBB_runtime_version(), PNG_LIBPNG_VER_STRING, OPENEXR_VERSION_STRING, aiGetVersionMajor(), aiGetVersionMinor(),
      aiGetVersionPatch(), FMT_VERSION / 10000, FMT_VERSION / 100 % 100, FMT_VERSION % 100, CLI11_VERSION);
}

}  // namespace holoray::cli
