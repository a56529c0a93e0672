// `aasim raster` end to end: the real binary writes its five outputs on good input (and the
// EQAA outputs with --fragments), and every bad input gives a non-zero exit, one stderr line
// naming the input and no output files. Also the in-process pieces the outputs are built from
// (sample ownership replay, primitive colours, the FMASK preview, the trace formats).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "cli/counters_json.h"
#include "cli/eqaa_output.h"
#include "cli/eqaa_trace.h"
#include "study/frame_scene.h"
#include "cli/image_io.h"
#include "cli/ownership.h"
#include "cli/raster_options.h"
#include "fmask/eqaa_surface.h"
#include "raster/counters.h"
#include "raster/rasterizer.h"
#include "scenes/scene.h"
#include "cli_test_util.h"
#include "scenes_test_util.h"

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
using scenes_test::TriangleGltf;

// x, y, z of three vertices.
const std::vector<float> kTrianglePositions{
    -1.0f, -1.0f, 0.0f,  //
    1.0f,  -1.0f, 0.0f,  //
    0.0f,  1.0f,  0.0f,
};

class CliRasterTest : public cli::testing::ScratchDirTest {};

std::vector<std::string> SmallRasterRun(const fs::path& out) {
  return {"raster",    "--scene", "builtin:default", "--width",   "64", "--height", "48",
          "--samples", "4",       "--out",           out.string()};
}

