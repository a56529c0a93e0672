#pragma once
// Template members of eqaa_surface.h.

#include <type_traits>

namespace fmask {

template <typename Self, typename Fn>
void VisitFragmentCounters(Self& c, Fn&& fn) {
  static constexpr const char* kBefore[] = {"fragments/before_0", "fragments/before_1", "fragments/before_2",
                                            "fragments/before_3", "fragments/before_4", "fragments/before_5",
                                            "fragments/before_6", "fragments/before_7", "fragments/before_8"};
  static constexpr const char* kAfter[] = {"fragments/after_0", "fragments/after_1", "fragments/after_2",
                                           "fragments/after_3", "fragments/after_4", "fragments/after_5",
                                           "fragments/after_6", "fragments/after_7", "fragments/after_8"};
  fn("pixels/updates", c.pixelUpdates);
  for (std::size_t k = 0; k < c.fragmentsBefore.size(); ++k) fn(kBefore[k], c.fragmentsBefore[k]);
  for (std::size_t k = 0; k < c.fragmentsAfter.size(); ++k) fn(kAfter[k], c.fragmentsAfter[k]);
  fn("fragments/added", c.fragmentsAdded);
  fn("fragments/removed", c.fragmentsRemoved);
  fn("fragments/evictions", c.evictions);
  fn("fragments/rejected", c.fragmentsRejected);
  fn("samples/unknown_by_eviction", c.samplesUnknownByEviction);
  fn("samples/unknown_by_untestable", c.samplesUnknownByUntestable);
  fn("samples/zplane_rescues", c.zPlaneRescues);
}

template <typename Fn>
void FragmentCounters::ForEach(Fn&& fn) const {
  VisitFragmentCounters(*this, fn);
}

template <typename ColourFn>
FragmentCounters EqaaSurface::UpdateAll(const raster::RasterResult& result, ColourFn&& colourOf) {
  using Fn = std::remove_reference_t<ColourFn>;
  return UpdateAllBins(result, {&colourOf, [](const void* context, const raster::QuadFragment& quad, int pixel) {
                                  return Colour((*static_cast<Fn*>(const_cast<void*>(context)))(quad, pixel));
                                }});
}

}  // namespace fmask
