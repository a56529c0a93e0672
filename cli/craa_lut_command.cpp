// `aasim craa-lut` (see craa_lut_command.h).

#include "cli/craa_lut_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <CLI/CLI.hpp>

#include "cli/common_options.h"
#include "cli/output_dir.h"
#include "cli/output_error.h"
#include "cli/text_io.h"
#include "passes/craa/craa_lut.h"
#include "raster/sample_pattern.h"

namespace cli {
namespace {

namespace fs = std::filesystem;

// The file's folder as an OutputDir (created if missing), so the file is renamed into place
// only once it is written whole. A directory as --out is refused before any work.
OutputDir OpenOutFile(const fs::path& out) {
  std::error_code error;
  if (out.filename().empty() || fs::is_directory(out, error)) {
    throw OutputError("--out " + out.string() + ": is a directory; give a file name");
  }
  return OpenOutOption(out.parent_path().empty() ? fs::path(".") : out.parent_path());
}

std::string Fixed(double value, const char* format) {
  char text[32];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

}  // namespace

CLI::App* AddCraaLutCommand(CLI::App& app, CraaLutCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "craa-lut",
      "Generate the CRAA LUT for a sample pattern: per FMASK value of a 1F xS surface, the up/bottom/left/right "
      "neighbour weights fitted to the exact coverage of synthetic edge, corner, junction, sliver and triangle "
      "configurations; written as a JSON fixture (docs/craa.md \"CRAA LUT\")");
  AddPatternOption(*command, options.pattern);
  command->add_option("--samples", options.samples, "Coverage samples per pixel S")
      ->check(SampleCountCheck())
      ->capture_default_str();
  command->add_option("--out", options.out, "Output file (its folder is created if missing)")
      ->required()
      ->type_name("FILE");
  command
      ->add_option("--configurations", options.configurations,
                   "Synthetic configurations to fit over (more: fewer near-tie entries that change with the "
                   "random seed, longer run)")
      ->check(CLI::Range(std::int64_t{1}, passes::craa::kMaxLutConfigurations))
      ->capture_default_str();
  AddThreadsOption(*command, options.threads);
  return command;
}

void RunCraaLutCommand(const CraaLutCommandOptions& options, std::ostream& summary) {
  const raster::SamplePattern pattern = raster::ResolvePattern(options.pattern, options.samples);
  OutputDir dir = OpenOutFile(options.out);
  const fs::path name = fs::path(options.out).filename();

  passes::craa::LutGeneratorSettings settings =
      passes::craa::WithConfigurations(passes::craa::LutGeneratorSettings{}, options.configurations);
  settings.threads = options.threads;
  const auto start = std::chrono::steady_clock::now();
  const passes::craa::GeneratedCraaLut generated = passes::craa::GenerateCraaLutWithSummary(pattern, settings);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  WriteText(dir.Stage(name.string()), passes::craa::FormatCraaLut(generated.lut));
  const fs::path written = dir.Commit().front();
  const passes::craa::LutFitSummary& s = generated.summary;
  summary << "wrote the " << options.samples << "S CRAA LUT for pattern '" << pattern.Name() << "' to "
          << written.string() << "\n"
          << generated.lut.Tables() << " table(s) of " << generated.lut.EntriesPerTable() << " entries ("
          << generated.lut.Bytes() << " bytes): " << s.fitted << " fitted, " << s.fallbacks
          << " fallbacks; mean squared coverage error " << Fixed(s.meanError, "%.5f") << " (all-own "
          << Fixed(s.meanErrorAllOwn, "%.5f") << ") over " << s.evaluations << " configuration images; "
          << Fixed(seconds, "%.2f") << " s\n";
}

}  // namespace cli
