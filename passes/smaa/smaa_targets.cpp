// SMAA's lookup tables as textures (see smaa_targets.h).

#include "passes/smaa/smaa_targets.h"

#include <algorithm>

#include "passes/smaa/area_tex.h"
#include "passes/smaa/search_tex.h"

namespace passes::smaa {

LookupTables LookupTables::Make() {
  LookupTables tables{{"smaa/area-tex", kAreaTexWidth, kAreaTexHeight, sim::Format::RG8Unorm},
                      {"smaa/search-tex", kSearchTexWidth, kSearchTexHeight, sim::Format::R8Unorm}};
  // The tables' bytes are the textures' codes (RG interleaved, as the published files).
  std::ranges::copy(AreaTexBytes(), tables.area.Codes().begin());
  std::ranges::copy(SearchTexBytes(), tables.search.Codes().begin());
  return tables;
}

}  // namespace passes::smaa
