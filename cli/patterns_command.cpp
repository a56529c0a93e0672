// `aasim patterns` (see patterns_command.h).

#include "cli/patterns_command.h"

#include <cstdio>
#include <filesystem>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/common_options.h"
#include "cli/number_format.h"
#include "cli/output_dir.h"
#include "cli/pattern_report.h"
#include "cli/text_io.h"
#include "raster/pattern_error.h"
#include "raster/sample_pattern.h"

namespace cli {
namespace {

raster::ReferenceFilter ParseReference(const std::string& name) {
  return name == "tent" ? raster::ReferenceFilter::kTent : raster::ReferenceFilter::kBox;
}

std::string Padded(std::string text, std::size_t width) {
  if (text.size() < width) text.append(width - text.size(), ' ');
  return text;
}

void PrintTable(const std::vector<PatternErrorRow>& rows, std::ostream& out) {
  constexpr std::size_t kName = 26, kSamples = 9, kError = 8, kSeed = 9;
  out << Padded("pattern", kName) << Padded("samples", kSamples) << Padded("E box", kError)
      << Padded("E tent", kError) << Padded("seed 001", kSeed) << "resolve footprint\n";
  for (const PatternErrorRow& row : rows) {
    out << Padded(row.name, kName) << Padded(std::to_string(row.samples), kSamples)
        << Padded(FormatFixed(row.errorBox, 4), kError) << Padded(FormatFixed(row.errorTent, 4), kError)
        << Padded(row.seedValue.empty() ? "-" : row.seedValue, kSeed) << row.footprint << "\n";
  }
}

void RunError(const PatternsCommandOptions& options, std::ostream& out) {
  if (options.pattern.empty()) {
    PrintTable(PatternErrorRows(), out);
    return;
  }
  const raster::SamplePattern pattern = raster::ResolvePattern(options.pattern, options.patternSamples);
  PrintTable({PatternErrorRowOf(pattern, pattern.Name())}, out);
}

void RunOptimise(const PatternsCommandOptions& options, std::ostream& out) {
  const raster::SamplePattern start = raster::ResolvePattern(options.start, options.samples);
  const std::filesystem::path file(options.out);
  OutputDir dir = OpenOutOption(file.has_parent_path() ? file.parent_path() : std::filesystem::path("."));
  const raster::OptimiserOptions optimiser{options.seed, options.iterations, options.perQuadPixel,
                                           ParseReference(options.reference)};
  const raster::OptimiserResult result = raster::OptimisePattern(start, optimiser, file.stem().string());
  WriteText(dir.Stage(file.filename().string()), raster::FormatPatternJson(result.pattern) + "\n");
  const std::vector<std::filesystem::path> written = dir.Commit();
  out << result.pattern.Name() << ": " << options.samples << " samples, error (" << options.reference
      << " reference, box resolve) " << FormatFixed(result.startError, 4) << " (" << start.Name() << ") -> "
      << FormatFixed(result.error, 4) << " after " << result.evaluations << " evaluations; wrote "
      << written.front().string() << "\n";
}

}  // namespace

CLI::App* AddPatternsCommand(CLI::App& app, PatternsCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "patterns",
      "Sample-pattern error: a weighted coverage error of straight edges over all orientations and offsets "
      "(docs/sample-patterns.md \"Pattern error\"), and a search for patterns that minimise it");
  command->require_subcommand(1);
  const std::vector<std::string> references = {"box", "tent"};

  CLI::App* error = command->add_subcommand(
      "error",
      "Print the error table: E against the box reference (the pixel's area coverage) and the tent reference "
      "(the pixel with a 0.5-px-radius blur), with the values seed 001 quotes. Without --pattern: 1x centre, "
      "2x2 uniform and rotated grids, quincunx, FLIPQUAD, standard and eqaa 2/4/8/16, optimised 2/4/8/16");
  CLI::Option* pattern = error->add_option("--pattern", options.pattern,
                                           "One pattern instead of the table: a built-in (" +
                                               JoinNames(raster::BuiltinPatternNames()) + ") or a JSON file");
  pattern->type_name("NAME|FILE");
  CLI::Option* patternSamples =
      error->add_option("--samples", options.patternSamples, "Samples of --pattern")->check(SampleCountCheck());
  pattern->needs(patternSamples);
  patternSamples->needs(pattern);

  CLI::App* optimise = command->add_subcommand(
      "optimise",
      "Search positions on the 1/16-px grid that minimise E of the box resolve (threshold accepting, then "
      "per-sample exhaustive polishing; deterministic for a seed), print the error before and after, and write "
      "the pattern as JSON for --pattern");
  optimise->add_option("--samples", options.samples, "Samples per pixel")->required()->check(SampleCountCheck());
  optimise->add_option("--out", options.out, "Pattern JSON file to write (its name without .json names the pattern)")
      ->required()
      ->type_name("FILE");
  optimise->add_option("--seed", options.seed, "Search seed")->capture_default_str();
  optimise->add_option("--start", options.start, "Start pattern: built-in or JSON file; the result is never worse")
      ->type_name("NAME|FILE")
      ->capture_default_str();
  optimise->add_flag("--per-quad-pixel", options.perQuadPixel,
                     "Search each pixel of the 2x2 quad separately (with the box resolve the pixels do not "
                     "interact, so this only helps a search that got stuck)");
  optimise->add_option("--iterations", options.iterations, "Proposals per searched pixel before polishing")
      ->check(CLI::Range(0, 10'000'000))
      ->capture_default_str();
  optimise->add_option("--reference", options.reference, "Reference filter of E")
      ->check(CLI::IsMember(references))
      ->capture_default_str();
  return command;
}

void RunPatternsCommand(const CLI::App& command, const PatternsCommandOptions& options, std::ostream& out) {
  if (command.got_subcommand("error")) {
    RunError(options, out);
  } else {
    RunOptimise(options, out);
  }
}

}  // namespace cli