TEST_F(CliRasterTest, WritesTheFiveOutputsAndCountersMatchTheFieldTable) {
  const fs::path out = scratch_ / "out";
  const CommandResult run = RunAasim(SmallRasterRun(out), scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_NE(run.out.find("builtin:default"), std::string::npos) << run.out;
  EXPECT_EQ(FilesIn(out), (std::vector<std::string>{"counters.json", "coverage.png", "depth.exr",
                                                    "primitives.png", "samples.exr"}));

  const nlohmann::ordered_json json =
      nlohmann::ordered_json::parse(ReadText(out / "counters.json"));
  EXPECT_EQ(json["schema"], "aasim.raster.counters");
  EXPECT_EQ(json["version"], 1);
  EXPECT_EQ(json["config"]["width"], 64);
  EXPECT_EQ(json["config"]["samples"], 4);
  EXPECT_EQ(json["config"]["depth_samples"], 4);
  std::vector<std::string> keys, fieldNames;
  for (const auto& [key, value] : json["counters"].items()) {
    keys.push_back(key);
    EXPECT_TRUE(value.is_number_unsigned()) << key;
  }
  for (const raster::RasterCounterField& field : raster::kRasterCounterFields) {
    fieldNames.emplace_back(field.name);
  }
  EXPECT_EQ(keys, fieldNames);
  EXPECT_GT(json["counters"]["samples/covered"].get<std::uint64_t>(), 0u);

  int width = 0, height = 0, channels = 0;
  ASSERT_TRUE(stbi_info((out / "coverage.png").c_str(), &width, &height, &channels));
  EXPECT_EQ(width, 64);
  EXPECT_EQ(height, 48);
  EXPECT_EQ(channels, 1);
  ASSERT_TRUE(stbi_info((out / "primitives.png").c_str(), &width, &height, &channels));
  EXPECT_EQ(channels, 3);
  // OpenEXR lists channels sorted by name.
  EXPECT_EQ(
      ExrChannelNames(out / "depth.exr"),
      (std::vector<std::string>{"Z", "coverage", "depth.s0", "depth.s1", "depth.s2", "depth.s3"}));
}

TEST_F(CliRasterTest, OutputsAreIdenticalWithOneAndTwoThreads) {
  std::vector<std::string> one = SmallRasterRun(scratch_ / "one"), two = SmallRasterRun(scratch_ / "two");
  one.insert(one.end(), {"--threads", "1"});
  two.insert(two.end(), {"--threads", "2"});
  ASSERT_EQ(RunAasim(one, scratch_).exitCode, 0);
  ASSERT_EQ(RunAasim(two, scratch_).exitCode, 0);
  for (const char* file : {"coverage.png", "primitives.png", "depth.exr", "samples.exr"}) {
    EXPECT_EQ(ReadText(scratch_ / "one" / file), ReadText(scratch_ / "two" / file)) << file;
  }
  const auto counters = [&](const char* dir) {
    return nlohmann::json::parse(ReadText(scratch_ / dir / "counters.json"))["counters"];
  };
  EXPECT_EQ(counters("one"), counters("two"));
}

TEST_F(CliRasterTest, RendersAValidGltfFile) {
  const fs::path scene =
      WriteFile(scratch_ / "tri.gltf", TriangleGltf(kTrianglePositions, {0, 1, 2}));
  const fs::path out = scratch_ / "out";
  const CommandResult run = RunAasim({"raster", "--scene", scene.string(), "--width", "32",
                                      "--height", "32", "--cull", "none", "--out", out.string()},
                                     scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(ReadText(out / "counters.json"));
  EXPECT_EQ(json["counters"]["triangles/in"], 1);
  EXPECT_GT(json["counters"]["samples/covered"].get<std::uint64_t>(), 0u);
}

// Every channel of an EXR file that stores 32-bit unsigned integers, by name; fails the test
// on a channel of another type.
std::map<std::string, std::vector<std::uint32_t>> ReadUintExrChannels(const fs::path& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  const std::size_t width = static_cast<std::size_t>(window.max.x - window.min.x + 1);
  const std::size_t height = static_cast<std::size_t>(window.max.y - window.min.y + 1);
  std::map<std::string, std::vector<std::uint32_t>> channels;
  Imf::FrameBuffer frameBuffer;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    EXPECT_EQ(it.channel().type, Imf::UINT) << it.name();
    std::vector<std::uint32_t>& values = channels[it.name()];
    values.resize(width * height);
    frameBuffer.insert(it.name(), Imf::Slice(Imf::UINT, reinterpret_cast<char*>(values.data()),
                                             sizeof(std::uint32_t), sizeof(std::uint32_t) * width));
  }
  file.setFrameBuffer(frameBuffer);
  file.readPixels(window.min.y, window.max.y);
  return channels;
}

// Which samples a triangle covers, from the documents alone: vertices snapped to 1/256 px
// (round half away from zero), reoriented so the doubled area is positive (y down), integer
// edge functions with the top-left rule (docs/raster.md), samples at the standard 4x offsets
// of hw-facts §4.1: (-2,-6) (6,-2) (-6,2) (2,6) in 1/16 px from the pixel centre.
struct SnappedTriangle {
  std::array<std::array<std::int64_t, 2>, 3> v;
};

SnappedTriangle Snap(const std::array<glm::vec4, 3>& clip, int width, int height) {
  SnappedTriangle t{};
  for (int i = 0; i < 3; ++i) {
    const double invW = 1.0 / static_cast<double>(clip[i].w);
    const double ndcX = static_cast<double>(clip[i].x) * invW, ndcY = static_cast<double>(clip[i].y) * invW;
    t.v[i] = {std::llround((ndcX * 0.5 + 0.5) * width * 256.0), std::llround((0.5 - ndcY * 0.5) * height * 256.0)};
  }
  return t;
}

bool Covers(SnappedTriangle t, std::int64_t x, std::int64_t y) {
  auto cross = [](auto a, auto b, auto c) { return (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]); };
  if (cross(t.v[0], t.v[1], t.v[2]) < 0) std::swap(t.v[1], t.v[2]);
  for (int e = 0; e < 3; ++e) {
    const auto& p = t.v[(e + 1) % 3];
    const auto& q = t.v[(e + 2) % 3];
    const std::int64_t dx = q[0] - p[0], dy = q[1] - p[1];
    const std::int64_t value = -dy * (x - p[0]) + dx * (y - p[1]);
    const bool topLeft = dy < 0 || (dy == 0 && dx > 0);
    if (value < 0 || (value == 0 && !topLeft)) return false;
  }
  return true;
}

