#pragma once
// Per-frame sample-pattern schedules for temporal passes: frame k of a sequence is drawn with
// the schedule's pattern k (cycling). Each schedule has a fixed sample count; "none" repeats the
// run's own pattern. Offsets are on the 1/16-px grid like every pattern (hw-facts §4), +y down.
//
//   none            the run's pattern every frame (any S)
//   halton8         1S, halton:(k mod 8): Halton(2,3) projection jitter, UE4's default length
//                   (seed 002; aa-facts §5.1, §5.3 "MiniEngine uses the 8-entry prefix")
//   halton16        1S, halton:(k mod 16) (aa-facts §5.2 INSIDE's default, §5.3 Intel TAA)
//   t2x             1S, SMAA T2x: (+0.25, +0.25) then (-0.25, -0.25) px (aa-facts §1.8, the
//                   table's (+0.25, -0.25) / (-0.25, +0.25) with y up)
//   4x              2S, SMAA 4x: the standard 2x pattern shifted by (+0.125, -0.125) then
//                   (-0.125, +0.125) px (aa-facts §1.8: net S0..S3 of the table, y flipped)
//   flipquad-split  1S, temporal FLIPQUAD (seed 001 "Temporal FLIPQUAD"): frame A draws sample 0
//                   of the 2x FLIPQUAD pattern in every quad pixel, frame B sample 1
//   quincunx        1S, the 2x quincunx pattern split over two frames: the pixel centre, then
//                   the shared top-left corner (seed 001 "2x Quincunx")

#include <string>
#include <string_view>
#include <vector>

#include "raster/sample_pattern.h"

namespace raster {

class JitterSchedule {
 public:
  // Throws RasterError listing the names for an unknown name. `base` is the run's pattern, used
  // by "none" only.
  static JitterSchedule Make(std::string_view name, const SamplePattern& base);

  const std::string& Name() const { return name_; }
  int Samples() const { return patterns_.front().Count(); }
  int Length() const { return static_cast<int>(patterns_.size()); }  // frames before it repeats
  // Frame k's pattern (k >= 0).
  const SamplePattern& At(int frame) const;

 private:
  JitterSchedule(std::string name, std::vector<SamplePattern> patterns)
      : name_(std::move(name)), patterns_(std::move(patterns)) {}
  std::string name_;
  std::vector<SamplePattern> patterns_;
};

std::vector<std::string> JitterScheduleNames();
// The sample count a named schedule draws with; 0 for "none" (the run's).
int JitterScheduleSamples(std::string_view name);

}  // namespace raster
