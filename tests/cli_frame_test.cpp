// `aasim frame` end to end: a small run writes every listed output, its dispatch report is
// consistent (lanes add up, one CSV row per dispatch, both strategies' images identical, the
// same counters with 1 and 2 threads), and every bad input fails with one stderr line and no
// output directory. Also the in-process writers on hand-built reports (JSON schema, CSV quoting,
// summary table, heat maps) and the frame inputs built from a scene.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <ostream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <stb_image.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "cli/dispatch_output.h"
#include "study/frame_scene.h"
#include "cli/frame_options.h"
#include "cli_test_util.h"
#include "passes/resolve.h"
#include "fmask/eqaa_surface.h"
#include "raster/counters.h"
#include "scenes/shading.h"
#include "sim/counters.h"
#include "sim/dispatch.h"
#include "sim/frame.h"
#include "sim/gpu_config.h"

namespace {

namespace fs = std::filesystem;

using cli::testing::BadInput;
using cli::testing::CommandResult;
using cli::testing::ExpectRefused;
using cli::testing::ExrChannelNames;
using cli::testing::FilesIn;
using cli::testing::ReadExrChannels;
using cli::testing::ReadText;
using cli::testing::RunAasim;
using cli::testing::WriteFile;

std::vector<std::string> SmallRun(const fs::path& out, const std::string& threads = "2") {
  return {"frame", "--scene",   "builtin:default", "--width", "320",       "--height",
          "180",   "--threads", threads,           "--out",   out.string()};
}

// Splits CSV text into rows of fields, honouring quoted fields with doubled quotes.
std::vector<std::vector<std::string>> ParseCsv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(field);
      field.clear();
    } else if (c == '\n') {
      row.push_back(field);
      rows.push_back(row);
      row.clear();
      field.clear();
    } else {
      field += c;
    }
  }
  return rows;
}

std::vector<std::string> LaneCounterNames() {
  std::vector<std::string> names;
  for (const sim::LaneCounterField& field : sim::kLaneCounterFields) names.emplace_back(field.name);
  return names;
}

// One run shared by the tests that only read its outputs.
class CliFrameTest : public cli::testing::ScratchDirTest {
 protected:
  static void SetUpTestSuite() {
    runDir_ = fs::temp_directory_path() / ("aasim_cli_frame_run_" + std::to_string(::getpid()));
    fs::remove_all(runDir_);
    fs::create_directories(runDir_);
    run_ = RunAasim(SmallRun(runDir_ / "out"), runDir_);
  }
  static void TearDownTestSuite() { fs::remove_all(runDir_); }

  static fs::path Out() { return runDir_ / "out"; }
  static nlohmann::ordered_json Report() {
    return nlohmann::ordered_json::parse(ReadText(Out() / "dispatches.json"));
  }

  static inline fs::path runDir_;
  static inline CommandResult run_;
};

TEST_F(CliFrameTest, SmallRunWritesEveryOutput) {
  ASSERT_EQ(run_.exitCode, 0) << run_.err;
  EXPECT_EQ(run_.err, "");
  EXPECT_EQ(FilesIn(Out()),
            (std::vector<std::string>{"colour.png", "dispatches.csv", "dispatches.json",
                                      "frame.exr", "heat", "post"}));
  EXPECT_EQ(FilesIn(Out() / "post"), (std::vector<std::string>{"queue", "stencil"}));
  for (const char* strategy : {"queue", "stencil"}) {
    EXPECT_EQ(FilesIn(Out() / "post" / strategy),
              (std::vector<std::string>{"edges.png", "output.png"}));
  }
  int width = 0, height = 0, channels = 0;
  ASSERT_TRUE(stbi_info((Out() / "colour.png").c_str(), &width, &height, &channels));
  EXPECT_EQ(width, 320);
  EXPECT_EQ(height, 180);
  EXPECT_EQ(channels, 3);
  ASSERT_TRUE(stbi_info((Out() / "post/queue/edges.png").c_str(), &width, &height, &channels));
  EXPECT_EQ(channels, 1);
  // OpenEXR lists channels sorted by name.
  EXPECT_EQ(ExrChannelNames(Out() / "frame.exr"),
            (std::vector<std::string>{"B", "G", "R", "depth", "normal.X", "normal.Y", "normal.Z",
                                      "objectId", "velocity.X", "velocity.Y"}));
  const std::map<std::string, std::vector<float>> frame = ReadExrChannels(Out() / "frame.exr");
  EXPECT_EQ(frame.at("depth").size(), 320u * 180u);
  EXPECT_TRUE(std::any_of(frame.at("objectId").begin(), frame.at("objectId").end(),
                          [](float id) { return id >= 0.0f; }));
  EXPECT_TRUE(std::all_of(frame.at("velocity.X").begin(), frame.at("velocity.X").end(),
                          [](float v) { return v == 0.0f; }));  // a still frame
}

