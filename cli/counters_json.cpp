// Raster and colour-block counters as JSON (see counters_json.h).

#include "cli/counters_json.h"

#include <cstdint>

namespace cli {

nlohmann::ordered_json CountersJson(const raster::RasterCounters& counters) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  for (const raster::RasterCounterField& field : raster::kRasterCounterFields) {
    json[field.name] = counters.*field.member;
  }
  return json;
}

nlohmann::ordered_json FragmentCountersJson(const fmask::FragmentCounters& counters) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  counters.ForEach([&](const char* name, std::uint64_t value) { json[name] = value; });
  return json;
}

}  // namespace cli
