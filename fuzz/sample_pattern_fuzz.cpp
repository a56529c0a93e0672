// The sample-pattern JSON reader, for every legal sample count (a file must match --samples).

#include "fuzz/fuzz_target.h"
#include "raster/raster_error.h"
#include "raster/sample_pattern.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (const int samples : {1, 2, 4, 8, 16}) {
    try {
      raster::ParsePatternJson(fuzz::Text(data, size), samples, "fuzz.json");
    } catch (const raster::RasterError&) {
    }
  }
  return 0;
}