TEST_F(CliFrameTest, StdoutHasTheTableTheComparisonAndTheReportPath) {
  ASSERT_EQ(run_.exitCode, 0) << run_.err;
  EXPECT_NE(run_.out.find("estimated from the GPU configuration '" +
                          std::string(sim::kDefaultGpuName) + "'"),
            std::string::npos)
      << run_.out;
  EXPECT_NE(run_.out.find("stencil vs queue"), std::string::npos) << run_.out;
  EXPECT_NE(run_.out.find("estimated µs"), std::string::npos) << run_.out;
  EXPECT_NE(run_.out.find("identical output: yes"), std::string::npos) << run_.out;
  EXPECT_NE(run_.out.find("report: " + (Out() / "dispatches.json").string() + "\n"),
            std::string::npos)
      << run_.out;
}

TEST_F(CliFrameTest, JsonHasTheSchemaEveryDispatchAndLanesThatAddUp) {
  ASSERT_EQ(run_.exitCode, 0) << run_.err;
  const nlohmann::ordered_json json = Report();
  EXPECT_EQ(json["schema"], cli::kDispatchesSchema);
  EXPECT_EQ(json["version"], cli::kDispatchesVersion);
  EXPECT_EQ(json["configuration"]["width"], 320);
  EXPECT_EQ(json["configuration"]["strategy"], "both");
  EXPECT_EQ(json["configuration"]["threads"], 2);
  std::vector<std::string> dispatches;
  for (const auto& dispatch : json["dispatches"]) {
    const std::string strategy = dispatch["strategy"].is_null() ? "" : dispatch["strategy"];
    dispatches.push_back(dispatch["name"].get<std::string>() + (strategy.empty() ? "" : "@") +
                         strategy);
    std::vector<std::string> keys;
    for (const auto& [key, value] : dispatch["counters"].items()) keys.push_back(key);
    EXPECT_EQ(keys, LaneCounterNames());
    const auto& c = dispatch["counters"];
    const std::uint64_t launched = c["lanes/launched"];
    EXPECT_EQ(launched, c["lanes/active"].get<std::uint64_t>() +
                            c["lanes/helper"].get<std::uint64_t>() +
                            c["lanes/dead_stencil"].get<std::uint64_t>() +
                            c["lanes/dead_empty"].get<std::uint64_t>())
        << dispatch["name"];
    EXPECT_EQ(launched, 64 * c["waves/launched"].get<std::uint64_t>()) << dispatch["name"];
    EXPECT_TRUE(dispatch["time_estimate_us"]["total"].is_number());
  }
  EXPECT_EQ(dispatches, (std::vector<std::string>{"frame/material", "frame/resolve", "demo/edge-detect@stencil",
                                                  "demo/blend@stencil", "demo/edge-detect@queue",
                                                  "demo/queue-args@queue", "demo/blend@queue"}));
  EXPECT_TRUE(json["dispatches"][0].contains("raster"));
  EXPECT_TRUE(json["dispatches"][0].contains("fragments"));
  EXPECT_GT(json["dispatches"][0]["counters"]["lanes/active"].get<std::uint64_t>(), 0u);
}

TEST_F(CliFrameTest, GpuBlockReadsBackAsAGpuFile) {
  ASSERT_EQ(run_.exitCode, 0) << run_.err;
  nlohmann::ordered_json gpu = Report()["gpu"];
  EXPECT_EQ(gpu["source"], "built-in");
  gpu.erase("source");
  // ParseGpuConfig wants every key of GpuConfig and no other, so this fails when the block
  // misses a field.
  const sim::GpuConfig parsed = sim::ParseGpuConfig(gpu.dump(), "dispatches.json gpu");
  const sim::GpuConfig builtin = sim::GpuConfigByName(sim::kDefaultGpuName);
  EXPECT_EQ(parsed.name, builtin.name);
  EXPECT_EQ(parsed.computeUnits, builtin.computeUnits);
  EXPECT_EQ(parsed.clockMhz, builtin.clockMhz);
}

TEST_F(CliFrameTest, CsvHasOneRowPerDispatchAndEqualColumnCounts) {
  ASSERT_EQ(run_.exitCode, 0) << run_.err;
  const std::vector<std::vector<std::string>> rows = ParseCsv(ReadText(Out() / "dispatches.csv"));
  ASSERT_EQ(rows.size(), Report()["dispatches"].size() + 1);
  for (const std::vector<std::string>& row : rows) EXPECT_EQ(row.size(), rows[0].size());
  EXPECT_EQ(rows[0][0], "name");
  EXPECT_EQ(rows[1][0], "frame/material");
  EXPECT_EQ(rows.back()[2], "queue");
}

TEST_F(CliFrameTest, BothStrategiesWriteIdenticalImages) {
  ASSERT_EQ(run_.exitCode, 0) << run_.err;
  for (const char* image : {"output.png", "edges.png"}) {
    const std::string stencil = ReadText(Out() / "post/stencil" / image);
    EXPECT_FALSE(stencil.empty());
    EXPECT_EQ(stencil, ReadText(Out() / "post/queue" / image)) << image;
  }
}

