#pragma once
// `aasim fixtures`: writes the canonical FMASK fixture set (fmask/fixtures.h) with a manifest,
// or re-derives a written set and fails on the first difference (format: docs/fixtures.md).

#include <ostream>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "cli/cli11_fwd.h"

namespace cli {

struct FixturesCommandOptions {
  std::string out;     // write the set here
  std::string verify;  // or verify the set here (exactly one of the two)
};

// Registers the `fixtures` subcommand on `app`, bound to `options`.
CLI::App* AddFixturesCommand(CLI::App& app, FixturesCommandOptions& options);

// Writing is all-or-nothing (OutputDir). Verification throws a one-line error naming the
// fixture and file at the first mismatch, a missing file or a corrupt manifest.
void RunFixturesCommand(const FixturesCommandOptions& options, std::ostream& summary);

}  // namespace cli
