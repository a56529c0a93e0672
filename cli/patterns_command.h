#pragma once
// `aasim patterns error` prints the sample-pattern error table (raster/pattern_error.h,
// cli/pattern_report.h); `aasim patterns optimise` searches sample positions that minimise it and
// writes them as a pattern JSON file that --pattern accepts (docs/sample-patterns.md).

#include <cstdint>
#include <ostream>
#include <string>

#include "cli/cli11_fwd.h"
#include "raster/pattern_optimiser.h"

namespace cli {

struct PatternsCommandOptions {
  // error
  std::string pattern;  // empty: the whole table
  int patternSamples = 0;
  // optimise
  int samples = 0;
  std::string out;
  std::uint64_t seed = 1;
  std::string start = "standard";
  bool perQuadPixel = false;
  int iterations = raster::kDefaultOptimiserIterations;
  std::string reference = "box";
};

CLI::App* AddPatternsCommand(CLI::App& app, PatternsCommandOptions& options);

// Runs whichever of `error` and `optimise` `command` parsed; the file is written atomically.
void RunPatternsCommand(const CLI::App& command, const PatternsCommandOptions& options, std::ostream& out);

}  // namespace cli
