// Raster counters as JSON (see counters_json.h).

#include "cli/counters_json.h"

namespace cli {

nlohmann::ordered_json CountersJson(const raster::RasterCounters& counters) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  for (const raster::RasterCounterField& field : raster::kRasterCounterFields) {
    json[field.name] = counters.*field.member;
  }
  return json;
}

}  // namespace cli
