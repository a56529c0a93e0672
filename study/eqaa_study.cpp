// The EQAA study's rows (see eqaa_study.h).

#include "study/eqaa_study.h"

#include <string_view>

#include "fmask/layout.h"
#include "study/study.h"

namespace study {
namespace {

constexpr std::uint64_t kColourFragmentBytes = 4;  // RGBA8 fragments (sim/eqaa_resources.h)

struct ResolveCost {
  std::uint64_t fmask = 0, fragments = 0, other = 0;
  std::uint64_t waves = 0, active = 0, launched = 0;
  double microseconds = 0.0;
};

ResolveCost CostOf(const Study& study, std::size_t first, std::size_t end) {
  ResolveCost cost;
  for (std::size_t i = first; i < end; ++i) {
    const sim::DispatchReport& report = study.dispatches[i].report;
    for (const sim::ResourceTraffic& traffic : report.resources) {
      std::uint64_t& bucket = traffic.name == "eqaa/fmask"       ? cost.fmask
                              : traffic.name == "eqaa/fragments" ? cost.fragments
                                                                 : cost.other;
      bucket += traffic.bytesRead;
    }
    cost.waves += report.lanes.waves;
    cost.active += report.lanes.lanesActive;
    cost.launched += report.lanes.lanesLaunched;
    cost.microseconds += report.time.totalMicroseconds;
  }
  return cost;
}

EqaaStudyRow RowOf(const Study& study, const StudyFrame& frame, std::string_view resolve, const ScoredImage& image,
                   std::size_t first, std::size_t end) {
  const ResolveCost cost = CostOf(study, first, end);
  return {.mode = fmask::EqaaName(frame.mode),
          .policy = frame.policy,
          .resolve = std::string(resolve),
          .quality = image.quality.scores,
          .pixels = static_cast<std::uint64_t>(image.colour.Width()) * static_cast<std::uint64_t>(image.colour.Height()),
          .written = ModelColourBlockBytes(frame.fragments, frame.mode),
          .fmaskBytesRead = cost.fmask,
          .fragmentBytesRead = cost.fragments,
          .tableBytesRead = cost.other,
          .unknown = frame.unknown,
          .evictions = frame.fragments.evictions,
          .resolveWaves = cost.waves,
          .resolveLanesActive = cost.active,
          .resolveLanesLaunched = cost.launched,
          .resolveMicroseconds = cost.microseconds};
}

}  // namespace

UnknownSamples CountUnknownSamples(const fmask::EqaaSurface& surface) {
  UnknownSamples unknown;
  const fmask::FmaskLayout& layout = surface.Layout();
  if (!layout.IsEqaa()) return unknown;
  for (int y = 0; y < surface.Height(); ++y) {
    for (int x = 0; x < surface.Width(); ++x) {
      const fmask::FmaskElement element = surface.Fmask(x, y);
      for (int s = 0; s < surface.Config().coverageSamples; ++s) {
        if (layout.Code(element, s) != layout.UnknownCode()) continue;
        switch (surface.Cause(x, y, s)) {
          case fmask::UnknownCause::Eviction: ++unknown.eviction; break;
          case fmask::UnknownCause::Untestable: ++unknown.untestable; break;
          default: ++unknown.initial; break;
        }
      }
    }
  }
  return unknown;
}

ColourBlockBytes ModelColourBlockBytes(const fmask::FragmentCounters& counters, const fmask::EqaaConfig& mode) {
  const fmask::FmaskLayout layout = fmask::FmaskLayout::For(mode.coverageSamples, mode.fragments);
  const std::uint64_t elementBytes = static_cast<std::uint64_t>(layout.ElementBits()) / 8;
  return {.fmaskRead = counters.pixelUpdates * elementBytes,
          .fmaskWritten = counters.pixelUpdates * elementBytes,
          .colourWritten = (counters.pixelUpdates - counters.fragmentsRejected) * kColourFragmentBytes};
}

std::vector<EqaaStudyRow> EqaaStudyRows(const Study& study) {
  std::vector<EqaaStudyRow> rows;
  for (const StudyFrame& frame : study.frames) {
    rows.push_back(RowOf(study, frame, "box", frame.image, frame.drawDispatch + 1, frame.drawDispatch + 2));
    for (const StudyResolve& resolve : frame.resolves) {
      rows.push_back(RowOf(study, frame, resolve.name, resolve.image, resolve.firstDispatch, resolve.endDispatch));
    }
  }
  return rows;
}

}  // namespace study
