// The library's version and the libraries it was built with, each from its
// own header (holoray/holoray.hpp).
#include <OpenEXR/OpenEXRConfig.h>
#include <assimp/version.h>
#include <fmt/format.h>
#include <oneapi/tbb/version.h>
#include <png.h>

#include "accel/embree_api.hpp"  // RTC_VERSION_STRING of the Embree built against
#include "holoray/holoray.hpp"

namespace holoray::api {

const char* version() { return HOLORAY_VERSION_STRING; }

std::string built_with() {
  return fmt::format("Embree {}, oneTBB {}, libpng {}, OpenEXR {}, assimp {}.{}.{}, FFmpeg (loaded for video only), fmt {}.{}.{}",
                     RTC_VERSION_STRING, TBB_runtime_version(), PNG_LIBPNG_VER_STRING, OPENEXR_VERSION_STRING,
                     aiGetVersionMajor(), aiGetVersionMinor(), aiGetVersionPatch(), FMT_VERSION / 10000,
                     FMT_VERSION / 100 % 100, FMT_VERSION % 100);
}

}  // namespace holoray::api
