// libFuzzer entry for the glTF mesh reader; the body is in fuzz_targets.hpp.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  holoray::fuzz::gltf(data, size);
  return 0;
}