// samples.exr holds, per sample, the coverage (before depth) and the visible primitive as
// 32-bit unsigned integers. Two triangles sharing an edge: every sample inside the pair is
// covered by exactly one, and its id is that triangle's.
TEST_F(CliRasterTest, SamplesExrHoldsPerSampleCoverageAndPrimitiveIds) {
  // Odd sizes: the last quad column and row stick out; 49 rows make two strips of 32-row bins,
  // and the pair, framed in the middle of the view, reaches into the second.
  constexpr int kWidth = 53, kHeight = 49;
  const std::vector<float> positions{-1.0f, -0.8f, 0.0f, 1.2f, -1.0f, 0.0f,
                                     0.9f,  1.0f,  0.0f, -1.1f, 0.7f,  0.0f};
  const std::vector<std::uint32_t> indices{0, 1, 2, 0, 2, 3};
  const fs::path scenePath = WriteFile(scratch_ / "pair.gltf", TriangleGltf(positions, indices));
  const fs::path out = scratch_ / "out";
  const CommandResult run =
      RunAasim({"raster", "--scene", scenePath.string(), "--width", std::to_string(kWidth),
                "--height", std::to_string(kHeight), "--samples", "4", "--pattern", "standard",
                "--cull", "none", "--out", out.string()},
               scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;

  // The clip positions the command rasterized, from the same scene and camera code.
  const float aspect = static_cast<float>(kWidth) / static_cast<float>(kHeight);
  const study::ClipSpaceScene clip = study::ToClipSpace(scenes::LoadScene(scenePath.string(), aspect), aspect);
  std::vector<SnappedTriangle> triangles;
  for (std::size_t t = 0; t < indices.size() / 3; ++t) {
    triangles.push_back(Snap({clip.positions[indices[3 * t]], clip.positions[indices[3 * t + 1]],
                              clip.positions[indices[3 * t + 2]]},
                             kWidth, kHeight));
  }
  constexpr int kOffsets[4][2] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};

  const auto channels = ReadUintExrChannels(out / "samples.exr");
  std::vector<std::string> names;
  for (const auto& [name, values] : channels) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"coverage.s0", "coverage.s1", "coverage.s2", "coverage.s3",
                                             "primitive.s0", "primitive.s1", "primitive.s2", "primitive.s3"}));
  std::array<int, 2> coveredBy{};
  int coveredInSecondStrip = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      for (int s = 0; s < 4; ++s) {
        const std::int64_t sx = x * 256 + 128 + 16 * kOffsets[s][0], sy = y * 256 + 128 + 16 * kOffsets[s][1];
        const bool in0 = Covers(triangles[0], sx, sy), in1 = Covers(triangles[1], sx, sy);
        ASSERT_FALSE(in0 && in1) << "shared edge covered twice at " << x << "," << y << " sample " << s;
        const std::uint32_t expected = in0 ? 0u : in1 ? 1u : cli::kNoPrimitive;
        const std::size_t pixel = static_cast<std::size_t>(y) * kWidth + x;
        const std::string suffix = ".s" + std::to_string(s);
        ASSERT_EQ(channels.at("coverage" + suffix)[pixel], (in0 || in1) ? 1u : 0u) << x << "," << y << " sample " << s;
        ASSERT_EQ(channels.at("primitive" + suffix)[pixel], expected) << x << "," << y << " sample " << s;
        coveredBy[0] += in0;
        coveredBy[1] += in1;
        coveredInSecondStrip += y >= 32 && (in0 || in1);
      }
    }
  }
  // Both triangles cover a good part of the image's 10388 samples.
  EXPECT_GT(coveredBy[0], 100);
  EXPECT_GT(coveredBy[1], 100);
  EXPECT_GT(coveredInSecondStrip, 0);
}

TEST_F(CliRasterTest, HelpExplainsEveryOption) {
  const CommandResult run = RunAasim({"raster", "--help"}, scratch_);
  EXPECT_EQ(run.exitCode, 0);
  EXPECT_EQ(run.err, "");
  for (const char* option :
       {"--scene", "--width", "--height", "--samples", "--depth-samples", "--pattern",
        "--max-zplanes", "--cull", "--depth-func", "--no-hiz", "--threads", "--out", "--fragments",
        "--policy", "--fmask-init", "--trace"}) {
    EXPECT_NE(run.out.find(option), std::string::npos) << option;
  }
  EXPECT_NE(run.out.find("[1 - 16384]=1920"), std::string::npos) << run.out;
}

TEST_F(CliRasterTest, TopLevelHelpListsEverySubcommand) {
  const CommandResult run = RunAasim({"--help"}, scratch_);
  EXPECT_EQ(run.exitCode, 0);
  for (const char* command : {"raster", "fixtures", "frame", "run"}) {
    EXPECT_NE(run.out.find(command), std::string::npos) << command << "\n" << run.out;
  }
}

// --- The colour block (--fragments): one run per EQAA mode of the issue. ---

