// The libFuzzer entry point of one target: compiled once per target with
// SSS_FUZZ_TARGET set to its function (fuzz/CMakeLists.txt).
#include "FuzzTargets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return SSS_FUZZ_TARGET(data, size);
}
