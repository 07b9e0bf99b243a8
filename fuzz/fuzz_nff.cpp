// libFuzzer entry for the nff reader; the body is in fuzz_targets.hpp.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  holoray::fuzz::nff(data, size);
  return 0;
}
