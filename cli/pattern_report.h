#pragma once
// The sample-pattern error table (raster/pattern_error.h) for the report and `aasim patterns
// error`: the seed's patterns, the standard and EQAA orders and the optimised patterns of
// docs/patterns/, each with its resolve footprint and the value seed 001 quotes, if any.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/report_html.h"
#include "raster/sample_pattern.h"

namespace cli {

struct PatternErrorRow {
  std::string name;
  int samples = 0;        // rendered per pixel
  std::string footprint;  // how the resolve reads and weights them
  double errorBox = 0.0;  // PatternError against the box reference
  double errorTent = 0.0;
  std::string seedValue;  // as seed 001 quotes it (">1.0", "0.698"), empty if it does not
};

PatternErrorRow PatternErrorRowOf(const raster::SamplePattern& pattern, std::string name, std::string seedValue = {});
// 1x centre, 2x2 uniform grid, 2x2 rotated grid, quincunx, FLIPQUAD, standard and eqaa 2/4/8/16,
// optimised 2/4/8/16.
std::vector<PatternErrorRow> PatternErrorRows();

// The optimised patterns shipped in docs/patterns/optimised-N.json (N = 2, 4, 8, 16), made by the
// command named there; tests/cli_patterns_test.cpp checks the files and these agree.
raster::SamplePattern OptimisedPattern(int samples);

ReportSection PatternErrorSection();
nlohmann::ordered_json PatternErrorJson();

}  // namespace cli
