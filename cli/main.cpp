// The `aasim` command line: parses the subcommand, maps errors to one stderr line and an exit
// code (0 success or help, 1 runtime input/output error, 2 invalid arguments), then runs it.

#include <exception>
#include <iostream>
#include <new>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/common_options.h"
#include "cli/craa_lut_command.h"
#include "cli/fixtures_command.h"
#include "cli/frame_command.h"
#include "cli/frame_options.h"
#include "cli/output_dir.h"
#include "cli/passes_command.h"
#include "cli/patterns_command.h"
#include "cli/post_command.h"
#include "cli/post_options.h"
#include "cli/raster_command.h"
#include "cli/raster_options.h"
#include "cli/run_command.h"
#include "cli/run_options.h"
#include "cli/smaa_tables_command.h"
#include "raster/raster_error.h"
#include "sim/host_memory.h"

namespace {

constexpr int kExitRuntimeError = 1;
constexpr int kExitUsageError = 2;

// Library messages are meant to be one line; a stray newline must not break that contract.
std::string OneLine(std::string message) {
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return message;
}

int ReportUsageError(const std::string& command, const CLI::ParseError& error) {
  std::cerr << command << ": " << OneLine(error.what()) << '\n';
  return kExitUsageError;
}

// A summary lost to a full disk is an error like any other output's; buffered write errors only
// surface at the flush. A run that already failed keeps its own one-line message.
int CheckStdout(int exitCode) {
  if (std::cout.flush() || exitCode != 0) return exitCode;
  std::cerr << "aasim: standard output: write error\n";
  return kExitRuntimeError;
}

// The rasterizer refuses an overdraw too deep for its quad stream without knowing the scene; the
// command line adds the scene the user named, as the scene loader's messages start with it.
template <typename Command>
void NamingTheScene(const std::string& scene, Command command) {
  try {
    command();
  } catch (const raster::QuadStreamError& error) {
    throw raster::QuadStreamError(scene + ": " + error.what());
  }
}

int RunAasim(int argc, char** argv) {
  CLI::App app{
      "aasim: a software model of GCN-class GPU coverage hardware (rasterizer, EQAA "
      "surfaces, anti-aliasing passes)",
      "aasim"};
  app.require_subcommand(0, 1);
  cli::RasterCommandOptions rasterOptions;
  CLI::App* raster = cli::AddRasterCommand(app, rasterOptions);
  cli::FixturesCommandOptions fixturesOptions;
  CLI::App* fixtures = cli::AddFixturesCommand(app, fixturesOptions);
  cli::FrameCommandOptions frameOptions;
  CLI::App* frame = cli::AddFrameCommand(app, frameOptions);
  cli::RunCommandOptions runOptions;
  CLI::App* run = cli::AddRunCommand(app, runOptions);
  cli::PassesCommandOptions passesOptions;
  CLI::App* passes = cli::AddPassesCommand(app, passesOptions);
  cli::PostCommandOptions postOptions;
  CLI::App* post = cli::AddPostCommand(app, postOptions);
  cli::SmaaTablesCommandOptions smaaTablesOptions;
  CLI::App* smaaTables = cli::AddSmaaTablesCommand(app, smaaTablesOptions);
  cli::PatternsCommandOptions patternsOptions;
  CLI::App* patterns = cli::AddPatternsCommand(app, patternsOptions);
  cli::CraaLutCommandOptions craaLutOptions;
  CLI::App* craaLut = cli::AddCraaLutCommand(app, craaLutOptions);
  cli::RequireDecimalIntegers(app);
  app.footer("Without a subcommand, aasim runs `aasim run` with its defaults: the main job on the built-in "
             "default scene, report in out/report/report.html.");

  try {
    app.parse(argc, argv);
    if (raster->parsed()) cli::ResolveRasterOptions(rasterOptions);
    if (frame->parsed()) cli::ResolveFrameOptions(frameOptions);
    if (passes->parsed()) cli::ResolvePassesOptions(passesOptions);
    if (post->parsed()) cli::ResolvePostOptions(postOptions);
    // `aasim` alone is the main job with its defaults.
    if (!raster->parsed() && !fixtures->parsed() && !frame->parsed() && !passes->parsed() && !post->parsed() &&
        !smaaTables->parsed() && !patterns->parsed() && !craaLut->parsed()) {
      cli::ResolveRunOptions(*run, runOptions);
    }
  } catch (const CLI::Success& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    const char* command = raster->parsed()       ? "aasim raster"
                          : fixtures->parsed()   ? "aasim fixtures"
                          : frame->parsed()      ? "aasim frame"
                          : run->parsed()        ? "aasim run"
                          : passes->parsed()     ? "aasim passes"
                          : post->parsed()       ? "aasim post"
                          : smaaTables->parsed() ? "aasim smaa-tables"
                          : patterns->parsed()   ? "aasim patterns"
                          : craaLut->parsed()    ? "aasim craa-lut"
                                                 : "aasim";
    return ReportUsageError(command, error);
  }

  try {
    if (raster->parsed()) {
      NamingTheScene(rasterOptions.scene, [&] { cli::RunRasterCommand(rasterOptions, std::cout); });
    } else if (frame->parsed()) {
      NamingTheScene(frameOptions.scene, [&] { cli::RunFrameCommand(frameOptions, std::cout); });
    } else if (fixtures->parsed()) {
      cli::RunFixturesCommand(fixturesOptions, std::cout);
    } else if (passes->parsed()) {
      cli::RunPassesCommand(passesOptions, std::cout);
    } else if (post->parsed()) {
      cli::RunPostCommand(postOptions, std::cout);
    } else if (smaaTables->parsed()) {
      cli::RunSmaaTablesCommand(smaaTablesOptions, std::cout);
    } else if (patterns->parsed()) {
      cli::RunPatternsCommand(*patterns, patternsOptions, std::cout);
    } else if (craaLut->parsed()) {
      cli::RunCraaLutCommand(craaLutOptions, std::cout);
    } else {
      NamingTheScene(runOptions.scene, [&] { cli::RunRunCommand(runOptions, std::cout, std::cerr); });
    }
  } catch (const std::bad_alloc&) {
    std::cerr << "aasim: out of memory\n";
    return kExitRuntimeError;
  } catch (const std::exception& error) {
    std::cerr << "aasim: " << OneLine(error.what()) << '\n';
    return kExitRuntimeError;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sim::KeepFreedHostMemory();  // frame-sized buffers reused, not re-faulted (sim/host_memory.h)
  cli::OutputDir::RemoveTemporariesOnSignals();
  return CheckStdout(RunAasim(argc, argv));
}
