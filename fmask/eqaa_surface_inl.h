#pragma once
// Template members of eqaa_surface.h.

#include <tbb/parallel_for.h>

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
  const std::size_t bins = result.quadsByBin.size();
  std::vector<FragmentCounters> binCounters(bins);
  std::vector<std::vector<TraceEvent>> binTraces(bins);
  tbb::parallel_for(std::size_t{0}, bins, [&](std::size_t bin) {
    for (const raster::QuadFragment& quad : result.quadsByBin[bin]) {
      std::array<Colour, 4> colours;
      for (int p = 0; p < raster::kQuadPixels; ++p) colours[p] = colourOf(quad, p);
      UpdateQuad(quad, colours, binCounters[bin], binTraces[bin]);
    }
  });
  FragmentCounters total;
  for (std::size_t bin = 0; bin < bins; ++bin) {
    total.Merge(binCounters[bin]);
    trace_.insert(trace_.end(), binTraces[bin].begin(), binTraces[bin].end());
  }
  return total;
}

}  // namespace fmask
