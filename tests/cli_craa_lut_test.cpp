// `aasim craa-lut` end to end: the real binary writes the table the library generates, as a
// fixture the reader accepts; usage errors exit 2, unwritable or unknown inputs exit 1 with one
// line, and a failed run leaves neither a partial file nor a changed old one.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_test_util.h"
#include "passes/craa/craa_lut.h"
#include "raster/sample_pattern.h"

namespace {

namespace fs = std::filesystem;
using cli::testing::CommandResult;

constexpr const char* kConfigurations = "20000";  // keeps a run well under a second

class CliCraaLut : public cli::testing::ScratchDirTest {
 protected:
  CommandResult Run(const std::vector<std::string>& args) const { return cli::testing::RunAasim(args, scratch_); }
};

TEST_F(CliCraaLut, WritesTheGeneratedTableAndASummary) {
  const fs::path out = scratch_ / "luts" / "standard4.json";
  const CommandResult run = Run({"craa-lut", "--pattern", "standard", "--samples", "4", "--configurations",
                                 kConfigurations, "--threads", "2", "--out", out.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(run.out.rfind("wrote the 4S CRAA LUT for pattern 'standard' to " + out.string() + "\n", 0), 0u)
      << run.out;
  EXPECT_NE(run.out.find("1 table(s) of 16 entries (32 bytes): "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(" fallbacks; mean squared coverage error "), std::string::npos) << run.out;
  EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 2) << run.out;

  const passes::craa::CraaLut written = passes::craa::ParseCraaLut(cli::testing::ReadText(out), out.string());
  const passes::craa::CraaLut expected = passes::craa::GenerateCraaLut(
      raster::MakeBuiltinPattern("standard", 4), passes::craa::WithConfigurations({}, 20000));
  EXPECT_EQ(written, expected);
  EXPECT_EQ(cli::testing::FilesIn(out.parent_path()), (std::vector<std::string>{"standard4.json"}));
}

TEST_F(CliCraaLut, ReadsAPatternFile) {
  const fs::path pattern = cli::testing::WriteFile(
      scratch_ / "p.json", R"({"name": "diagonal", "samples": 2, "offsets": [[-3, -3], [3, 3]]})");
  const fs::path out = scratch_ / "lut.json";
  const CommandResult run = Run({"craa-lut", "--pattern", pattern.string(), "--samples", "2", "--configurations",
                                 kConfigurations, "--out", out.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(passes::craa::ParseCraaLut(cli::testing::ReadText(out), "lut.json").PatternName(), "diagonal");
}

TEST_F(CliCraaLut, HelpNamesTheCommandAndTheDocument) {
  const CommandResult top = Run({"--help"});
  EXPECT_EQ(top.exitCode, 0);
  EXPECT_NE(top.out.find("craa-lut"), std::string::npos);
  const CommandResult help = Run({"craa-lut", "--help"});
  EXPECT_EQ(help.exitCode, 0);
  for (const char* text : {"docs/craa.md", "--pattern", "--samples", "--out", "--configurations", "--threads"}) {
    EXPECT_NE(help.out.find(text), std::string::npos) << text;
  }
}

TEST_F(CliCraaLut, BadArgumentsAreUsageErrors) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"craa-lut"}, {"craa-lut", "--out", "x.json", "--samples", "3"},
        {"craa-lut", "--out", "x.json", "--configurations", "0"}}) {
    const CommandResult run = Run(args);
    EXPECT_EQ(run.exitCode, 2) << args.size();
    EXPECT_EQ(run.err.rfind("aasim craa-lut: ", 0), 0u) << run.err;
  }
}

TEST_F(CliCraaLut, RuntimeErrorsAreOneLineAndLeaveNothing) {
  cli::testing::WriteFile(scratch_ / "file", "not a directory");
  fs::create_directory(scratch_ / "dir");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--out", (scratch_ / "file" / "lut.json").string()}, "aasim: --out "},
      {{"--out", (scratch_ / "dir").string()}, "aasim: --out "},
      {{"--pattern", "nonesuch", "--out", (scratch_ / "lut.json").string()}, "aasim: "},
      {{"--pattern", "quincunx", "--samples", "8", "--out", (scratch_ / "lut.json").string()}, "aasim: "},
  };
  for (const auto& [extra, prefix] : cases) {
    std::vector<std::string> args = {"craa-lut", "--configurations", kConfigurations};
    args.insert(args.end(), extra.begin(), extra.end());
    const CommandResult run = Run(args);
    EXPECT_EQ(run.exitCode, 1) << extra.back();
    EXPECT_EQ(run.err.rfind(prefix, 0), 0u) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_EQ(cli::testing::FilesIn(scratch_), (std::vector<std::string>{"dir", "file", "stderr.txt", "stdout.txt"}));
    EXPECT_TRUE(fs::is_empty(scratch_ / "dir"));
  }
}

TEST_F(CliCraaLut, FailedRunKeepsTheOldFile) {
  const fs::path out = scratch_ / "lut.json";
  cli::testing::WriteFile(out, "old");
  const CommandResult run = Run({"craa-lut", "--pattern", "nonesuch", "--out", out.string()});
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(cli::testing::ReadText(out), "old");
  const CommandResult again = Run({"craa-lut", "--samples", "2", "--configurations", kConfigurations, "--out", out.string()});
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_NE(cli::testing::ReadText(out), "old");
}

}  // namespace
