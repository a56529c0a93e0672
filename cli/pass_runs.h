#pragma once
// A post pass run once per dispatch strategy on one frame, as `aasim frame --post` and
// `aasim post` do it: a fresh instance per strategy, every dispatch labelled with the pass and
// strategy, every later output compared with the first by the strategy-identity rule
// (passes/compare.h), and the comparison printed side by side.

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <span>
#include <vector>

#include "passes/compare.h"
#include "passes/registry.h"
#include "study/dispatch_log.h"

namespace cli {

struct PassRun {
  passes::Strategy strategy;
  passes::PassOutput output;
  std::size_t firstDispatch = 0, endDispatch = 0;  // [first, end) in the dispatch records
};

struct PassRuns {
  std::vector<PassRun> runs;  // in the order of the strategies given
  // The first difference of a later strategy's output from the first's.
  passes::StrategyDifference difference;
};

// Runs `pass` under each of `strategies` in order, moving the machine's reports into `records`.
PassRuns RunUnderStrategies(sim::Machine& machine, const passes::PassConfig& pass, const passes::FrameInputs& frame,
                            std::span<const passes::Strategy> strategies, std::vector<study::DispatchRecord>& records);

// The estimated µs of every dispatch of one run.
double EstimatedMicroseconds(std::span<const study::DispatchRecord> records, const PassRun& run);

// The studied dispatch of the first two runs side by side, then whether the outputs are identical.
void PrintStrategyComparison(std::ostream& out, std::span<const study::DispatchRecord> records,
                             const passes::PassInfo& info, const PassRuns& runs);

// When the runs' outputs differ (a bug in the pass: the strategies run the same arithmetic in the
// same order), std::runtime_error naming the difference, the pass's source and `outputs`, where
// the outputs were kept for inspection.
void ThrowIfStrategiesDiffer(const PassRuns& runs, const passes::PassInfo& info, const std::filesystem::path& outputs);

}  // namespace cli
