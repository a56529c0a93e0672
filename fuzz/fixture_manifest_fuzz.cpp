// The fixture manifest reader: schema, version and the canonical-set check of `fixtures --verify`.

#include <stdexcept>

#include "cli/fixture_manifest.h"
#include "fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    cli::ParseFixtureManifest(fuzz::Text(data, size), "manifest.json");
  } catch (const std::runtime_error&) {
  }
  return 0;
}
