// The GPU file reader (JSON with comments, key ranges, consistency checks).

#include "fuzz/fuzz_target.h"
#include "sim/gpu_config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    sim::ParseGpuConfig(fuzz::Text(data, size), "fuzz.jsonc");
  } catch (const sim::GpuConfigError&) {
  }
  return 0;
}
