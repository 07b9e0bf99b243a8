// libFuzzer entry for the camera_path reader; the body is in fuzz_targets.hpp.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  holoray::fuzz::camera_path(data, size);
  return 0;
}