TEST_F(CliFrameTest, EveryDispatchWithAHeatMapHasBothFiles) {
  ASSERT_EQ(run_.exitCode, 0) << run_.err;
  const std::vector<std::string> heat = FilesIn(Out() / "heat");
  EXPECT_TRUE(std::find(heat.begin(), heat.end(), "0-frame-material.exr") != heat.end());
  EXPECT_TRUE(std::find(heat.begin(), heat.end(), "3-demo-blend-stencil.png") != heat.end());
  for (const std::string& name : heat) {
    const fs::path path(name);
    const std::string other = path.stem().string() + (path.extension() == ".exr" ? ".png" : ".exr");
    EXPECT_TRUE(std::find(heat.begin(), heat.end(), other) != heat.end()) << name;
  }
  // A tile's lanes are at most the 64 of its pixels, per kind and in total.
  const std::map<std::string, std::vector<float>> exr =
      ReadExrChannels(Out() / "heat/0-frame-material.exr");
  EXPECT_EQ(exr.at("launched").size(), 40u * 23u);  // 320x180 in 8x8 tiles
  for (std::size_t tile = 0; tile < exr.at("launched").size(); ++tile) {
    EXPECT_EQ(exr.at("launched")[tile],
              exr.at("active")[tile] + exr.at("helper")[tile] + exr.at("dead")[tile]);
  }
}

TEST_F(CliFrameTest, CountersAreTheSameWithOneThread) {
  ASSERT_EQ(run_.exitCode, 0) << run_.err;
  const CommandResult one = RunAasim(SmallRun(scratch_ / "one", "1"), scratch_);
  ASSERT_EQ(one.exitCode, 0) << one.err;
  EXPECT_EQ(ReadText(scratch_ / "one/dispatches.csv"), ReadText(Out() / "dispatches.csv"));
  EXPECT_EQ(ReadText(scratch_ / "one/colour.png"), ReadText(Out() / "colour.png"));
}

TEST_F(CliFrameTest, OneStrategyAndNoPostRunOnlyWhatWasAskedFor) {
  std::vector<std::string> args = SmallRun(scratch_ / "queue");
  args.insert(args.end(), {"--strategy", "queue"});
  const CommandResult queue = RunAasim(args, scratch_);
  ASSERT_EQ(queue.exitCode, 0) << queue.err;
  EXPECT_EQ(FilesIn(scratch_ / "queue/post"), std::vector<std::string>{"queue"});
  EXPECT_EQ(queue.out.find("stencil vs queue"), std::string::npos);

  args = SmallRun(scratch_ / "none");
  args.insert(args.end(), {"--post", "none"});
  const CommandResult none = RunAasim(args, scratch_);
  ASSERT_EQ(none.exitCode, 0) << none.err;
  EXPECT_FALSE(fs::exists(scratch_ / "none/post"));
  const nlohmann::json json = nlohmann::json::parse(ReadText(scratch_ / "none/dispatches.json"));
  // The frame's draw and its box resolve.
  EXPECT_EQ(json["dispatches"].size(), 2u);
}

// `aasim frame --post NAME` reaches every registered pass through the registry, both strategies
// agree, and a setting reaches the pass (the demo's threshold changes its work set).
TEST_F(CliFrameTest, EveryRegisteredPassRunsFromThePostOption) {
  for (const std::string& name : passes::PassNames()) {
    std::vector<std::string> args = SmallRun(scratch_ / name);
    args.insert(args.end(), {"--post", name});
    // A pass reading an S-sample EQAA surface gets a frame with S samples.
    if (const int samples = passes::PassByName(name).info().eqaaSamples; samples != 0) {
      const std::string s = std::to_string(samples);
      args.insert(args.end(), {"--samples", s, "--depth-samples", s, "--fragments", s, "--pattern", "standard"});
    }
    const CommandResult run = RunAasim(args, scratch_);
    ASSERT_EQ(run.exitCode, 0) << name << ": " << run.err;
    // A pass declaring one strategy (a full-screen temporal resolve) has nothing to compare.
    const std::vector<passes::Strategy>& strategies = passes::PassByName(name).info().strategies;
    if (strategies.size() > 1) {
      EXPECT_NE(run.out.find("identical output: yes"), std::string::npos) << name << ": " << run.out;
    }
    const nlohmann::json json = nlohmann::json::parse(ReadText(scratch_ / name / "dispatches.json"));
    EXPECT_EQ(json["configuration"]["post"], name);
    std::vector<std::string> expected;
    for (const passes::Strategy strategy : strategies) expected.emplace_back(passes::StrategyName(strategy));
    std::ranges::sort(expected);
    EXPECT_EQ(FilesIn(scratch_ / name / "post"), expected) << name;
  }
  auto edgeLanes = [&](const std::string& spec) {
    std::vector<std::string> args = SmallRun(scratch_ / "threshold");
    args.insert(args.end(), {"--post", spec, "--strategy", "queue"});
    const CommandResult run = RunAasim(args, scratch_);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json json = nlohmann::json::parse(ReadText(scratch_ / "threshold/dispatches.json"));
    EXPECT_EQ(json["configuration"]["pass_settings"], spec == "demo" ? "threshold=0.1" : "threshold=0.5");
    return json["dispatches"].back()["counters"]["lanes/active"].get<std::uint64_t>();
  };
  EXPECT_GT(edgeLanes("demo"), edgeLanes("demo:threshold=0.5"));
}

