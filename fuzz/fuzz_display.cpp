// libFuzzer entry for the display-file reader; the body is in fuzz_targets.hpp.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  holoray::fuzz::display(data, size);
  return 0;
}
