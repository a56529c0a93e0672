// `aasim patterns` end to end: the error table, an optimised pattern written as JSON that
// `aasim raster --pattern FILE` renders with, the same file for the same seed, one-line errors
// that leave nothing behind; and the report's pattern table with the shipped optimised patterns.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/pattern_report.h"
#include "cli_test_util.h"
#include "raster/pattern_error.h"
#include "raster/pattern_optimiser.h"
#include "raster/sample_pattern.h"

namespace {

namespace fs = std::filesystem;
using cli::testing::CommandResult;
using cli::testing::ReadText;
using cli::testing::RunAasim;

class CliPatterns : public cli::testing::ScratchDirTest {};

TEST_F(CliPatterns, ErrorPrintsTheWholeTable) {
  const CommandResult run = RunAasim({"patterns", "error"}, scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(run.out.rfind("pattern ", 0), 0u) << run.out;
  for (const cli::PatternErrorRow& row : cli::PatternErrorRows()) {
    EXPECT_NE(run.out.find("\n" + row.name + " "), std::string::npos) << row.name;
  }
  EXPECT_NE(run.out.find("0.364"), std::string::npos);  // FLIPQUAD's seed value
}

TEST_F(CliPatterns, ErrorOfOnePattern) {
  const CommandResult run = RunAasim({"patterns", "error", "--pattern", "eqaa", "--samples", "16"}, scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const cli::PatternErrorRow row = cli::PatternErrorRowOf(raster::MakeBuiltinPattern("eqaa", 16), "eqaa");
  EXPECT_NE(run.out.find("\neqaa "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(row.footprint), std::string::npos) << run.out;
  EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 2) << run.out;  // header and the row
}

TEST_F(CliPatterns, OptimisedFileRendersWithRasterAndRepeatsForTheSeed) {
  const fs::path file = scratch_ / "mine.json", again = scratch_ / "again" / "mine.json";
  const std::vector<std::string> args = {"patterns", "optimise", "--samples", "4", "--seed", "9", "--iterations", "150"};
  std::vector<std::string> first = args, second = args;
  first.insert(first.end(), {"--out", file.string()});
  second.insert(second.end(), {"--out", again.string()});
  const CommandResult run = RunAasim(first, scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.out.rfind("mine: 4 samples, error (box reference, box resolve) 0.3533 (standard) -> ", 0), 0u)
      << run.out;
  const raster::SamplePattern pattern = raster::LoadPatternJson(file, 4);
  EXPECT_EQ(pattern.Name(), "mine");
  EXPECT_LT(raster::OptimiserError(pattern, raster::ReferenceFilter::kBox),
            raster::OptimiserError(raster::MakeBuiltinPattern("standard", 4), raster::ReferenceFilter::kBox));
  ASSERT_EQ(RunAasim(second, scratch_).exitCode, 0);
  EXPECT_EQ(ReadText(file), ReadText(again));

  const CommandResult raster = RunAasim({"raster", "--pattern", file.string(), "--samples", "4", "--width", "16",
                                         "--height", "16", "--out", (scratch_ / "raster").string()},
                                        scratch_);
  ASSERT_EQ(raster.exitCode, 0) << raster.err;
  EXPECT_TRUE(fs::is_regular_file(scratch_ / "raster" / "counters.json"));
}

TEST_F(CliPatterns, ErrorsAreOneLineAndWriteNothing) {
  const fs::path blocker = cli::testing::WriteFile(scratch_ / "file", "x");
  struct Case {
    std::vector<std::string> args;
    int exitCode;
    std::string mentions;
  };
  const std::vector<Case> cases = {
      {{"patterns", "optimise", "--samples", "3", "--out", (scratch_ / "a.json").string()}, 2, "--samples"},
      {{"patterns", "optimise", "--samples", "4"}, 2, "--out"},
      {{"patterns", "optimise", "--samples", "4", "--out", (blocker / "a.json").string()}, 1, "--out"},
      {{"patterns", "optimise", "--samples", "4", "--start", "nope.json", "--out", (scratch_ / "a.json").string()},
       1,
       "nope.json"},
      {{"patterns", "optimise", "--samples", "4", "--reference", "gauss", "--out", (scratch_ / "a.json").string()},
       2,
       "--reference"},
      {{"patterns", "error", "--pattern", "standard"}, 2, "--samples"},
      {{"patterns"}, 2, "subcommand"},
  };
  for (const Case& c : cases) {
    const CommandResult run = RunAasim(c.args, scratch_);
    EXPECT_EQ(run.exitCode, c.exitCode) << c.mentions << ": " << run.err;
    EXPECT_NE(run.err.find(c.mentions), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(scratch_ / "a.json")) << c.mentions;
  }
}

TEST_F(CliPatterns, HelpExplainsBothSubcommands) {
  const CommandResult run = RunAasim({"patterns", "--help"}, scratch_);
  ASSERT_EQ(run.exitCode, 0);
  EXPECT_NE(run.out.find("error"), std::string::npos);
  EXPECT_NE(run.out.find("optimise"), std::string::npos);
  const CommandResult optimise = RunAasim({"patterns", "optimise", "--help"}, scratch_);
  for (const char* option : {"--samples", "--out", "--seed", "--start", "--per-quad-pixel", "--iterations"}) {
    EXPECT_NE(optimise.out.find(option), std::string::npos) << option;
  }
}

// docs/patterns/optimised-N.json are what the report shows, and the optimiser's defaults still
// make the small ones (the large ones take seconds; docs/sample-patterns.md has the command).
TEST(PatternReport, ShippedOptimisedPatternsMatchTheReportAndTheOptimiser) {
  for (const int samples : {2, 4, 8, 16}) {
    const std::string name = "optimised-" + std::to_string(samples);
    const raster::SamplePattern shipped =
        raster::LoadPatternJson(fs::path(AASIM_SOURCE_DIR) / "docs" / "patterns" / (name + ".json"), samples);
    EXPECT_EQ(shipped, cli::OptimisedPattern(samples)) << samples;
    EXPECT_LT(raster::PatternError(shipped, raster::ReferenceFilter::kBox),
              raster::PatternError(raster::MakeBuiltinPattern("standard", samples), raster::ReferenceFilter::kBox));
  }
  for (const int samples : {2, 4}) {
    const raster::OptimiserResult result =
        raster::OptimisePattern(raster::MakeBuiltinPattern("standard", samples), raster::OptimiserOptions{},
                                "optimised-" + std::to_string(samples));
    EXPECT_EQ(result.pattern, cli::OptimisedPattern(samples)) << samples;
  }
}

TEST(PatternReport, TableSectionAndJsonAgree) {
  const std::vector<cli::PatternErrorRow> rows = cli::PatternErrorRows();
  ASSERT_EQ(rows.size(), 17u);
  EXPECT_EQ(rows[0].name, "1x centre");
  EXPECT_EQ(rows[3].footprint, "5 (2 own, rest shared): 1/2 x1, 1/8 x4");
  EXPECT_EQ(rows[4].footprint, "4 (2 own, rest shared): 1/4 x4");
  EXPECT_EQ(rows[1].footprint, "4 own, 1/4 each");
  const cli::ReportSection section = cli::PatternErrorSection();
  ASSERT_EQ(section.charts.size(), 1u);
  EXPECT_EQ(section.charts[0].categories.size(), rows.size());
  ASSERT_EQ(section.tables.size(), 1u);
  EXPECT_EQ(section.tables[0].rows.size(), rows.size());
  const nlohmann::ordered_json json = cli::PatternErrorJson();
  ASSERT_EQ(json["patterns"].size(), rows.size());
  EXPECT_EQ(json["patterns"][4]["pattern"], "FLIPQUAD");
  EXPECT_EQ(json["patterns"][4]["seed"], "0.364");
  EXPECT_TRUE(json["patterns"][5]["seed"].is_null());
  EXPECT_EQ(json["patterns"][4]["error_tent"].get<double>(), rows[4].errorTent);
}

}  // namespace
