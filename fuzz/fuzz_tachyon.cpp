// libFuzzer entry for the Tachyon reader; the body is in fuzz_targets.hpp.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  holoray::fuzz::tachyon(data, size);
  return 0;
}
