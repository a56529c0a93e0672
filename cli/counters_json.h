#pragma once
// Raster counters as JSON, generated from raster::kRasterCounterFields so keys never drift
// from the counters (style.md anti-pattern 1).

#include <nlohmann/json.hpp>

#include "raster/counters.h"

namespace cli {

// {"triangles/in": n, ...}: one entry per field, in table order.
nlohmann::ordered_json CountersJson(const raster::RasterCounters& counters);

}  // namespace cli
