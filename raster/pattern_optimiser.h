#pragma once
// A search for sample positions on the 1/16-px grid that minimise the pattern error
// (raster/pattern_error.h) of the box resolve: threshold accepting from a start pattern, then
// exhaustive per-sample polishing (docs/sample-patterns.md "Pattern optimiser"). Deterministic
// for a seed: its own std::mt19937_64, whose output the standard fixes, mapped to integers here.

#include <cstdint>
#include <string>

#include "raster/pattern_error.h"
#include "raster/sample_pattern.h"

namespace raster {

inline constexpr int kDefaultOptimiserIterations = 20000;

struct OptimiserOptions {
  std::uint64_t seed = 1;
  int iterations = kDefaultOptimiserIterations;  // proposals per searched set of positions, >= 0
  bool perQuadPixel = false;                     // search each quad pixel's positions separately
  ReferenceFilter reference = ReferenceFilter::kBox;
};

struct OptimiserResult {
  SamplePattern pattern;
  double startError = 0.0;  // OptimiserError of the start pattern
  double error = 0.0;       // OptimiserError of `pattern`, never above startError
  std::int64_t evaluations = 0;
};

// The objective: PatternError of the pattern's box footprints (every pattern, quincunx and
// FLIPQUAD included, is scored as its own samples with equal weights).
double OptimiserError(const SamplePattern& pattern, ReferenceFilter reference);

// Starts from `start` (its sample count is the one searched) and names the result `name`.
// Without perQuadPixel the result has the same offsets in every quad pixel, starting from the
// start's best quad pixel. Throws std::invalid_argument for negative iterations.
OptimiserResult OptimisePattern(const SamplePattern& start, const OptimiserOptions& options, std::string name);

}  // namespace raster