struct EqaaMode {
  std::string name;
  int samples, depthSamples, fragments;
};

void PrintTo(const EqaaMode& mode, std::ostream* os) { *os << mode.name; }

std::vector<std::string> EqaaRun(const EqaaMode& mode, const fs::path& out) {
  return {"raster",
          "--scene",
          "builtin:default",
          "--width",
          "96",
          "--height",
          "64",
          "--samples",
          std::to_string(mode.samples),
          "--depth-samples",
          std::to_string(mode.depthSamples),
          "--fragments",
          std::to_string(mode.fragments),
          "--out",
          out.string()};
}

std::vector<std::string> FragmentCounterNames() {
  std::vector<std::string> names;
  fmask::FragmentCounters{}.ForEach(
      [&](const char* name, std::uint64_t) { names.emplace_back(name); });
  return names;
}

class CliRasterEqaaTest : public CliRasterTest, public ::testing::WithParamInterface<EqaaMode> {};

TEST_P(CliRasterEqaaTest, WritesTheEqaaOutputsAndCounters) {
  const EqaaMode& mode = GetParam();
  const fs::path out = scratch_ / "out";
  const CommandResult run = RunAasim(EqaaRun(mode, out), scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  const std::string config = std::to_string(mode.samples) + "S/" +
                             std::to_string(mode.depthSamples) + "Z/" +
                             std::to_string(mode.fragments) + "F";
  EXPECT_NE(run.out.find("eqaa       " + config + ", policy hraa"), std::string::npos) << run.out;
  EXPECT_EQ(FilesIn(out),
            (std::vector<std::string>{"counters.json", "coverage.png", "depth.exr", "eqaa.exr",
                                      "fmask.png", "primitives.png", "resolve.png",
                                      "samples.exr"}));

  const nlohmann::ordered_json json =
      nlohmann::ordered_json::parse(ReadText(out / "counters.json"));
  const nlohmann::ordered_json& eqaa = json["eqaa"];
  EXPECT_EQ(eqaa["config"], config);
  EXPECT_EQ(eqaa["policy"], "hraa");
  EXPECT_EQ(eqaa["init"], "cleared");
  std::vector<std::string> keys;
  for (const auto& [key, value] : eqaa["counters"].items()) {
    keys.push_back(key);
    EXPECT_TRUE(value.is_number_unsigned()) << key;
  }
  EXPECT_EQ(keys, FragmentCounterNames());
  EXPECT_GT(eqaa["counters"]["pixels/updates"].get<std::uint64_t>(), 0u);

  for (const char* png : {"resolve.png", "fmask.png"}) {
    int width = 0, height = 0, channels = 0;
    ASSERT_TRUE(stbi_info((out / png).c_str(), &width, &height, &channels)) << png;
    EXPECT_EQ(width, 96) << png;
    EXPECT_EQ(height, 64) << png;
    EXPECT_EQ(channels, 3) << png;
  }

  // OpenEXR lists channels sorted by name (fmask.s10 before fmask.s2).
  const std::map<std::string, std::vector<float>> exr = ReadExrChannels(out / "eqaa.exr");
  std::vector<std::string> expected{"A", "B", "G", "R", "fragments", "unknown"};
  for (int s = 0; s < mode.samples; ++s) expected.push_back("fmask.s" + std::to_string(s));
  std::sort(expected.begin(), expected.end());
  std::vector<std::string> names;
  for (const auto& [name, values] : exr) names.push_back(name);
  ASSERT_EQ(names, expected);

  // Per pixel: codes are integers naming a slot or UNKNOWN (= F; 0 or 1 for 1F), `unknown`
  // counts the UNKNOWN codes, and no pixel holds more than F fragments.
  const float unknownCode = static_cast<float>(mode.fragments);
  for (std::size_t pixel = 0; pixel < exr.at("unknown").size(); ++pixel) {
    int unknown = 0;
    for (int s = 0; s < mode.samples; ++s) {
      const float code = exr.at("fmask.s" + std::to_string(s))[pixel];
      ASSERT_EQ(code, std::floor(code)) << pixel;
      ASSERT_GE(code, 0.0f) << pixel;
      ASSERT_LE(code, unknownCode) << pixel;
      unknown += code == unknownCode;
    }
    ASSERT_EQ(exr.at("unknown")[pixel], static_cast<float>(unknown)) << pixel;
    ASSERT_GE(exr.at("fragments")[pixel], 0.0f) << pixel;
    ASSERT_LE(exr.at("fragments")[pixel], unknownCode) << pixel;
  }
}

INSTANTIATE_TEST_SUITE_P(CliEqaaModes, CliRasterEqaaTest,
                         ::testing::Values(EqaaMode{"8S8Z1F", 8, 8, 1}, EqaaMode{"8S4Z2F", 8, 4, 2},
                                           EqaaMode{"16S8Z4F", 16, 8, 4}),
                         [](const auto& param) { return param.param.name; });

TEST_F(CliRasterTest, TraceRecordsEveryUpdateOfTheTracedPixel) {
  const fs::path out = scratch_ / "out";
  std::vector<std::string> args = EqaaRun({"8S4Z2F", 8, 4, 2}, out);
  args.insert(args.end(), {"--trace", "48,32"});
  const CommandResult run = RunAasim(args, scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json trace = nlohmann::json::parse(ReadText(out / "trace.json"));
  EXPECT_EQ(trace["schema"], "aasim.raster.trace");
  EXPECT_EQ(trace["eqaa"], "8S/4Z/2F");
  EXPECT_EQ(trace["fmask_format"], "FMASK16_S8_F2");
  EXPECT_EQ(trace["traced"], nlohmann::json::parse("[[48, 32]]"));
  // The centre of the default scene is drawn at least once.
  ASSERT_FALSE(trace["events"].empty());
  for (const nlohmann::json& event : trace["events"]) {
    EXPECT_EQ(event["pixel"], nlohmann::json::parse("[48, 32]"));
    EXPECT_EQ(event["codes_before"].size(), 8u);
    EXPECT_EQ(event["codes_after"].size(), 8u);
    EXPECT_EQ(event["causes_after"].size(), 8u);
    EXPECT_EQ(event["slots_after"].size(), 2u);
    EXPECT_EQ(event["fmask_after"].get<std::string>().size(), 2u + 16u / 4u);
    EXPECT_FALSE(event["steps"].empty());
  }
  EXPECT_NE(ReadText(out / "trace.txt").find("event 0: pixel (48, 32)"), std::string::npos);
}

TEST_F(CliRasterTest, EqaaOutputsAreIdenticalWithOneAndTwoThreads) {
  const EqaaMode mode{"8S4Z2F", 8, 4, 2};
  std::vector<std::string> one = EqaaRun(mode, scratch_ / "one"),
                           two = EqaaRun(mode, scratch_ / "two");
  one.insert(one.end(), {"--threads", "1", "--trace", "48,32", "--trace", "20,40"});
  two.insert(two.end(), {"--threads", "2", "--trace", "48,32", "--trace", "20,40"});
  ASSERT_EQ(RunAasim(one, scratch_).exitCode, 0);
  ASSERT_EQ(RunAasim(two, scratch_).exitCode, 0);
  for (const char* file : {"eqaa.exr", "resolve.png", "fmask.png", "trace.json", "trace.txt"}) {
    EXPECT_EQ(ReadText(scratch_ / "one" / file), ReadText(scratch_ / "two" / file)) << file;
  }
  const auto counters = [&](const char* dir) {
    return nlohmann::json::parse(ReadText(scratch_ / dir / "counters.json"))["eqaa"];
  };
  EXPECT_EQ(counters("one"), counters("two"));
}

// --- Every bad input: exit code, one stderr line naming the input, no output files. ---

// Names the case in test listings instead of gtest's byte dump.

std::vector<BadInput> RasterBadInputs() {
  const auto fixed = [](std::vector<std::string> args) {
    return [args](const fs::path&) { return args; };
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  return {
      {"SamplesNotAPowerOfTwo", fixed({"--samples", "3"}), "--samples", "not in {1,2,4,8,16}", 2},
      {"DepthSamplesAboveSamples", fixed({"--samples", "4", "--depth-samples", "8"}),
       "--depth-samples 8", "need S >= Z", 2},
      {"WidthZero", fixed({"--width", "0"}), "--width", "not in range 1 to 16384", 2},
      {"WidthTooLarge", fixed({"--width", "100000"}), "100000", "not in range", 2},
      {"MaxZPlanesTooLarge", fixed({"--max-zplanes", "17"}), "--max-zplanes",
       "not in range 0 to 16", 2},
      {"SurfaceOverMemoryLimit",
       fixed({"--width", "16384", "--height", "16384", "--samples", "16"}), "--width 16384",
       "4.0 GiB limit", 2},
      {"UnknownPattern", fixed({"--pattern", "nosuch"}), "nosuch", "unknown sample pattern", 1},
      {"PatternFileOffGrid",
       [](const fs::path& scratch) -> std::vector<std::string> {
         const fs::path file = WriteFile(scratch / "offgrid.json",
                                         R"({"name": "offgrid", "samples": 4,
                           "offsets": [[-2, -6], [6.5, -2], [-6, 2], [2, 6]]})");
         return {"--samples", "4", "--pattern", file.string()};
       },
       "offgrid.json", "off the sample grid", 1},
      {"MalformedGltf",
       [](const fs::path& scratch) -> std::vector<std::string> {
         return {"--scene", WriteFile(scratch / "x.gltf", "garbage{").string()};
       },
       "x.gltf", "cannot load glTF", 1},
      {"GltfWithNanVertex",
       [nan](const fs::path& scratch) -> std::vector<std::string> {
         std::vector<float> positions = kTrianglePositions;
         positions[4] = nan;
         return {"--scene",
                 WriteFile(scratch / "nan.gltf", TriangleGltf(positions, {0, 1, 2})).string()};
       },
       "nan.gltf", "non-finite", 1},
      {"GltfWithIndexOutOfRange",
       [](const fs::path& scratch) -> std::vector<std::string> {
         return {"--scene",
                 WriteFile(scratch / "index.gltf", TriangleGltf(kTrianglePositions, {0, 1, 7}))
                     .string()};
       },
       "index.gltf", "out of range", 1},
      {"UnknownBuiltinScene", fixed({"--scene", "builtin:nosuch"}), "builtin:nosuch", "unknown", 1},
      {"FragmentsNotAPowerOfTwo", fixed({"--fragments", "3"}), "--fragments",
       "not in {1,2,4,8}", 2},
      {"EqaaModeIllegal", fixed({"--samples", "4", "--fragments", "8"}), "4S/4Z/8F", "8S/4Z/2F",
       2},
      {"UnknownInitWithoutUnknownCode",
       fixed({"--samples", "4", "--fragments", "4", "--fmask-init", "unknown"}),
       "--fmask-init unknown", "F < S", 2},
      {"UnknownPolicy", fixed({"--fragments", "2", "--policy", "nosuch"}), "--policy",
       "nosuch not in", 2},
      {"PolicyWithoutFragments", fixed({"--policy", "hraa"}), "--policy", "requires --fragments",
       2},
      {"TraceWithoutFragments", fixed({"--trace", "5,5"}), "--trace", "requires --fragments", 2},
      {"TraceOutsideViewport", fixed({"--fragments", "2", "--trace", "5000,5"}), "--trace 5000,5",
       "outside the 64x48 viewport", 2},
      {"TraceNotAPixel", fixed({"--fragments", "2", "--trace", "5;5"}), "--trace 5;5",
       "expected X,Y", 2},
      {"EqaaSurfaceOverMemoryLimit",
       fixed({"--width", "4096", "--height", "4096", "--samples", "16", "--fragments", "4"}),
       "--fragments 4", "4.0 GiB limit", 2},
      {"OutUnderARegularFile",
       [](const fs::path& scratch) -> std::vector<std::string> {
         WriteFile(scratch / "somefile", "x");
         return {"--out", (scratch / "somefile" / "out").string()};
       },
       "somefile/out", "cannot create directory: Not a directory", 1},
  };
}

class CliRasterBadInputTest : public CliRasterTest,
                              public ::testing::WithParamInterface<BadInput> {};

TEST_P(CliRasterBadInputTest, FailsWithOneLineNamingTheInputAndWritesNothing) {
  const fs::path out = scratch_ / "out";
  const CommandResult run = ExpectRefused("raster", GetParam(), scratch_, out);
  EXPECT_EQ(FilesIn(out), std::vector<std::string>{}) << run.err;
}

INSTANTIATE_TEST_SUITE_P(Inputs, CliRasterBadInputTest, ::testing::ValuesIn(RasterBadInputs()),
                         [](const auto& param) { return param.param.name; });

// --- Sample ownership replay (cli/ownership.h). ---

raster::QuadFragment Quad(int x, int y, std::uint32_t primitive,
                          std::initializer_list<std::pair<int, int>> passedSamples) {
  raster::QuadFragment quad;
  quad.x = static_cast<std::uint16_t>(x);
  quad.y = static_cast<std::uint16_t>(y);
  quad.primitiveId = primitive;
  for (const auto& [pixel, sample] : passedSamples) quad.passed.SetSample(pixel, sample);
  quad.covered = quad.passed;
  return quad;
}

raster::RasterResult OneBin(std::vector<raster::QuadFragment> quads) {
  raster::RasterResult result;
  result.binsX = 1;
  result.binsY = 1;
  result.quadsByBin.push_back(std::move(quads));
  return result;
}

TEST(CliOwnership, LastPassingWriterOwnsEachSample) {
  // S = 4. Pixel 0: all four samples by 5. Pixel 1: 5 writes samples 0, 1, then 7 overwrites
  // 1 and adds 2. Pixel 3: one sample each for 9 and 3, a tie.
  const raster::RasterResult result = OneBin({
      Quad(0, 0, 5, {{0, 0}, {0, 1}, {0, 2}, {0, 3}, {1, 0}, {1, 1}}),
      Quad(0, 0, 7, {{1, 1}, {1, 2}}),
      Quad(0, 0, 9, {{3, 0}}),
      Quad(0, 0, 3, {{3, 1}}),
  });
  const cli::PixelOwnership own = cli::ComputeOwnership(result, 2, 2, 4);
  EXPECT_EQ(own.coverage, (std::vector<float>{1.0f, 0.75f, 0.0f, 0.5f}));
  EXPECT_EQ(own.majorityPrimitive, (std::vector<std::uint32_t>{5, 7, cli::kNoPrimitive, 3}));
  EXPECT_EQ(own.ownerCount, (std::vector<std::uint8_t>{1, 2, 0, 2}));
  EXPECT_EQ(own.PixelsCovered(), 3u);
  EXPECT_EQ(own.PixelsPartial(), 2u);

  const std::vector<std::uint8_t> coverage = cli::CoverageImage(own);
  EXPECT_EQ(coverage, (std::vector<std::uint8_t>{255, 225, 0, 188}));
  const std::vector<std::uint8_t> primitives = cli::PrimitiveImage(own);
  EXPECT_EQ(std::vector<std::uint8_t>(primitives.begin() + 6, primitives.begin() + 9),
            (std::vector<std::uint8_t>{0, 0, 0}));
  EXPECT_GT(primitives[0] + primitives[1] + primitives[2], 0);
}

TEST(CliOwnership, QuadOutsideItsBinIsReported) {
  const raster::RasterResult result = OneBin({Quad(40, 0, 1, {{0, 0}})});
  EXPECT_THROW(cli::ComputeOwnership(result, 32, 32, 1), std::logic_error);
}

// --- EQAA outputs (cli/eqaa_output.h, cli/eqaa_trace.h). ---

TEST(CliEqaaOutput, PrimitiveColoursAreSaturatedOpaqueAndDiffer) {
  for (std::uint32_t id = 0; id < 64; ++id) {
    const fmask::Colour c = cli::PrimitiveColour(id);
    EXPECT_EQ(std::max({c.r, c.g, c.b}), 1.0f) << id;
    EXPECT_EQ(std::min({c.r, c.g, c.b}), 0.0f) << id;
    EXPECT_EQ(c.a, 1.0f) << id;
    EXPECT_NE(c, cli::PrimitiveColour(id + 1)) << id;
  }
}

TEST(CliEqaaOutput, FmaskPreviewBrightensWithUnknownAndTintsByFragments) {
  // S = 4; pixels: 1 fragment none unknown, 2 fragments none unknown, 0 fragments all unknown.
  cli::EqaaPlanes planes;
  planes.width = 3;
  planes.height = 1;
  planes.samples = 4;
  planes.fragments = {1.0f, 2.0f, 0.0f};
  planes.unknown = {0.0f, 0.0f, 4.0f};
  const std::vector<std::uint8_t> image = cli::FmaskImage(planes);
  const std::uint8_t grey = cli::EncodeSrgb8(0.25f);
  EXPECT_EQ(std::vector<std::uint8_t>(image.begin(), image.begin() + 3),
            (std::vector<std::uint8_t>{grey, grey, grey}));
  EXPECT_LT(image[3], image[5]);  // two fragments: blue
  EXPECT_EQ(std::vector<std::uint8_t>(image.begin() + 6, image.end()),
            (std::vector<std::uint8_t>{255, 255, 255}));
}

TEST(CliEqaaOutput, EqaaSurfaceCountsInTheMemoryEstimate) {
  const std::uint64_t pixels = 64 * 48;
  const std::uint64_t without = cli::EstimateRasterBytes(64, 48, 8, 4, 0);
  const std::uint64_t with = cli::EstimateRasterBytes(64, 48, 8, 4, 2);
  // FMASK element, F slots and S causes per pixel at least.
  EXPECT_GE(with - without, pixels * (8 + 2 * 24 + 8));
}

TEST(CliEqaaOutput, CounterJsonHasEveryCounterInForEachOrder) {
  fmask::FragmentCounters counters;
  counters.evictions = 7;
  const nlohmann::ordered_json json = cli::FragmentCountersJson(counters);
  std::vector<std::string> keys;
  for (const auto& [key, value] : json.items()) keys.push_back(key);
  EXPECT_EQ(keys, FragmentCounterNames());
  EXPECT_EQ(json["fragments/evictions"], 7);
}

TEST(CliEqaaTrace, JsonAndTextCarryEveryEventField) {
  cli::RasterCommandOptions options;
  options.samples = 8;
  options.depthSamples = 4;
  options.fragments = 2;
  options.traced = {{1, 0}};
  fmask::EqaaSurface surface(2, 2, options.Eqaa(), fmask::PolicyByName("hraa"),
                             fmask::InitialState::Cleared, cli::kClearColour);
  surface.TracePixels(options.traced);
  raster::QuadFragment quad = Quad(0, 0, 5, {{1, 0}, {1, 1}, {1, 2}, {1, 3}});
  quad.depthExact = quad.passed;
  fmask::FragmentCounters counters;
  const fmask::Colour red{1.0f, 0.0f, 0.0f, 1.0f};
  surface.Update(quad, {red, red, red, red}, counters);
  ASSERT_EQ(surface.Trace().size(), 1u);

  const nlohmann::ordered_json json = cli::TraceJson(options, surface);
  EXPECT_EQ(json["eqaa"], "8S/4Z/2F");
  EXPECT_EQ(json["unknown_code"], 2);
  ASSERT_EQ(json["events"].size(), 1u);
  const nlohmann::ordered_json& event = json["events"][0];
  std::vector<std::string> keys;
  for (const auto& [key, value] : event.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"pixel", "primitive", "colour", "covered", "passed",
                                            "exact", "slots_before", "fmask_before",
                                            "codes_before", "victim", "slot", "slots_after",
                                            "fmask_after", "codes_after", "causes_after",
                                            "steps"}));
  EXPECT_EQ(event["pixel"], nlohmann::ordered_json::parse("[1, 0]"));
  EXPECT_EQ(event["primitive"], 5);
  EXPECT_EQ(event["covered"], nlohmann::ordered_json::parse("[0, 1, 2, 3]"));
  EXPECT_EQ(event["fmask_before"], "0x0000");  // FMASK16_S8_F2: 4 hex digits, cleared
  EXPECT_EQ(event["codes_before"], nlohmann::ordered_json::parse("[0, 0, 0, 0, 0, 0, 0, 0]"));
  EXPECT_EQ(event["slots_before"][0]["primitive"], nullptr);  // the clear colour
  EXPECT_EQ(event["slots_before"][0]["colour"], nlohmann::ordered_json::parse("[0, 0, 0, 1]"));
  EXPECT_EQ(event["causes_after"].size(), 8u);

  const std::string text = cli::TraceText(options, surface);
  EXPECT_NE(text.find("FMASK16_S8_F2"), std::string::npos) << text;
  EXPECT_NE(text.find("event 0: pixel (1, 0), primitive 5"), std::string::npos) << text;
  EXPECT_NE(text.find("samples covered 0,1,2,3"), std::string::npos) << text;
  EXPECT_NE(text.find("before fmask 0x0000  codes 0 0 0 0 0 0 0 0"), std::string::npos) << text;
}

}  // namespace
