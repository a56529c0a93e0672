// `aasim post` end to end on PNG and OpenEXR images the tests write: the copy pass gives back an
// 8-bit sRGB image byte for byte and an OpenEXR image value for value, the demo pass writes its
// layers, both strategies write the identical image, the same image through `aasim frame` and
// `aasim post` gives the same pass output and counters, and every bad image, depth file or
// setting is refused with one stderr line naming it while a previous result in the output
// directory survives untouched. Also the input check, in process, on a pass that reads depth.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <stb_image.h>
#include <nlohmann/json.hpp>

#include "cli/image_io.h"
#include "cli/post_options.h"
#include "cli_test_util.h"
#include "passes/registry.h"

namespace {

namespace fs = std::filesystem;

using cli::testing::BadInput;
using cli::testing::CommandResult;
using cli::testing::ExrChannelNames;
using cli::testing::FilesIn;
using cli::testing::ReadExrChannels;
using cli::testing::ReadText;
using cli::testing::RunAasim;
using cli::testing::WriteFile;

constexpr int kPostWidth = 24, kPostHeight = 16;

struct Png {
  int width = 0, height = 0, channels = 0;
  std::vector<std::uint8_t> pixels;
};

// Every code 0..255 appears in every channel; a bright square on a dark ground gives the demo
// edges.
Png TestPng(int channels) {
  Png png{kPostWidth, kPostHeight, channels, {}};
  for (int y = 0; y < kPostHeight; ++y) {
    for (int x = 0; x < kPostWidth; ++x) {
      const int i = y * kPostWidth + x;
      const bool square = x >= 8 && x < 16 && y >= 4 && y < 12;
      png.pixels.push_back(static_cast<std::uint8_t>(square ? 200 + i % 56 : i % 256));
      png.pixels.push_back(static_cast<std::uint8_t>(255 - i % 256));
      png.pixels.push_back(static_cast<std::uint8_t>((i * 7) % 256));
      if (channels == 4) png.pixels.push_back(static_cast<std::uint8_t>((i * 13) % 256));
    }
  }
  return png;
}

fs::path Write(const fs::path& path, const Png& png) {
  cli::WritePng(path, png.width, png.height, png.channels, png.pixels);
  return path;
}

Png ReadPng(const fs::path& path) {
  Png png;
  stbi_uc* data = stbi_load(path.c_str(), &png.width, &png.height, &png.channels, 0);
  if (data == nullptr) return png;
  png.pixels.assign(data, data + std::size_t(png.width) * std::size_t(png.height) * std::size_t(png.channels));
  stbi_image_free(data);
  return png;
}

using Planes = std::map<std::string, std::vector<float>>;

// Linear colour with values above 1 and below the 8-bit sRGB step, so nothing but a float path
// keeps them.
Planes TestPlanes(int width = kPostWidth, int height = kPostHeight) {
  Planes planes;
  for (const char* name : {"R", "G", "B"}) planes[name].resize(std::size_t(width) * std::size_t(height));
  for (std::size_t i = 0; i < planes["R"].size(); ++i) {
    planes["R"][i] = 0.001f * float(i);
    planes["G"][i] = 1.0f / float(i + 3);
    planes["B"][i] = i % 5 == 0 ? 2.5f : 0.25f;
  }
  return planes;
}

fs::path WriteExr(const fs::path& path, const Planes& planes, int width = kPostWidth, int height = kPostHeight) {
  std::vector<cli::ExrChannel> channels;
  for (const auto& [name, values] : planes) channels.push_back({name, values});
  cli::WriteExr(path, width, height, channels);
  return path;
}

std::vector<std::string> Post(const std::string& pass, const fs::path& input, const fs::path& out,
                              std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"post", "--pass", pass, "--input", input.string(), "--out", out.string(),
                                "--threads", "2"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

nlohmann::json Report(const fs::path& out) { return nlohmann::json::parse(ReadText(out / "report.json")); }

class CliPostTest : public cli::testing::ScratchDirTest {};

TEST_F(CliPostTest, CopyGivesBackAnRgbPngByteForByte) {
  const Png input = TestPng(3);
  const fs::path out = scratch_ / "out";
  const CommandResult run = RunAasim(Post("copy", Write(scratch_ / "in.png", input), out), scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const Png output = ReadPng(out / "output.png");
  EXPECT_EQ(output.channels, 3);
  EXPECT_EQ(output.pixels, input.pixels);
  const Planes exr = ReadExrChannels(out / "output.exr");
  EXPECT_EQ(ExrChannelNames(out / "output.exr"), (std::vector<std::string>{"A", "B", "G", "R"}));
  EXPECT_TRUE(std::all_of(exr.at("A").begin(), exr.at("A").end(), [](float a) { return a == 1.0f; }));
  for (const char* file : {"dispatches.json", "dispatches.csv", "report.json", "heat"}) {
    EXPECT_TRUE(fs::exists(out / file)) << file;
  }
  const nlohmann::json report = Report(out);
  EXPECT_EQ(report["schema"], "aasim.post");
  EXPECT_EQ(report["input"]["format"], "png");
  EXPECT_EQ(report["input"]["alpha"], false);
  EXPECT_EQ(report["work_items"], kPostWidth * kPostHeight);
  EXPECT_EQ(report["layers"].size(), 0u);
}

TEST_F(CliPostTest, CopyKeepsAlpha) {
  const Png input = TestPng(4);
  const fs::path out = scratch_ / "out";
  const CommandResult run = RunAasim(Post("copy", Write(scratch_ / "in.png", input), out), scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const Png output = ReadPng(out / "output.png");
  EXPECT_EQ(output.channels, 4);
  EXPECT_EQ(output.pixels, input.pixels);
  EXPECT_EQ(Report(out)["input"]["alpha"], true);
}

TEST_F(CliPostTest, CopyGivesBackAnExrValueForValue) {
  const Planes input = TestPlanes();
  const fs::path out = scratch_ / "out";
  const CommandResult run = RunAasim(Post("copy", WriteExr(scratch_ / "in.exr", input), out), scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const Planes output = ReadExrChannels(out / "output.exr");
  for (const char* name : {"R", "G", "B"}) EXPECT_EQ(output.at(name), input.at(name)) << name;
  const Png png = ReadPng(out / "output.png");
  ASSERT_EQ(png.pixels.size(), input.at("R").size() * 3);
  for (std::size_t i = 0; i < input.at("R").size(); ++i) {
    EXPECT_EQ(png.pixels[i * 3], cli::EncodeSrgb8(input.at("R")[i])) << i;
    EXPECT_EQ(png.pixels[i * 3 + 2], cli::EncodeSrgb8(input.at("B")[i])) << i;
  }
  EXPECT_EQ(Report(out)["input"]["format"], "exr");
}

TEST_F(CliPostTest, DemoWritesItsLayersAndComparesTheStrategies) {
  const fs::path out = scratch_ / "out";
  const CommandResult run = RunAasim(Post("demo", Write(scratch_ / "in.png", TestPng(3)), out), scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const Png edges = ReadPng(out / "edges.png");
  EXPECT_EQ(edges.channels, 1);
  EXPECT_EQ(edges.width, kPostWidth);
  EXPECT_EQ(ExrChannelNames(out / "edges.exr"), std::vector<std::string>{"Y"});
  const std::vector<float> mask = ReadExrChannels(out / "edges.exr").at("Y");
  for (std::size_t i = 0; i < mask.size(); ++i) EXPECT_EQ(edges.pixels[i], mask[i] == 1.0f ? 255 : 0) << i;
  const nlohmann::json report = Report(out);
  EXPECT_EQ(report["pass"]["name"], "demo");
  EXPECT_EQ(report["pass"]["settings"]["threshold"], 0.1);
  EXPECT_EQ(report["written_strategy"], "stencil");
  ASSERT_EQ(report["strategies"].size(), 2u);
  EXPECT_EQ(report["strategies"][1]["strategy"], "queue");
  EXPECT_EQ(report["comparison"]["identical"], true);
  EXPECT_GT(report["work_items"].get<int>(), 0);
  EXPECT_EQ(report["layers"][0]["name"], "edges");
  EXPECT_NE(run.out.find("stencil vs queue: demo/blend"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("identical output: yes"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("of the stencil run"), std::string::npos) << run.out;
}

TEST_F(CliPostTest, EachStrategyAloneWritesTheIdenticalImage) {
  const fs::path input = Write(scratch_ / "in.png", TestPng(3));
  for (const char* strategy : {"stencil", "queue"}) {
    const CommandResult run =
        RunAasim(Post("demo", input, scratch_ / strategy, {"--strategy", strategy}), scratch_);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(Report(scratch_ / strategy)["written_strategy"], strategy);
    EXPECT_TRUE(Report(scratch_ / strategy)["comparison"].is_null());
  }
  for (const char* file : {"output.png", "output.exr", "edges.png", "edges.exr"}) {
    EXPECT_EQ(ReadText(scratch_ / "stencil" / file), ReadText(scratch_ / "queue" / file)) << file;
  }
}

TEST_F(CliPostTest, SettingsReachThePass) {
  const fs::path input = Write(scratch_ / "in.png", TestPng(3));
  ASSERT_EQ(RunAasim(Post("demo", input, scratch_ / "low", {"--set", "threshold=0.01"}), scratch_).exitCode, 0);
  ASSERT_EQ(RunAasim(Post("demo", input, scratch_ / "high", {"--set", "threshold=0.9"}), scratch_).exitCode, 0);
  EXPECT_EQ(Report(scratch_ / "low")["pass"]["settings"]["threshold"], 0.01);
  EXPECT_GT(Report(scratch_ / "low")["work_items"].get<int>(), Report(scratch_ / "high")["work_items"].get<int>());
}

TEST_F(CliPostTest, CountersDoNotDependOnTheThreadCount) {
  const fs::path input = Write(scratch_ / "in.png", TestPng(3));
  ASSERT_EQ(RunAasim(Post("demo", input, scratch_ / "one", {"--threads", "1"}), scratch_).exitCode, 0);
  ASSERT_EQ(RunAasim(Post("demo", input, scratch_ / "two", {"--threads", "2"}), scratch_).exitCode, 0);
  EXPECT_EQ(ReadText(scratch_ / "one" / "dispatches.csv"), ReadText(scratch_ / "two" / "dispatches.csv"));
  EXPECT_EQ(ReadText(scratch_ / "one" / "output.exr"), ReadText(scratch_ / "two" / "output.exr"));
}

TEST_F(CliPostTest, DepthIsReadFromTheFirstOfZYR) {
  const fs::path input = Write(scratch_ / "in.png", TestPng(3));
  Planes depth{{"Y", std::vector<float>(kPostWidth * kPostHeight, 0.5f)}, {"R", std::vector<float>(kPostWidth * kPostHeight, 0.25f)}};
  const fs::path out = scratch_ / "out";
  const CommandResult run =
      RunAasim(Post("copy", input, out, {"--depth", WriteExr(scratch_ / "d.exr", depth).string()}), scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(Report(out)["input"]["depth_channel"], "Y");
  EXPECT_NE(run.out.find("channel Y"), std::string::npos) << run.out;
}

// The rendered frame's colour, saved as OpenEXR and run through `aasim post`, gives what
// `aasim frame --post` gave: the same images and the same counters for every pass dispatch.
TEST_F(CliPostTest, AFrameThroughPostGivesWhatFrameGave) {
  const fs::path frame = scratch_ / "frame";
  const CommandResult rendered = RunAasim({"frame", "--width", "64", "--height", "48", "--threads", "2", "--out",
                                           frame.string()},
                                          scratch_);
  ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
  Planes colour = ReadExrChannels(frame / "frame.exr");
  const Planes rgb{{"R", colour.at("R")}, {"G", colour.at("G")}, {"B", colour.at("B")}};
  const fs::path out = scratch_ / "out";
  const CommandResult run = RunAasim(Post("demo", WriteExr(scratch_ / "in.exr", rgb, 64, 48), out), scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  for (const char* file : {"output.png", "edges.png"}) {
    EXPECT_EQ(ReadText(out / file), ReadText(frame / "post" / "stencil" / file)) << file;
  }
  const nlohmann::json framed = nlohmann::json::parse(ReadText(frame / "dispatches.json"))["dispatches"];
  nlohmann::json passDispatches = nlohmann::json::array();
  for (const nlohmann::json& dispatch : framed) {
    if (!dispatch["pass"].is_null()) passDispatches.push_back(dispatch);
  }
  const nlohmann::json posted = nlohmann::json::parse(ReadText(out / "dispatches.json"))["dispatches"];
  ASSERT_EQ(posted.size(), passDispatches.size());
  for (std::size_t i = 0; i < posted.size(); ++i) {
    for (const char* key : {"name", "strategy", "counters", "resources", "time_estimate_us"}) {
      EXPECT_EQ(posted[i][key], passDispatches[i][key]) << i << " " << key;
    }
  }
}

TEST_F(CliPostTest, HelpListsThePassesWithTheirSettingsFromTheRegistry) {
  const CommandResult run = RunAasim({"post", "--help"}, scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  // `aasim passes` lists the passes, then the resolves, which `aasim post` does not run.
  const CommandResult passes = RunAasim({"passes"}, scratch_);
  const std::string passList = passes.out.substr(0, passes.out.find("\nResolves of the EQAA surface"));
  EXPECT_NE(run.out.find(passList), std::string::npos) << run.out;
  for (const std::string& name : passes::PassNames()) EXPECT_NE(run.out.find(name + ": "), std::string::npos) << name;
  for (const char* option : {"--pass", "--preset", "--set", "--input", "--depth", "--strategy", "--gpu", "--threads",
                             "--out", "RenderDoc", "Z, Y or R", "first strategy run (stencil with both)"}) {
    EXPECT_NE(run.out.find(option), std::string::npos) << option;
  }
}

// --- Refusals: exit code, one stderr line naming the input, a previous result intact. ---

// A PNG's IHDR: width at byte 16, height at 20, bit depth at 24 (stb_image does not check CRCs).
std::string PatchedPng(const fs::path& path, std::uint32_t width, std::uint32_t height, int bitDepth = 8) {
  Write(path, TestPng(3));
  std::string bytes = ReadText(path);
  for (int i = 0; i < 4; ++i) {
    bytes[16 + i] = static_cast<char>(width >> (24 - 8 * i));
    bytes[20 + i] = static_cast<char>(height >> (24 - 8 * i));
  }
  bytes[24] = static_cast<char>(bitDepth);
  WriteFile(path, bytes);
  return path.string();
}

std::string Truncated(const fs::path& path, std::size_t keep) {
  WriteFile(path, ReadText(path).substr(0, keep));
  return path.string();
}

using Args = std::function<std::vector<std::string>(const fs::path& scratch)>;

Args Input(std::function<std::string(const fs::path&)> make) {
  return [make](const fs::path& scratch) { return std::vector<std::string>{"--input", make(scratch)}; };
}

Args Depth(std::function<std::string(const fs::path&)> make) {
  return [make](const fs::path& scratch) {
    return std::vector<std::string>{"--input", Write(scratch / "in.png", TestPng(3)).string(), "--depth",
                                    make(scratch)};
  };
}

Args Options(std::vector<std::string> options) {
  return [options](const fs::path& scratch) {
    std::vector<std::string> args{"--input", Write(scratch / "in.png", TestPng(3)).string()};
    args.insert(args.end(), options.begin(), options.end());
    return args;
  };
}

std::vector<BadInput> PostBadInputs() {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  return {
      {"MissingFile", Input([](const fs::path& s) { return (s / "nosuch.png").string(); }), "nosuch.png",
       "no such file", 1},
      {"Directory", Input([](const fs::path& s) { return s.string(); }), "aasim_cli", "not a regular file", 1},
      {"NotAnImage", Input([](const fs::path& s) { return WriteFile(s / "t.png", "hello").string(); }), "t.png",
       "not a PNG or OpenEXR file", 1},
      {"Jpeg", Input([](const fs::path& s) { return WriteFile(s / "t.jpg", "\xFF\xD8\xFF\xE0 jfif").string(); }),
       "t.jpg", "not a PNG or OpenEXR file", 1},
      {"TruncatedPng",
       Input([](const fs::path& s) { return Truncated(Write(s / "t.png", TestPng(3)), 60); }), "t.png",
       "cannot decode", 1},
      {"EmptyPng", Input([](const fs::path& s) { return PatchedPng(s / "e.png", 0, 0); }), "e.png", "image size 0x0 is empty", 1},
      {"PngOverTheSideLimit", Input([](const fs::path& s) { return PatchedPng(s / "big.png", 20000, 4); }),
       "big.png", "exceeds 16384 texels on a side", 1},
      {"PngOverTheMemoryLimit", Input([](const fs::path& s) { return PatchedPng(s / "big.png", 8000, 8000); }),
       "big.png", "over the 4.0 GiB limit", 1},
      {"SixteenBitPng", Input([](const fs::path& s) { return PatchedPng(s / "w.png", kPostWidth, kPostHeight, 16); }),
       "w.png", "16 bits per channel", 1},
      {"ExrWithoutBlue",
       Input([](const fs::path& s) {
         Planes planes = TestPlanes();
         planes.erase("B");
         return WriteExr(s / "rg.exr", planes).string();
       }),
       "rg.exr", "OpenEXR channels G, R; a colour image needs R, G and B", 1},
      {"TruncatedExr",
       Input([](const fs::path& s) {
         const fs::path path = WriteExr(s / "t.exr", TestPlanes());
         return Truncated(path, fs::file_size(path) - 40);
       }),
       "t.exr", "OpenEXR", 1},
      {"ExrHeaderOnly",
       Input([](const fs::path& s) { return Truncated(WriteExr(s / "t.exr", TestPlanes()), 20); }), "t.exr",
       "cannot read OpenEXR", 1},
      {"ExrOverTheSideLimit",
       Input([](const fs::path& s) {
         return WriteExr(s / "wide.exr", {{"R", std::vector<float>(16385)}, {"G", std::vector<float>(16385)},
                                          {"B", std::vector<float>(16385)}},
                         16385, 1)
             .string();
       }),
       "wide.exr", "16384", 1},
      {"ExrNotFinite",
       Input([nan](const fs::path& s) {
         Planes planes = TestPlanes();
         planes["G"][kPostWidth * 2 + 3] = nan;
         return WriteExr(s / "nan.exr", planes).string();
       }),
       "nan.exr", "channel G of pixel (3, 2) is nan", 1},
      {"DepthWrongSize",
       Depth([](const fs::path& s) { return WriteExr(s / "d.exr", {{"Z", std::vector<float>(8 * 4)}}, 8, 4).string(); }),
       "d.exr", "depth is 8x4, the image", 1},
      {"DepthWithoutADepthChannel",
       Depth([](const fs::path& s) {
         return WriteExr(s / "d.exr", {{"depth", std::vector<float>(kPostWidth * kPostHeight)}}).string();
       }),
       "d.exr", "channels depth; depth is read from a channel named Z, Y or R", 1},
      {"DepthNotFinite",
       Depth([](const fs::path& s) {
         std::vector<float> z(kPostWidth * kPostHeight, 0.5f);
         z[5] = std::numeric_limits<float>::infinity();
         return WriteExr(s / "d.exr", {{"Z", z}}).string();
       }),
       "d.exr", "channel Z of pixel (5, 0) is inf", 1},
      {"DepthAsPng", Depth([](const fs::path& s) { return Write(s / "d.png", TestPng(3)).string(); }), "d.png",
       "not an OpenEXR file", 1},
      {"UnknownPass", Options({"--pass", "nosuch"}), "--pass nosuch", "unknown post pass 'nosuch' (passes: demo", 2},
      {"PresetOfAPassWithout", Options({"--preset", "high"}), "--preset high", "pass demo has no presets", 2},
      {"UnknownSetting", Options({"--set", "speed=1"}), "--set speed=1",
       "unknown setting 'speed' (settings: threshold)", 2},
      {"SettingOutOfRange", Options({"--set", "threshold=2"}), "--set threshold=2", "threshold=2 outside (0, 1]", 2},
      {"SettingNotANumber", Options({"--set", "threshold=high"}), "--set threshold=high", "not a finite decimal", 2},
      {"SettingWithoutValue", Options({"--set", "threshold"}), "--set threshold", "is not key=value", 2},
      {"SettingTwice", Options({"--set", "threshold=0.2", "--set", "threshold=0.3"}), "--set threshold=0.3",
       "threshold is given twice", 2},
      {"SetTakesOneValue", Options({"--set", "threshold=0.2", "threshold=0.3"}), "threshold=0.3", "not expected", 2},
      {"UnknownStrategy", Options({"--strategy", "foo"}), "--strategy", "foo not in", 2},
      {"UnknownGpu", Options({"--gpu", "nosuch"}), "nosuch", "built-in GPUs", 1},
  };
}

class CliPostBadInputTest : public cli::testing::ScratchDirTest, public ::testing::WithParamInterface<BadInput> {};

// Every file under `dir` (hidden ones included) with its bytes.
std::map<std::string, std::string> PostSnapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    files[fs::relative(entry.path(), dir).string()] = entry.is_regular_file() ? ReadText(entry.path()) : "";
  }
  return files;
}

TEST_P(CliPostBadInputTest, FailsWithOneLineNamingTheInputAndKeepsThePreviousResult) {
  const fs::path out = scratch_ / "out";
  const fs::path good = Write(scratch_ / "good.png", TestPng(3));
  ASSERT_EQ(RunAasim(Post("demo", good, out), scratch_).exitCode, 0);
  const std::map<std::string, std::string> before = PostSnapshot(out);

  const BadInput& input = GetParam();
  std::vector<std::string> args{"post", "--pass", "demo", "--out", out.string()};
  const std::vector<std::string> extra = input.args(scratch_);
  args.insert(args.end(), extra.begin(), extra.end());
  const CommandResult run = RunAasim(args, scratch_);
  EXPECT_EQ(run.exitCode, input.exitCode) << run.err;
  ASSERT_FALSE(run.err.empty());
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_NE(run.err.find(input.named), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(input.reason), std::string::npos) << run.err;
  EXPECT_EQ(run.err.rfind(input.exitCode == 2 ? "aasim post: " : "aasim: ", 0), 0u) << run.err;
  EXPECT_TRUE(PostSnapshot(out) == before) << run.err;
}

INSTANTIATE_TEST_SUITE_P(CliPost, CliPostBadInputTest, ::testing::ValuesIn(PostBadInputs()),
                         [](const auto& param) { return param.param.name; });

TEST_F(CliPostTest, ABadImageIntoANewDirectoryCreatesNothing) {
  const fs::path out = scratch_ / "new";
  const CommandResult run = RunAasim(Post("copy", WriteFile(scratch_ / "x.png", "x"), out), scratch_);
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_FALSE(fs::exists(out));
}

// --- The input check, in process: no registered pass reads depth yet. ---

passes::PassInfo Reading(std::vector<passes::FrameInput> inputs) {
  passes::PassInfo info;
  info.name = "deep";
  info.inputs = std::move(inputs);
  return info;
}

std::string Refusal(const passes::PassInfo& info, bool haveDepth, bool haveVelocity = false) {
  try {
    cli::CheckPostInputs(info, haveDepth, haveVelocity);
  } catch (const CLI::ValidationError& error) {
    return error.what();
  }
  return "";
}

TEST(CliPostInputs, APassReadingDepthNeedsTheDepthOption) {
  const passes::PassInfo info = Reading({passes::FrameInput::Colour, passes::FrameInput::Depth});
  EXPECT_EQ(Refusal(info, false), "--pass deep reads a depth buffer: give it with --depth");
  EXPECT_EQ(Refusal(info, true), "");
}

TEST(CliPostInputs, InputsOnlyAFrameHasAreRefusedWithWhereToGetThem) {
  for (const passes::FrameInput input : {passes::FrameInput::Normal, passes::FrameInput::ObjectId,
                                         passes::FrameInput::Eqaa}) {
    const std::string refusal = Refusal(Reading({passes::FrameInput::Colour, input}), true);
    EXPECT_NE(refusal.find("only a rendered frame has: run it with aasim frame --post deep"), std::string::npos)
        << refusal;
  }
}

TEST(CliPostInputs, APassReadingVelocitiesNeedsTheVelocityOption) {
  const passes::PassInfo info = Reading({passes::FrameInput::Colour, passes::FrameInput::Velocity});
  EXPECT_EQ(Refusal(info, true, false), "--pass deep reads velocities: give it with --velocity");
  EXPECT_EQ(Refusal(info, true, true), "");
}

// The test PNG moved `shift` pixels right (wrapping), as a panning camera would show it.
Png ShiftedPng(int shift) {
  const Png base = TestPng(3);
  Png png = base;
  for (int y = 0; y < kPostHeight; ++y) {
    for (int x = 0; x < kPostWidth; ++x) {
      const int from = (y * kPostWidth + (x - shift + kPostWidth) % kPostWidth) * 3;
      for (int c = 0; c < 3; ++c) png.pixels[std::size_t((y * kPostWidth + x) * 3 + c)] = base.pixels[std::size_t(from + c)];
    }
  }
  return png;
}

fs::path WriteVelocity(const fs::path& path, float vx) {
  Planes planes;
  planes["R"].assign(std::size_t(kPostWidth) * kPostHeight, vx);
  planes["G"].assign(std::size_t(kPostWidth) * kPostHeight, 0.0f);
  return WriteExr(path, planes);
}

// Three frames through `copy`: each frame's outputs in frame-NNN/, the same bytes as its input,
// one dispatch log labelled by frame, and report.json listing the frames with their velocity files.
TEST_F(CliPostTest, ASequenceRunsFrameByFrameAndWritesEachFramesOutputs) {
  std::vector<std::string> extra;
  for (int k = 0; k < 3; ++k) {
    const std::string n = std::to_string(k);
    extra.insert(extra.end(), {"--input", Write(scratch_ / ("f" + n + ".png"), ShiftedPng(k)).string(), "--velocity",
                               WriteVelocity(scratch_ / ("v" + n + ".exr"), 1.0f).string()});
  }
  std::vector<std::string> args{"post", "--pass", "copy", "--out", (scratch_ / "out").string(), "--threads", "2"};
  args.insert(args.end(), extra.begin(), extra.end());
  const CommandResult run = RunAasim(args, scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = Report(scratch_ / "out");
  ASSERT_EQ(report["frames"].size(), 3u);
  for (int k = 0; k < 3; ++k) {
    char folder[32];
    std::snprintf(folder, sizeof folder, "frame-%03d", k);
    EXPECT_EQ(ReadPng(scratch_ / "out" / folder / "output.png").pixels, ShiftedPng(k).pixels) << folder;
    const nlohmann::json& frame = report["frames"][std::size_t(k)];
    EXPECT_EQ(frame["input"]["velocity"], (scratch_ / ("v" + std::to_string(k) + ".exr")).string());
    EXPECT_TRUE(frame["comparison"]["identical"].get<bool>());
  }
  EXPECT_EQ(report["jitter"], "none");
  const nlohmann::json dispatches = nlohmann::json::parse(ReadText(scratch_ / "out" / "dispatches.json"));
  EXPECT_NE(ReadText(scratch_ / "out" / "dispatches.csv").find("frame 2"), std::string::npos);
  EXPECT_EQ(dispatches["configuration"]["input"].size(), 3u);
}

TEST_F(CliPostTest, ASequenceRefusesMismatchedFilesWithOneLineAndNoOutput) {
  const fs::path a = Write(scratch_ / "a.png", TestPng(3));
  const fs::path v = WriteVelocity(scratch_ / "v.exr", 0.0f);
  const CommandResult counts = RunAasim({"post", "--pass", "copy", "--input", a.string(), "--input", a.string(),
                                         "--velocity", v.string(), "--out", (scratch_ / "out").string()},
                                        scratch_);
  EXPECT_EQ(counts.exitCode, 2);
  EXPECT_NE(counts.err.find("--velocity: given 1 times for 2 --input images"), std::string::npos) << counts.err;
  Png small = TestPng(3);
  small.width = kPostWidth / 2;
  small.pixels.resize(std::size_t(small.width) * kPostHeight * 3);
  const fs::path b = Write(scratch_ / "b.png", small);
  const CommandResult sizes =
      RunAasim({"post", "--pass", "copy", "--input", a.string(), "--input", b.string(), "--out", (scratch_ / "out").string()},
               scratch_);
  EXPECT_EQ(sizes.exitCode, 1);
  EXPECT_NE(sizes.err.find(b.string() + ": 12x16, the first image " + a.string() + " is 24x16"), std::string::npos)
      << sizes.err;
  EXPECT_EQ(std::count(sizes.err.begin(), sizes.err.end(), '\n'), 1) << sizes.err;
  EXPECT_FALSE(fs::exists(scratch_ / "out"));
  // A velocity file without R and G (or X and Y) names its channels.
  Planes depthOnly;
  depthOnly["Z"].assign(std::size_t(kPostWidth) * kPostHeight, 0.5f);
  const fs::path z = WriteExr(scratch_ / "z.exr", depthOnly);
  const CommandResult channels = RunAasim({"post", "--pass", "copy", "--input", a.string(), "--input", a.string(),
                                           "--velocity", z.string(), "--velocity", z.string(), "--out",
                                           (scratch_ / "out").string()},
                                          scratch_);
  EXPECT_EQ(channels.exitCode, 1);
  EXPECT_NE(channels.err.find(z.string() + ": OpenEXR channels Z; velocity is read from channels R and G, or X and Y"),
            std::string::npos)
      << channels.err;
  EXPECT_FALSE(fs::exists(scratch_ / "out"));
}

}  // namespace
