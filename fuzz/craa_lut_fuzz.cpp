// The CRAA LUT fixture reader (docs/craa.md "File format"); a table it accepts must format and
// read back equal.

#include <cstdlib>

#include "fuzz/fuzz_target.h"
#include "passes/craa/craa_lut.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const passes::craa::CraaLut lut = passes::craa::ParseCraaLut(fuzz::Text(data, size), "fuzz.json");
    if (passes::craa::ParseCraaLut(passes::craa::FormatCraaLut(lut), "formatted") != lut) std::abort();
  } catch (const passes::craa::CraaLutError&) {
  }
  return 0;
}
