#pragma once
// `aasim passes [NAME...]`: the pass registry as a user reads it: each pass's description, the
// strategies it runs under, the dispatches the study compares, its inputs, settings (default,
// range, meaning) and presets, the syntax --post accepts.

#include <ostream>
#include <string>
#include <vector>

#include "cli/cli11_fwd.h"

namespace cli {

struct PassesCommandOptions {
  std::vector<std::string> names;  // empty = every registered pass
};

CLI::App* AddPassesCommand(CLI::App& app, PassesCommandOptions& options);
// Throws CLI::ValidationError for an unknown name.
void ResolvePassesOptions(const PassesCommandOptions& options);
void RunPassesCommand(const PassesCommandOptions& options, std::ostream& out);
// What `aasim passes` prints for every registered pass, for other commands' --help.
std::string DescribeAllPasses();

}  // namespace cli