TEST_F(CliFrameTest, APassReadingASampleCountTheFrameLacksIsRefused) {
  std::vector<std::string> args = SmallRun(scratch_ / "s2x");
  args.insert(args.end(), {"--post", "smaa-s2x"});
  const CommandResult run = RunAasim(args, scratch_);
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("reads a 2-sample EQAA surface"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(scratch_ / "s2x"));
}

TEST_F(CliFrameTest, PassesListsTheRegistryWithSettings) {
  const CommandResult run = RunAasim({"passes"}, scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  for (const std::string& name : passes::PassNames()) EXPECT_NE(run.out.find(name + ": "), std::string::npos) << name;
  EXPECT_NE(run.out.find("threshold=0.1  (0, 1]"), std::string::npos) << run.out;
  // The resolves follow, each with what it reads; naming passes shows only those passes.
  for (const std::string& name : passes::ResolveNames()) EXPECT_NE(run.out.find(name + ": "), std::string::npos) << name;
  EXPECT_NE(run.out.find("  reads       1F surfaces of 2 to 16 samples"), std::string::npos) << run.out;
  const CommandResult one = RunAasim({"passes", "demo"}, scratch_);
  EXPECT_EQ(one.out.find("Resolves of the EQAA surface"), std::string::npos) << one.out;
  const CommandResult unknown = RunAasim({"passes", "nosuch"}, scratch_);
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_EQ(unknown.err.rfind("aasim passes: unknown post pass 'nosuch'", 0), 0u) << unknown.err;
}

TEST_F(CliFrameTest, HelpExplainsEveryOption) {
  const CommandResult run = RunAasim({"frame", "--help"}, scratch_);
  EXPECT_EQ(run.exitCode, 0);
  for (const char* option : {"--scene", "--width", "--height", "--samples", "--depth-samples",
                             "--fragments", "--pattern", "--policy", "--gpu", "--flush", "--post",
                             "--strategy", "--threads", "--out"}) {
    EXPECT_NE(run.out.find(option), std::string::npos) << option;
  }
  for (const std::string& gpu : sim::BuiltinGpuNames()) {
    EXPECT_NE(run.out.find(gpu), std::string::npos) << gpu;
  }
}

// --- Every bad input: exit code, one stderr line naming the input, no output directory. ---


std::vector<BadInput> FrameBadInputs() {
  const auto fixed = [](std::vector<std::string> args) {
    return [args](const fs::path&) { return args; };
  };
  return {
      {"UnknownGpu", fixed({"--gpu", "nosuch"}), "nosuch", std::string(sim::kDefaultGpuName), 1},
      {"FragmentsNotAPowerOfTwo", fixed({"--fragments", "3"}), "--fragments", "not in {1,2,4,8}",
       2},
      {"EqaaModeIllegal", fixed({"--samples", "4", "--depth-samples", "4", "--fragments", "8"}),
       "4S/4Z/8F", "8S/4Z/2F", 2},
      {"UnknownStrategy", fixed({"--strategy", "foo"}), "--strategy", "foo not in", 2},
      {"StrategyWithoutPost", fixed({"--post", "none", "--strategy", "queue"}), "--strategy queue",
       "needs a post pass", 2},
      {"UnknownFlush", fixed({"--flush", "sometimes"}), "--flush", "not in", 2},
      {"UnknownPass", fixed({"--post", "nosuch"}), "--post nosuch", "unknown post pass 'nosuch' (passes: demo", 2},
      {"PassSettingOutOfRange", fixed({"--post", "demo:threshold=2"}), "--post demo:threshold=2",
       "pass demo: threshold=2 outside (0, 1]", 2},
      {"UnknownPassSetting", fixed({"--post", "demo:speed=1"}), "--post demo:speed=1",
       "unknown setting 'speed' (settings: threshold)", 2},
      {"WidthZero", fixed({"--width", "0"}), "--width", "not in range 1 to 16384", 2},
      {"OverMemoryLimit",
       fixed({"--width", "16384", "--height", "16384", "--samples", "16", "--depth-samples", "8"}),
       "--width 16384", "4.0 GiB limit", 2},
      {"UnknownPattern", fixed({"--pattern", "nosuch"}), "nosuch", "unknown sample pattern", 1},
      {"UnknownScene", fixed({"--scene", "builtin:nosuch"}), "builtin:nosuch", "unknown", 1},
      {"OutUnderARegularFile",
       [](const fs::path& scratch) -> std::vector<std::string> {
         WriteFile(scratch / "somefile", "x");
         return {"--out", (scratch / "somefile" / "out").string()};
       },
       "--out", "cannot create directory: Not a directory", 1},
  };
}

class CliFrameBadInputTest : public cli::testing::ScratchDirTest,
                             public ::testing::WithParamInterface<BadInput> {};

TEST_P(CliFrameBadInputTest, FailsWithOneLineNamingTheInputAndCreatesNothing) {
  const fs::path out = scratch_ / "out";
  const CommandResult run = ExpectRefused("frame", GetParam(), scratch_, out);
  EXPECT_FALSE(fs::exists(out)) << run.err;
}

INSTANTIATE_TEST_SUITE_P(CliFrame, CliFrameBadInputTest, ::testing::ValuesIn(FrameBadInputs()),
                         [](const auto& param) { return param.param.name; });

TEST_F(CliFrameTest, MissingOutIsRefused) {
  const CommandResult run = RunAasim({"frame", "--width", "64"}, scratch_);
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(run.err, "aasim frame: --out is required\n");
}

// --- The writers on a hand-built report. ---

sim::DispatchReport HandBuiltReport() {
  sim::DispatchReport report;
  report.name = "test/a,b \"quoted\"";
  report.kind = sim::DispatchKind::Compute;
  report.kernel = {
      .vgprs = 24, .sgprs = 16, .ldsBytesPerGroup = 400, .valuInstructionsPerWave = 12.5};
  report.groupSize = {8, 8, 1};
  report.groupCount = {3, 2, 1};
  report.lanes.waves = 6;
  report.lanes.groups = 6;
  report.lanes.lanesLaunched = 384;
  report.lanes.lanesActive = 300;
  report.lanes.lanesDeadEmpty = 84;
  report.lanes.wavesByActiveLanes[50] = 6;
  sim::ResourceTraffic colour{
      .name = "colour", .access = sim::Access::Read, .bytesRead = 1200, .fetches = 300, .linesRead = 20};
  sim::ResourceTraffic queue{
      .name = "queue", .access = sim::Access::Append, .bytesWritten = 40, .atomics = 10, .storesDroppedOob = 3,
      .linesWritten = 1};
  report.resources = {colour, queue};
  report.occupancy = {.wavesPerSimd = 8,
                      .maxWavesPerSimd = 10,
                      .limiter = sim::OccupancyLimiter::Vgpr,
                      .byVgpr = 8,
                      .bySgpr = 10,
                      .byLds = 10,
                      .byGroups = 10,
                      .wavesPerGroup = 1,
                      .vgprsAllocated = 24,
                      .sgprsAllocated = 16,
                      .ldsBytesAllocated = 512};
  report.time = {.aluMicroseconds = 0.25,
                 .memoryMicroseconds = 0.5,
                 .launchMicroseconds = 0.125,
                 .rasterMicroseconds = 0.0,
                 .overheadMicroseconds = 1.0,
                 .totalMicroseconds = 1.5,
                 .bound = "memory"};
  report.raster = raster::RasterCounters{};
  report.raster->trianglesIn = 7;
  return report;
}

TEST(CliFrameDispatchOutput, JsonFollowsTheSchemaAndTheFieldTables) {
  const sim::DispatchReport report = HandBuiltReport();
  const sim::GpuConfig gpu = sim::GpuConfigByName(sim::kDefaultGpuName);
  const study::DispatchRecord record{report, "", "demo", "queue"};
  const nlohmann::ordered_json json = cli::DispatchReportsJson(std::span(&record, 1), gpu, {{"scene", "hand-built"}});
  EXPECT_EQ(json["schema"], "aasim.dispatches");
  EXPECT_EQ(json["version"], 1);
  EXPECT_EQ(json["gpu"]["name"], gpu.name);
  EXPECT_EQ(json["timing_model"], "estimate: see docs/timing-model.md");
  EXPECT_EQ(json["configuration"]["scene"], "hand-built");
  ASSERT_EQ(json["dispatches"].size(), 1u);
  const nlohmann::ordered_json& d = json["dispatches"][0];
  EXPECT_EQ(d["name"], report.name);
  EXPECT_EQ(d["kind"], "compute");
  EXPECT_EQ(d["strategy"], "queue");
  EXPECT_EQ(d["pass"], "demo");
  EXPECT_FALSE(d.contains("frame"));
  EXPECT_EQ(d["kernel"]["lds_bytes_per_group"], 400);
  EXPECT_EQ(d["kernel"]["valu_instructions_per_wave_estimate"], 12.5);
  EXPECT_EQ(d["group_size"], nlohmann::ordered_json({8, 8, 1}));
  EXPECT_EQ(d["group_count"], nlohmann::ordered_json({3, 2, 1}));
  std::vector<std::string> keys;
  for (const auto& [key, value] : d["counters"].items()) keys.push_back(key);
  EXPECT_EQ(keys, LaneCounterNames());
  EXPECT_EQ(d["counters"]["lanes/dead_empty"], 84);
  EXPECT_EQ(d["histograms"][sim::kWavesByActiveLanes].size(), 65u);
  EXPECT_EQ(d["histograms"][sim::kWavesByActiveLanes][50], 6);
  EXPECT_EQ(d["histograms"][sim::kQuadsByLivePixels].size(), 5u);
  EXPECT_EQ(d["histograms"][sim::kWavesByPrimitives].size(), 17u);
  ASSERT_EQ(d["resources"].size(), 2u);
  EXPECT_EQ(d["resources"][0]["name"], "colour");
  EXPECT_EQ(d["resources"][0]["dram_bytes"], 20 * 64);
  EXPECT_EQ(d["resources"][0]["access"], "read");
  EXPECT_EQ(d["resources"][1]["access"], "append");
  EXPECT_EQ(d["resources"][1]["atomics"], 10);
  EXPECT_EQ(d["resources"][1]["stores_dropped_oob"], 3);
  EXPECT_EQ(d["occupancy"]["waves_per_simd"], 8);
  EXPECT_EQ(d["occupancy"]["limiter"], sim::LimiterName(sim::OccupancyLimiter::Vgpr));
  EXPECT_EQ(d["occupancy"]["lds_bytes_allocated"], 512);
  EXPECT_EQ(d["time_estimate_us"]["total"], 1.5);
  EXPECT_EQ(d["time_estimate_us"]["bound"], "memory");
  ASSERT_TRUE(d.contains("raster"));
  EXPECT_EQ(d["raster"].size(), std::size(raster::kRasterCounterFields));
  EXPECT_EQ(d["raster"]["triangles/in"], 7);
  EXPECT_FALSE(d.contains("fragments"));
}

TEST(CliFrameDispatchOutput, CsvQuotesOnlyWhatNeedsIt) {
  EXPECT_EQ(cli::CsvField("plain"), "plain");
  EXPECT_EQ(cli::CsvField("full-screen PS"), "full-screen PS");
  EXPECT_EQ(cli::CsvField("a,b"), "\"a,b\"");
  EXPECT_EQ(cli::CsvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(cli::CsvField("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(cli::CsvField(""), "");
}

TEST(CliFrameDispatchOutput, CsvRowsMatchTheHeader) {
  const study::DispatchRecord record{HandBuiltReport(), "", "", ""};
  const sim::DispatchReport& report = record.report;
  const std::vector<std::vector<std::string>> rows = ParseCsv(cli::DispatchReportsCsv(std::span(&record, 1)));
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[0].size(), rows[1].size());
  std::map<std::string, std::string> row;
  for (std::size_t c = 0; c < rows[0].size(); ++c) row[rows[0][c]] = rows[1][c];
  EXPECT_EQ(row["name"], report.name);  // the comma and quotes survive the round trip
  EXPECT_EQ(row["kind"], "compute");
  EXPECT_EQ(row["strategy"], "");
  for (const std::string& name : LaneCounterNames()) EXPECT_EQ(row.count(name), 1u) << name;
  EXPECT_EQ(row["lanes/active"], "300");
  EXPECT_EQ(row["bytes_read"], "1200");
  EXPECT_EQ(row["bytes_written"], "40");
  EXPECT_EQ(row["stores_dropped_oob"], "3");
  EXPECT_EQ(row["dram_bytes"], std::to_string(21 * 64));
  EXPECT_EQ(row["occupancy_waves_per_simd"], "8");
  EXPECT_EQ(row["occupancy_limiter"], sim::LimiterName(sim::OccupancyLimiter::Vgpr));
  EXPECT_EQ(row["estimate_total_us"], "1.5");
  EXPECT_EQ(row["estimate_bound"], "memory");
  EXPECT_EQ(rows[0].front(), "name");
  EXPECT_EQ(rows[0].back(), "estimate_bound");
}

TEST(CliFrameDispatchOutput, PassCountersReachJsonAndCsvByName) {
  sim::DispatchReport smaa = HandBuiltReport();
  smaa.passCounters = {{"smaa/search_steps", 1234}, {"smaa/edges", 56}};
  sim::DispatchReport fxaa = HandBuiltReport();
  fxaa.name = "fxaa";
  fxaa.passCounters = {{"fxaa/horizontal_items", 7}, {"smaa/edges", 8}};
  const sim::DispatchReport plain = HandBuiltReport();
  const std::vector<study::DispatchRecord> reports{{smaa, "", "", ""}, {fxaa, "", "", ""}, {plain, "", "", ""}};

  const nlohmann::ordered_json json =
      cli::DispatchReportsJson(reports, sim::GpuConfigByName(sim::kDefaultGpuName), {});
  EXPECT_EQ(json["dispatches"][0]["pass_counters"],
            nlohmann::ordered_json({{"smaa/search_steps", 1234}, {"smaa/edges", 56}}));
  EXPECT_EQ(json["dispatches"][1]["pass_counters"]["fxaa/horizontal_items"], 7);
  EXPECT_EQ(json["dispatches"][2]["pass_counters"], nlohmann::ordered_json::object());

  const std::vector<std::vector<std::string>> rows = ParseCsv(cli::DispatchReportsCsv(reports));
  ASSERT_EQ(rows.size(), 4u);
  // The union of names in first-seen order, after every fixed column.
  const std::vector<std::string> tail(rows[0].end() - 3, rows[0].end());
  EXPECT_EQ(tail, (std::vector<std::string>{"pass_counters/smaa/search_steps", "pass_counters/smaa/edges",
                                            "pass_counters/fxaa/horizontal_items"}));
  EXPECT_EQ(std::vector<std::string>(rows[1].end() - 3, rows[1].end()),
            (std::vector<std::string>{"1234", "56", ""}));
  EXPECT_EQ(std::vector<std::string>(rows[2].end() - 3, rows[2].end()), (std::vector<std::string>{"", "8", "7"}));
  EXPECT_EQ(std::vector<std::string>(rows[3].end() - 3, rows[3].end()), (std::vector<std::string>{"", "", ""}));
  for (const std::vector<std::string>& row : rows) EXPECT_EQ(row.size(), rows[0].size());
}

TEST(CliFrameDispatchOutput, SummaryNamesTheGpuAndAlignsItsColumns) {
  sim::DispatchReport other = HandBuiltReport();
  other.name = "x";
  other.lanes.waves = 123456;
  const std::vector<study::DispatchRecord> records{{HandBuiltReport(), "", "demo", "stencil"}, {other, "", "", ""}};
  sim::GpuConfig gpu;
  gpu.name = "test-gpu";
  std::ostringstream out;
  cli::PrintDispatchSummary(out, records, gpu);
  std::vector<std::string> lines;
  std::istringstream in(out.str());
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u) << out.str();
  EXPECT_NE(lines[0].find("estimated from the GPU configuration 'test-gpu'"), std::string::npos);
  EXPECT_EQ(lines[1].rfind("dispatch", 0), 0u);
  EXPECT_NE(lines[2].find("[stencil]"), std::string::npos);
  EXPECT_NE(lines[2].find("8/10 (VGPR)"), std::string::npos) << lines[2];
  EXPECT_NE(lines[2].find("78.1"), std::string::npos) << lines[2];  // 300 of 384 lanes active
  // Right-aligned numbers: the waves column ends at the same place in every row.
  const std::size_t wavesEnd = lines[1].find("waves") + 5;
  EXPECT_EQ(lines[3].find("123456") + 6, wavesEnd) << out.str();
  EXPECT_EQ(lines[2].find(" 6 ") + 2, wavesEnd) << out.str();
}

class CliFrameHeatMapTest : public cli::testing::ScratchDirTest {};

TEST_F(CliFrameHeatMapTest, ExrHasLaneCountsAndPngShowsUtilization) {
  sim::TileHeatMap heat(24, 8);  // three tiles in a row
  for (int i = 0; i < 48; ++i) heat.Add(i % 8, i / 8, sim::LaneKind::Active);
  for (int i = 0; i < 16; ++i) heat.Add(i % 8, 6 + i / 8, sim::LaneKind::Helper);
  heat.Add(8, 0, sim::LaneKind::DeadStencil);  // tile 1: launched, nothing active
  cli::WriteHeatMap(heat, scratch_ / "h.exr", scratch_ / "h.png");

  const std::map<std::string, std::vector<float>> exr = ReadExrChannels(scratch_ / "h.exr");
  EXPECT_EQ(exr.at("active"), (std::vector<float>{48, 0, 0}));
  EXPECT_EQ(exr.at("helper"), (std::vector<float>{16, 0, 0}));
  EXPECT_EQ(exr.at("dead"), (std::vector<float>{0, 1, 0}));
  EXPECT_EQ(exr.at("launched"), (std::vector<float>{64, 1, 0}));
  EXPECT_EQ(exr.at("utilization"), (std::vector<float>{0.75f, 0, 0}));

  int width = 0, height = 0, channels = 0;
  stbi_uc* png = stbi_load((scratch_ / "h.png").c_str(), &width, &height, &channels, 3);
  ASSERT_NE(png, nullptr);
  EXPECT_EQ(width, 12);
  EXPECT_EQ(height, 4);
  const auto pixel = [&](int x, int y) {
    const stbi_uc* p = png + (y * width + x) * 3;
    return std::vector<int>{p[0], p[1], p[2]};
  };
  EXPECT_EQ(pixel(0, 0), pixel(3, 3));         // nearest-neighbour 4x
  EXPECT_GT(pixel(0, 0)[0], pixel(4, 0)[0]);   // 75% is yellower than 0%
  EXPECT_GT(pixel(4, 0)[2], pixel(4, 0)[0]);   // 0% is blue
  const std::vector<int> empty = pixel(8, 0);  // no lanes: grey
  EXPECT_EQ(empty[0], empty[1]);
  EXPECT_EQ(empty[1], empty[2]);
  stbi_image_free(png);

  EXPECT_THROW(cli::WriteHeatMap(sim::TileHeatMap(), scratch_ / "e.exr", scratch_ / "e.png"),
               std::invalid_argument);
}

TEST(CliFrameDispatchOutput, HeatMapStemsAreFileNamesInRunOrder) {
  EXPECT_EQ(cli::HeatMapStem(0, "frame/material", ""), "0-frame-material");
  EXPECT_EQ(cli::HeatMapStem(4, "demo/blend", "queue"), "4-demo-blend-queue");
  EXPECT_EQ(cli::HeatMapStem(12, "a b:c\\d", ""), "12-a-b-c-d");
}

// --- Frame inputs from a scene (study/frame_scene.h). ---

TEST(CliFrameInput, ObjectIdsAreMeshIndicesAndColoursComeFromThePalette) {
  scenes::Scene scene;
  scene.name = "two meshes";
  scenes::Mesh withNormals{.name = "a",
                           .positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                           .normals = {{0, 0, -1}, {0, 0, -1}, {0, 0, -1}},
                           .texcoords = {},
                           .indices = {0, 1, 2},
                           .material = -1};
  scenes::Mesh without{.name = "b",
                       .positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}},
                       .normals = {},
                       .texcoords = {},
                       .indices = {0, 1, 2, 1, 3, 2},
                       .material = -1};
  scene.meshes = {withNormals, without};
  const study::FrameScene frame = study::ToFrameScene(scene, 1.0f);
  EXPECT_EQ(frame.objectIds, (std::vector<std::uint32_t>{0, 1, 1}));
  EXPECT_EQ(frame.baseColours,
            (std::vector<glm::vec3>{scenes::kMeshPalette[0], scenes::kMeshPalette[1]}));
  ASSERT_EQ(frame.normals.size(), 7u);
  EXPECT_EQ(frame.normals[0], glm::vec3(0, 0, -1));  // the mesh's own normals are kept
  EXPECT_EQ(frame.normals[3], glm::vec3(0, 0, 1));   // computed ones face the front
  const sim::FrameGeometry geometry = frame.Geometry();
  EXPECT_EQ(geometry.clipPositions.size(), 7u);
  EXPECT_TRUE(geometry.previousClipPositions.empty());
  EXPECT_EQ(geometry.indices.size(), 9u);
}

