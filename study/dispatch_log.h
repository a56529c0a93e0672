#pragma once
// The study's dispatches, each with where it ran, in run order. One record per dispatch instead
// of parallel label vectors, so a run that adds a sweep point or a frame index adds a field here,
// not another vector to keep in step.

#include <string>
#include <vector>

#include "sim/dispatch.h"

namespace study {

struct DispatchRecord {
  sim::DispatchReport report;
  std::string frame;     // label of the frame (EQAA mode) it belongs to; "" when a run has one frame
  std::string pass;      // "" outside post passes
  std::string strategy;  // "" outside post passes
  std::string sweepPoint = {};  // "threshold=0.05" for a pass run at a point of a sweep axis
};

// Moves the reports the machine holds into `log`, labelled; the machine keeps none, so a long run
// holds each report once.
inline void TakeDispatches(sim::Machine& machine, std::vector<DispatchRecord>& log, const std::string& frame,
                           const std::string& pass = "", const std::string& strategy = "",
                           const std::string& sweepPoint = "") {
  for (sim::DispatchReport& report : machine.TakeReports()) {
    log.push_back({std::move(report), frame, pass, strategy, sweepPoint});
  }
}

}  // namespace study
