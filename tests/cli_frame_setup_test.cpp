// The CRAA setup options (--draw-order, --depth-prepass, --max-zplanes) on `aasim frame` and
// `aasim run`: they reach the frame (the pre-pass dispatch, the summary), are recorded in the
// configuration, keep the run's draw_dispatch on the material draw, and bad values are refused
// before any output exists.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;

using cli::testing::BadInput;
using cli::testing::CommandResult;
using cli::testing::ExpectRefused;
using cli::testing::ReadText;
using cli::testing::RunAasim;

const std::vector<std::string> kSetup = {"--draw-order", "front-to-back", "--depth-prepass", "--max-zplanes", "0"};

class CliFrameSetup : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch_ = fs::temp_directory_path() / ("aasim_cli_frame_setup_" + std::to_string(::getpid()));
    fs::remove_all(scratch_);
    fs::create_directories(scratch_);
  }
  void TearDown() override { fs::remove_all(scratch_); }
  fs::path scratch_;
};

TEST_F(CliFrameSetup, FrameDrawsThePrepassAndRecordsTheSettings) {
  std::vector<std::string> args = {"frame", "--scene", "builtin:pixel-crossing", "--width", "96", "--height", "64",
                                   "--fragments", "1", "--post", "none", "--out", (scratch_ / "out").string()};
  args.insert(args.end(), kSetup.begin(), kSetup.end());
  const CommandResult run = RunAasim(args, scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("policy hraa, draw order front-to-back, depth pre-pass, max Z planes 0, GPU"),
            std::string::npos)
      << run.out;
  const nlohmann::json json = nlohmann::json::parse(ReadText(scratch_ / "out/dispatches.json"));
  EXPECT_EQ(json["configuration"]["draw_order"], "front-to-back");
  EXPECT_EQ(json["configuration"]["depth_prepass"], true);
  EXPECT_EQ(json["configuration"]["max_zplanes"], 0);
  ASSERT_EQ(json["dispatches"].size(), 3u);  // the pre-pass, the material draw, the box resolve
  EXPECT_EQ(json["dispatches"][2]["name"], "frame/resolve");
  const nlohmann::json& prepass = json["dispatches"][0];
  EXPECT_EQ(prepass["name"], "frame/depth-prepass");
  EXPECT_EQ(prepass["counters"]["lanes/launched"], 0);
  EXPECT_FALSE(prepass.contains("fragments")) << "no colour block";
  EXPECT_GT(prepass["raster"]["samples/depth_passed"].get<long>(), 0);
  EXPECT_EQ(json["dispatches"][1]["name"], "frame/material");
  EXPECT_EQ(json["dispatches"][1]["raster"]["zplanes/tiles_compressed"], 0) << "--max-zplanes 0";
}

TEST_F(CliFrameSetup, RunCarriesTheSettingsIntoEveryFrame) {
  std::vector<std::string> args = {"run",          "--quick",    "--width",  "96",
                                   "--height",     "64",         "--gt-samples", "4", "--lut-configurations", "20000",
                                   "--modes",      "8S/4Z/1F,8S/8Z/1F", "--post",   "none",
                                   "--cache",      (scratch_ / "cache").string(), "--progress", "never",
                                   "--out",        (scratch_ / "out").string()};
  args.insert(args.end(), kSetup.begin(), kSetup.end());
  const CommandResult run = RunAasim(args, scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(ReadText(scratch_ / "out/report.json"));
  EXPECT_EQ(report["configuration"]["draw_order"], "front-to-back");
  EXPECT_EQ(report["configuration"]["depth_prepass"], true);
  EXPECT_EQ(report["configuration"]["max_zplanes"], 0);
  const nlohmann::json& dispatches = report["dispatches"]["dispatches"];
  std::size_t resolves = 0;
  for (const nlohmann::json& frame : report["frames"]) resolves += frame["resolves"].size();
  ASSERT_EQ(dispatches.size(), 6u + resolves) << "a pre-pass, a material draw and the box resolve per mode";
  ASSERT_EQ(report["frames"].size(), 2u);
  for (const nlohmann::json& frame : report["frames"]) {
    const std::size_t draw = frame["draw_dispatch"].get<std::size_t>();
    ASSERT_GE(draw, 1u);
    EXPECT_EQ(dispatches[draw]["name"], "frame/material");
    EXPECT_EQ(dispatches[draw - 1]["name"], "frame/depth-prepass");
    EXPECT_EQ(dispatches[draw]["frame"], frame["mode"]);
  }
}

TEST_F(CliFrameSetup, BadSettingsAreRefusedBeforeAnyOutput) {
  const std::vector<BadInput> inputs = {
      {"UnknownOrder", [](const fs::path&) { return std::vector<std::string>{"--draw-order", "sideways"}; },
       "--draw-order", "sideways", 2},
      {"TooManyPlanes", [](const fs::path&) { return std::vector<std::string>{"--max-zplanes", "17"}; },
       "--max-zplanes", "17", 2},
  };
  for (const std::string command : {"frame", "run"}) {
    for (const BadInput& input : inputs) {
      const fs::path out = scratch_ / (command + input.name);
      ExpectRefused(command, input, scratch_, out);
      EXPECT_FALSE(fs::exists(out)) << command << " " << input.name;
    }
  }
}

}  // namespace
