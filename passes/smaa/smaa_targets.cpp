// SMAA's lookup tables as textures (see smaa_targets.h).

#include "passes/smaa/smaa_targets.h"

#include "passes/smaa/area_tex.h"
#include "passes/smaa/search_tex.h"

namespace passes::smaa {

LookupTables LookupTables::Make() {
  LookupTables tables{{"smaa/area-tex", kAreaTexWidth, kAreaTexHeight, sim::Format::RG8Unorm},
                      {"smaa/search-tex", kSearchTexWidth, kSearchTexHeight, sim::Format::R8Unorm}};
  const std::span<const std::uint8_t> area = AreaTexBytes();
  std::span<glm::vec2> areaTexels = tables.area.Texels();
  for (std::size_t i = 0; i < areaTexels.size(); ++i) {
    areaTexels[i] = {sim::Unorm8ToFloat(area[2 * i]), sim::Unorm8ToFloat(area[2 * i + 1])};
  }
  const std::span<const std::uint8_t> search = SearchTexBytes();
  std::span<float> searchTexels = tables.search.Texels();
  for (std::size_t i = 0; i < searchTexels.size(); ++i) searchTexels[i] = sim::Unorm8ToFloat(search[i]);
  return tables;
}

}  // namespace passes::smaa
