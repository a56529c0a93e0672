// `aasim run --frames N`: the sequence part of the main job end to end on a small frame: every
// frame image of every technique and of the ground truth, report.json's sequence agreeing with
// them, and the report's sequence sections loading in headless Chromium (the sequence options'
// usage errors are CliRun.BadOptionListsAndCombinationsAreUsageErrors).

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "browser_check.h"
#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;

using cli::testing::CommandResult;
using cli::testing::ReadText;
using cli::testing::RunAasim;

constexpr int kFrames = 3;

std::vector<std::string> SequenceRun(const fs::path& out) {
  return {"run",      "--scene",    "builtin:wheel", "--width",   "96",       "--height",   "64",
          "--modes",  "1S/1Z/1F",   "--resolves",    "none",      "--post",   "copy,smaa,taa-ue4,smaa-4x", "--sequence-post", "all",  "--gt-samples",
          "4",        "--no-cache", "--progress",    "never",     "--frames", std::to_string(kFrames),
          "--camera-path", "orbit", "--out",         out.string()};
}

class CliSequenceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new fs::path(fs::temp_directory_path() / ("aasim_cli_sequence_" + std::to_string(::getpid())));
    fs::remove_all(*scratch_);
    fs::create_directories(*scratch_);
    run_ = new CommandResult(RunAasim(SequenceRun(*scratch_ / "out"), *scratch_));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*scratch_);
    delete scratch_;
    delete run_;
  }
  static fs::path Out() { return *scratch_ / "out"; }
  static fs::path* scratch_;
  static CommandResult* run_;
};
fs::path* CliSequenceTest::scratch_ = nullptr;
CommandResult* CliSequenceTest::run_ = nullptr;

TEST_F(CliSequenceTest, EveryTechniqueHasEveryFrameAndTheJsonAgrees) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  const nlohmann::json report = nlohmann::json::parse(ReadText(Out() / "report.json"));
  ASSERT_TRUE(report.contains("sequence"));
  const nlohmann::json& sequence = report["sequence"];
  EXPECT_EQ(sequence["frames"], kFrames);
  EXPECT_EQ(sequence["camera_path"], "orbit");
  EXPECT_EQ(report["configuration"]["frames"], kFrames);
  // smaa-4x reads a 2-sample surface: no 1S mode feeds it, but its schedule draws 2S/2Z/2F.
  ASSERT_EQ(sequence["groups"].size(), 3u);
  EXPECT_EQ(sequence["groups"][1]["schedule"], "halton8");
  EXPECT_EQ(sequence["groups"][2]["schedule"], "4x");
  EXPECT_EQ(sequence["groups"][2]["mode"], "2S/2Z/2F");
  ASSERT_EQ(sequence["groups"][1]["tracks"].size(), 2u);  // frames, taa-ue4
  const nlohmann::json& group = sequence["groups"][0];
  EXPECT_EQ(group["schedule"], "none");
  ASSERT_EQ(group["tracks"].size(), 3u);  // frames, copy, smaa
  // The temporal pass's study entry is its sequence's last frame.
  bool taa = false;
  for (const nlohmann::json& pass : report["passes"]) {
    if (pass["name"] == "taa-ue4") taa = pass["input_frame"] == "frame " + std::to_string(kFrames - 1) + " halton8 1S/1Z/1F";
  }
  EXPECT_TRUE(taa);
  // Seed 001's temporal timing rows: hraa and tfq did not run here, so no estimate.
  ASSERT_EQ(sequence["seed_001_timings"].size(), 4u);
  EXPECT_EQ(sequence["seed_001_timings"][1]["seed_ps4_1080p_ms"], 0.2);
  EXPECT_TRUE(sequence["seed_001_timings"][1]["estimated_1080p_ms"].is_null());
  for (int k = 0; k < kFrames; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%03d.png", k);
    EXPECT_TRUE(fs::is_regular_file(Out() / sequence["ground_truth"]["folder"].get<std::string>() / name));
    for (const nlohmann::json& track : group["tracks"]) {
      EXPECT_TRUE(fs::is_regular_file(Out() / track["folder"].get<std::string>() / name)) << track["folder"] << name;
    }
  }
  for (const nlohmann::json& track : group["tracks"]) {
    EXPECT_EQ(track["quality"].size(), static_cast<std::size_t>(kFrames));
    EXPECT_TRUE(track["flicker_codes"][0].is_null());
    EXPECT_TRUE(track["flicker_codes"][1].is_number());
    EXPECT_TRUE(track["strategies_identical"].get<bool>());
    for (const nlohmann::json& run : track["runs"]) EXPECT_EQ(run["frames"].size(), static_cast<std::size_t>(kFrames));
  }
}

TEST_F(CliSequenceTest, ReportShowsTheSequenceAndLoadsInHeadlessChromium) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  const std::string html = ReadText(Out() / "report.html");
  EXPECT_NE(html.find("Sequence: " + std::to_string(kFrames) + " frames"), std::string::npos);
  EXPECT_NE(html.find("data-group='sequence: smaa (none, 1S/1Z/1F)'"), std::string::npos);
  EXPECT_NE(html.find("<caption>Per-frame counters</caption>"), std::string::npos);
  const cli::testing::BrowserCheck check = cli::testing::CheckInChromium(Out() / "report.html");
  ASSERT_TRUE(check.ran) << check.error;
  EXPECT_TRUE(check.consoleErrors.empty()) << check.consoleErrors.front();
  EXPECT_TRUE(check.loadErrors.empty()) << check.loadErrors.front();
  EXPECT_EQ(check.imagesLoaded, check.imagesTotal);
}

}  // namespace