// A textured material reaches the material kernel as its factor plus the texture, so the frame
// shades what scenes::BaseColour (and the ground truth) does; untextured meshes keep their colour.
TEST(CliFrameInput, TexturedMaterialsCarryFactorTextureAndTexcoords) {
  scenes::Scene scene;
  scene.name = "textured";
  scene.textures = {{.name = "checks", .width = 2, .height = 1, .texels = {glm::vec4(1.0f), glm::vec4(0.0f)}}};
  scene.materials = {{.name = "textured", .baseColourFactor = {0.5f, 0.25f, 1.0f, 1.0f}, .baseColourTexture = 0},
                     {.name = "plain", .baseColourFactor = {0.2f, 0.4f, 0.6f, 1.0f}, .baseColourTexture = -1}};
  scenes::Mesh textured{.name = "t", .positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, .normals = {},
                        .texcoords = {{0, 0}, {1, 0}, {0, 1}}, .indices = {0, 1, 2}, .material = 0};
  scenes::Mesh plain{.name = "p", .positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, .normals = {},
                     .texcoords = {}, .indices = {0, 1, 2}, .material = 1};
  scene.meshes = {textured, plain};
  const study::FrameScene frame = study::ToFrameScene(scene, 1.0f);
  EXPECT_EQ(frame.baseColours, (std::vector<glm::vec3>{{0.5f, 0.25f, 1.0f}, {0.2f, 0.4f, 0.6f}}));
  EXPECT_EQ(frame.baseColourTextures, (std::vector<int>{0, -1}));
  ASSERT_EQ(frame.textures.size(), 1u);
  EXPECT_EQ(frame.textures[0].Width(), 2);
  EXPECT_EQ(frame.textures[0].At(1, 0), glm::vec4(0.0f));
  EXPECT_EQ(frame.textures[0].TexelBytes(), 4);  // modelled as RGBA8
  // Every vertex has texcoords once any mesh is textured; the plain mesh's are never read.
  ASSERT_EQ(frame.texcoords.size(), 6u);
  EXPECT_EQ(frame.texcoords[1], glm::vec2(1, 0));
  const sim::FrameGeometry geometry = frame.Geometry();
  EXPECT_EQ(geometry.textures.size(), 1u);
  EXPECT_EQ(geometry.baseColourTextures.size(), 2u);
}

TEST(CliFrameOptions, EveryStrategyCountsInTheMemoryEstimate) {
  const fmask::EqaaConfig eqaa{8, 4, 2};
  const passes::PassInfo& demo = passes::PassByName("demo").info();
  EXPECT_LT(cli::EstimateFrameBytes(64, 48, eqaa, &demo, 1), cli::EstimateFrameBytes(64, 48, eqaa, &demo, 2));
  EXPECT_LT(cli::EstimateFrameBytes(64, 48, eqaa, nullptr, 0), cli::EstimateFrameBytes(128, 48, eqaa, nullptr, 0));
  // What the pass declares is what the estimate adds per strategy (plus its previews).
  EXPECT_GE(cli::EstimateFrameBytes(64, 48, eqaa, &demo, 1) - cli::EstimateFrameBytes(64, 48, eqaa, nullptr, 0),
            64u * 48u * demo.bytesPerPixel);
}

}  // namespace
