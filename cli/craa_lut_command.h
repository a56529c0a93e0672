#pragma once
// `aasim craa-lut --pattern P --samples S --out FILE`: generates the CRAA LUT for a sample
// pattern (passes/craa/craa_lut.h) and writes it as a JSON fixture (docs/craa.md "CRAA LUT").

#include <cstdint>
#include <ostream>
#include <string>

#include "cli/cli11_fwd.h"

namespace cli {

struct CraaLutCommandOptions {
  std::string pattern = "eqaa";  // the pattern `aasim frame` renders EQAA surfaces with
  int samples = 8;
  std::string out;
  std::int64_t configurations = 960000;  // passes::craa::LutGeneratorSettings' default total
  int threads = 0;  // set to every core by AddThreadsOption
};

CLI::App* AddCraaLutCommand(CLI::App& app, CraaLutCommandOptions& options);

// Writes the file all-or-nothing and prints where, then a one-line summary.
void RunCraaLutCommand(const CraaLutCommandOptions& options, std::ostream& summary);

}  // namespace cli
