#pragma once
// Raster and colour-block counters as JSON, generated from raster::kRasterCounterFields and
// fmask::FragmentCounters::ForEach so keys never drift from the counters (style.md
// anti-pattern 1).

#include <nlohmann/json.hpp>

#include "fmask/eqaa_surface.h"
#include "raster/counters.h"

namespace cli {

// {"triangles/in": n, ...}: one entry per field, in table order.
nlohmann::ordered_json CountersJson(const raster::RasterCounters& counters);

// {"pixels/updates": n, ...}: every counter ForEach visits, in its order.
nlohmann::ordered_json FragmentCountersJson(const fmask::FragmentCounters& counters);

}  // namespace cli
