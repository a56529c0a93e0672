// `aasim run`, the main job, end to end on a small frame: every output of the set is written and
// consistent (report.json against counters.csv and quality.csv, EXR layers, the strategies'
// identical images), anti-aliasing measurably improves on the aliased frame, the report loads in
// headless Chromium with no console errors and every image decoded, results do not depend on
// the thread count, and every bad input fails with one stderr line and no output directory.

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "browser_check.h"
#include "cli/run_options.h"
#include "cli/study_report.h"
#include "cli_test_util.h"
#include "passes/registry.h"
#include "passes/resolve.h"

namespace {

namespace fs = std::filesystem;

using cli::testing::BadInput;
using cli::testing::CommandResult;
using cli::testing::ExpectRefused;
using cli::testing::ExrChannelNames;
using cli::testing::ReadText;
using cli::testing::RunAasim;
using cli::testing::WriteFile;

// The default --modes, by name.
const std::vector<std::string> kRunModes = [] {
  std::vector<std::string> names;
  for (const fmask::EqaaConfig& mode : cli::ParseEqaaModes(cli::kDefaultModes)) names.push_back(fmask::EqaaName(mode));
  return names;
}();

std::vector<std::string> SmallStudyRun(const fs::path& scratch, const fs::path& out, const std::string& threads) {
  return {"run",       "--quick", "--width",   "160",   "--height",         "96",
          "--gt-samples", "16",   "--threads", threads, "--cache",          (scratch / "cache").string(),
          "--progress", "never",  "--out",     out.string(), "--lut-configurations", "20000"};
}

// `--post all` with the default modes: every registered pass those frames feed (SMAA S2x needs a
// 2S frame and is left out).
std::vector<std::string> PassesTheDefaultModesFeed() {
  const std::vector<fmask::EqaaConfig> modes = cli::ParseEqaaModes(cli::kDefaultModes);
  std::vector<std::string> names;
  for (const passes::RegisteredPass& pass : passes::AllPasses()) {
    const int samples = pass.info().eqaaSamples;
    const bool fed = samples == 0 || std::any_of(modes.begin(), modes.end(), [&](const fmask::EqaaConfig& mode) {
                       return mode.coverageSamples == samples;
                     });
    if (fed) names.emplace_back(pass.info().name);
  }
  return names;
}

std::size_t CountLines(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

// One small run shared by the tests that only read its outputs.
class CliRunTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new fs::path(fs::temp_directory_path() / ("aasim_cli_run_" + std::to_string(::getpid())));
    fs::remove_all(*scratch_);
    fs::create_directories(*scratch_);
    run_ = new CommandResult(RunAasim(SmallStudyRun(*scratch_, Out(), "2"), *scratch_));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*scratch_);
    delete scratch_;
    delete run_;
  }
  static fs::path Out() { return *scratch_ / "out"; }
  static nlohmann::json Report() { return nlohmann::json::parse(ReadText(Out() / "report.json")); }

  static fs::path* scratch_;
  static CommandResult* run_;
};
fs::path* CliRunTest::scratch_ = nullptr;
CommandResult* CliRunTest::run_ = nullptr;

TEST_F(CliRunTest, SucceedsAndEndsWithTheReportPath) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  const std::string last = "report: " + (Out() / "report.html").string() + "\n";
  ASSERT_GE(run_->out.size(), last.size());
  EXPECT_EQ(run_->out.substr(run_->out.size() - last.size()), last) << run_->out;
  EXPECT_NE(run_->out.find("identical output: yes"), std::string::npos) << run_->out;
  EXPECT_TRUE(run_->err.empty()) << "--progress never must keep stderr quiet: " << run_->err;
}

TEST_F(CliRunTest, WritesTheWholeOutputSetWithNamedExrLayers) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  for (const char* file : {"report.html", "report.json", "counters.csv", "quality.csv", "images/ground-truth/colour.png",
                           "images/ground-truth/edges.png", "images/passes/demo/output.png",
                           "images/passes/demo/flip.png", "images/passes/demo/stencil/edges.png",
                           "images/passes/demo/queue/edges.png"}) {
    EXPECT_TRUE(fs::is_regular_file(Out() / file)) << file;
  }
  using Names = std::vector<std::string>;
  const auto sorted = [](Names names) {
    std::sort(names.begin(), names.end());
    return names;
  };
  EXPECT_EQ(sorted(ExrChannelNames(Out() / "images/ground-truth/ground-truth.exr")),
            sorted({"R", "G", "B", "coverage", "edge"}));
  for (const fmask::EqaaConfig& mode : cli::ParseEqaaModes(cli::kDefaultModes)) {
    const std::string slug = study::ModeSlug(mode);
    const fs::path folder = Out() / "images/frames" / slug;
    const Names frame = ExrChannelNames(folder / "frame.exr");
    for (const char* layer : {"R", "depth", "normal.X", "objectId", "velocity.Y"}) {
      EXPECT_NE(std::find(frame.begin(), frame.end(), layer), frame.end()) << slug << " " << layer;
    }
    const Names eqaa = ExrChannelNames(folder / "eqaa.exr");
    EXPECT_NE(std::find(eqaa.begin(), eqaa.end(), "fmask.s0"), eqaa.end()) << slug;
    EXPECT_EQ(sorted(ExrChannelNames(folder / "error.exr")), sorted({"squared_error", "ssim_error", "flip"})) << slug;
    for (const char* png : {"colour.png", "fmask.png", "flip.png"}) {
      EXPECT_TRUE(fs::is_regular_file(folder / png)) << slug << " " << png;
    }
  }
  // No temporary of the all-or-nothing writer is left behind.
  for (const auto& entry : fs::recursive_directory_iterator(Out())) {
    EXPECT_EQ(entry.path().filename().string().find(".aasim-tmp-"), std::string::npos) << entry.path();
  }
}

TEST_F(CliRunTest, ReportJsonAgreesWithTheCsvFiles) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  const nlohmann::json report = Report();
  EXPECT_EQ(report["schema"], cli::kReportSchema);
  EXPECT_EQ(report["version"], 1);
  EXPECT_EQ(report["configuration"]["width"], 160);
  ASSERT_EQ(report["frames"].size(), std::size(kRunModes));
  for (std::size_t i = 0; i < std::size(kRunModes); ++i) EXPECT_EQ(report["frames"][i]["mode"], kRunModes[i]);
  // --post all: every registered pass the modes feed, in registry order, each under its strategies.
  const std::vector<std::string> passNames = PassesTheDefaultModesFeed();
  ASSERT_EQ(report["passes"].size(), passNames.size());
  std::size_t passDispatches = 0;
  for (std::size_t i = 0; i < passNames.size(); ++i) {
    const nlohmann::json& pass = report["passes"][i];
    EXPECT_EQ(pass["name"], passNames[i]);
    EXPECT_EQ(pass["input_frame"], "1S/1Z/1F");
    EXPECT_TRUE(pass["strategies_identical"].get<bool>());
    for (const nlohmann::json& run : pass["strategies"]) passDispatches += run["dispatches"].size();
  }
  EXPECT_EQ(report["passes"][0]["name"], "demo");
  // The demo pass: 2 dispatches stencil-culled, 3 queued.
  EXPECT_EQ(report["passes"][0]["strategies"][0]["dispatches"].size() +
                report["passes"][0]["strategies"][1]["dispatches"].size(),
            5u);
  const nlohmann::json& dispatches = report["dispatches"]["dispatches"];
  // Per mode the material draw, the box resolve and the registered resolves reading the mode,
  // then the passes' dispatches.
  std::size_t resolveDispatches = 0;
  for (const nlohmann::json& frame : report["frames"]) resolveDispatches += frame["resolves"].size();
  ASSERT_EQ(dispatches.size(), 2 * std::size(kRunModes) + resolveDispatches + passDispatches);
  const std::string counters = ReadText(Out() / "counters.csv");
  EXPECT_EQ(counters.rfind("frame,name,kind,strategy,", 0), 0u) << counters.substr(0, 80);
  EXPECT_EQ(CountLines(counters), dispatches.size() + 1);
  for (std::size_t i = 0; i < std::size(kRunModes); ++i) {
    const nlohmann::json& draw = dispatches[report["frames"][i]["draw_dispatch"].get<std::size_t>()];
    EXPECT_EQ(draw["name"], "frame/material");
    EXPECT_EQ(draw["frame"], kRunModes[i]);
  }
  const std::string quality = ReadText(Out() / "quality.csv");
  // Header, the modes, their resolves, the 1S frame as the passes' 8-bit sRGB target holds it, the
  // passes.
  EXPECT_EQ(CountLines(quality), 1 + std::size(kRunModes) + resolveDispatches + 1 + passNames.size());
  EXPECT_NE(quality.find("\n1S/1Z/1F sRGB8,frame sRGB8,"), std::string::npos) << quality;
  EXPECT_FALSE(report["frames"][0]["srgb8"].is_null());
  EXPECT_TRUE(report["frames"][1]["srgb8"].is_null());
  EXPECT_NE(quality.find("\n16S/8Z/4F,frame,"), std::string::npos) << quality;
  EXPECT_NE(quality.find("\n8S/4Z/2F fetch,resolve,"), std::string::npos) << quality;
  // Every registered resolve that reads a mode ran on it, in registry order, as its own dispatches.
  for (std::size_t i = 0; i < std::size(kRunModes); ++i) {
    const nlohmann::json& frame = report["frames"][i];
    const fmask::EqaaConfig mode{frame["samples"].get<int>(), frame["depth_samples"].get<int>(),
                                 frame["fragments"].get<int>()};
    std::vector<std::string> expected, ran;
    for (const passes::RegisteredResolve& resolve : passes::AllResolves()) {
      if (resolve.info().reads(mode)) expected.emplace_back(resolve.info().name);
    }
    for (const nlohmann::json& resolve : frame["resolves"]) {
      ran.push_back(resolve["name"].get<std::string>());
      EXPECT_TRUE(fs::is_regular_file(Out() / resolve["folder"].get<std::string>() / "error.exr"));
      const nlohmann::json& first = dispatches[resolve["dispatches"][0].get<std::size_t>()];
      EXPECT_EQ(first["name"].get<std::string>().rfind("resolve/" + ran.back(), 0), 0u) << first["name"];
    }
    EXPECT_EQ(ran, expected) << kRunModes[i];
    EXPECT_EQ(dispatches[frame["resolve_dispatch"].get<std::size_t>()]["name"], "frame/resolve");
  }
}

// The point of the study: more samples per pixel, closer to the ground truth at the edges.
TEST_F(CliRunTest, AntiAliasingBeatsTheAliasedFrameAtEdges) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  const nlohmann::json report = Report();
  const nlohmann::json& aliased = report["frames"][0]["quality"];
  const nlohmann::json& sixteen = report["frames"][3]["quality"];
  EXPECT_GT(aliased["edge_pixels"].get<int>(), 100);
  EXPECT_LT(sixteen["edge_flip"].get<double>(), 0.75 * aliased["edge_flip"].get<double>());
  EXPECT_GT(sixteen["edge_psnr_db"].get<double>(), aliased["edge_psnr_db"].get<double>() + 3.0);
  for (const nlohmann::json& frame : report["frames"]) {
    EXPECT_GT(frame["quality"]["psnr_db"].get<double>(), 20.0) << frame["mode"];
    EXPECT_GT(frame["quality"]["ssim"].get<double>(), 0.9) << frame["mode"];
  }
}

TEST_F(CliRunTest, ReportLoadsInHeadlessChromiumWithEveryImage) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  const std::string html = ReadText(Out() / "report.html");
  int images = 0;
  for (std::size_t at = html.find("<figure><img"); at != std::string::npos; at = html.find("<figure><img", at + 1)) ++images;
  EXPECT_GT(images, 20);
  const cli::testing::BrowserCheck check = cli::testing::CheckInChromium(Out() / "report.html");
  ASSERT_TRUE(check.ran) << check.error;
  EXPECT_TRUE(check.consoleErrors.empty()) << check.consoleErrors.front();
  EXPECT_TRUE(check.loadErrors.empty()) << check.loadErrors.front();
  // The image comparer's two layers come on top of the report's figures.
  EXPECT_EQ(check.imagesTotal, images + 2);
  EXPECT_EQ(check.imagesLoaded, images + 2);
}

// The comparer offers the whole frame and every hard region, each with the ground truth, every
// frame and every pass; the pass table has a row per pass and strategy.
TEST_F(CliRunTest, ReportComparesEveryImageAndEveryPass) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  const std::string html = ReadText(Out() / "report.html");
  const nlohmann::json report = Report();
  EXPECT_NE(html.find("id='cmp-view'"), std::string::npos);
  std::size_t resolves = 0;
  for (const nlohmann::json& frame : report["frames"]) resolves += frame["resolves"].size();
  const std::size_t perGroup = 1 + std::size(kRunModes) + resolves + 1 + report["passes"].size();
  auto count = [&](const std::string& text) {
    std::size_t n = 0;
    for (std::size_t at = html.find(text); at != std::string::npos; at = html.find(text, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("data-group='whole frame'"), perGroup);
  EXPECT_EQ(count("data-group='region 1 at ("), perGroup);
  EXPECT_EQ(count("data-label='smaa on 1S/1Z/1F'") * perGroup, count("data-group='"));  // in every group
  EXPECT_NE(html.find("<h2>Passes compared</h2>"), std::string::npos);
  std::size_t runs = 0;
  for (const nlohmann::json& pass : report["passes"]) runs += pass["strategies"].size();
  const std::size_t table = html.find("<caption>Cost and quality per pass and strategy</caption>");
  ASSERT_NE(table, std::string::npos);
  const std::size_t end = html.find("</table>", table);
  std::size_t rows = 0;
  for (std::size_t at = html.find("<tr>", table); at < end; at = html.find("<tr>", at + 1)) ++rows;
  EXPECT_EQ(rows, 1 + runs);
}

TEST_F(CliRunTest, SameCountersQualityAndImagesWithOneThread) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  const fs::path one = *scratch_ / "one-thread";
  const CommandResult run = RunAasim(SmallStudyRun(*scratch_, one, "1"), *scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  for (const char* file : {"counters.csv", "quality.csv", "images/frames/8s-4z-2f/colour.png",
                           "images/frames/8s-4z-2f/eqaa.exr", "images/passes/demo/output.png"}) {
    EXPECT_EQ(ReadText(one / file), ReadText(Out() / file)) << file;
  }
  // The second run read the first run's ground truth from the cache.
  EXPECT_TRUE(nlohmann::json::parse(ReadText(one / "report.json"))["ground_truth"]["cache_hit"].get<bool>());
  EXPECT_FALSE(Report()["ground_truth"]["cache_hit"].get<bool>());
}

// The EQAA study's options: a bad name, a repeated one, the run's own policy, a table size out of
// range are usage errors (exit 2, one line naming the option) that create no output.
TEST(CliRun, BadOptionListsAndCombinationsAreUsageErrors) {
  const fs::path scratch = fs::temp_directory_path() / ("aasim_cli_run_lists_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--resolves", "craa-foo"}, "--resolves: unknown name 'craa-foo'"},
      {{"--resolves", "fetch,fetch"}, "--resolves: fetch is named twice"},
      {{"--compare-policies", "hraa"}, "--compare-policies: hraa is already the run's --policy"},
      {{"--compare-policies", "nosuch"}, "--compare-policies: unknown name 'nosuch'"},
      {{"--lut-configurations", "0"}, "--lut-configurations"},
      {{"--lut-configurations", "9999999"}, "--lut-configurations"},
      {{"--post", "smaa", "--sweep", "fxaa:threshold=0.1"}, "--sweep fxaa:threshold=0.1: fxaa is not a pass of the run"},
      {{"--sweep", "smaa:threshold=0.1,x"}, "--sweep smaa:threshold=0.1,x: 'x' is not a finite decimal"},
      {{"--sweep", "smaa"}, "--sweep smaa: expected PASS:SETTING=V1,V2,..."},
      {{"--jitter", "halton8"}, "--jitter: only a multi-frame run uses it"},
      {{"--camera-path", "orbit"}, "--camera-path: only a multi-frame run uses it"},
      {{"--sequence-post", "all"}, "--sequence-post: only a multi-frame run uses it"},
      {{"--frames", "0"}, "--frames"},
      {{"--frames", "3", "--camera-path", "spiral"}, "--camera-path"},
      {{"--frames", "3", "--jitter", "halton9"}, "--jitter"},
      {{"--frames", "3", "--fps", "0"}, "--fps"},
      {{"--frames", "3", "--velocity-buffer", "rg16"}, "--velocity-buffer"},
      {{"--frames", "3", "--post", "smaa", "--sequence-post", "fxaa"},
       "--sequence-post: fxaa is not one of the run's --post passes"}};
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"run", "--quick", "--out", (scratch / "out").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const CommandResult run = RunAasim(args, scratch);
    EXPECT_EQ(run.exitCode, 2) << extra.front();
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(scratch / "out")) << extra.front();
  }
  fs::remove_all(scratch);
}

TEST(CliRun, HelpExplainsEveryOptionAndTheDefaultJob) {
  const fs::path scratch = fs::temp_directory_path() / ("aasim_cli_run_help_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  const CommandResult run = RunAasim({"run", "--help"}, scratch);
  EXPECT_EQ(run.exitCode, 0);
  for (const char* option : {"--scene", "--width", "--height", "--quick", "--modes", "--pattern", "--policy", "--post",
                             "--gpu", "--flush", "--gt-samples", "--cache", "--no-cache", "--progress", "--threads",
                             "--out", "--resolves", "--compare-policies", "--lut-configurations"}) {
    EXPECT_NE(run.out.find(option), std::string::npos) << option;
  }
  const CommandResult top = RunAasim({"--help"}, scratch);
  EXPECT_NE(top.out.find("Without a subcommand, aasim runs `aasim run`"), std::string::npos) << top.out;
  fs::remove_all(scratch);
}

// --post with settings and --strategy reach the study: one strategy, the pass's own setting.
TEST_F(CliRunTest, PassSettingsAndOneStrategyReachTheStudy) {
  std::vector<std::string> args = SmallStudyRun(*scratch_, *scratch_ / "queue-only", "2");
  args.insert(args.end(), {"--modes", "1S/1Z/1F", "--post", "demo:threshold=0.3", "--strategy", "queue"});
  const CommandResult run = RunAasim(args, *scratch_);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(ReadText(*scratch_ / "queue-only/report.json"));
  ASSERT_EQ(report["passes"].size(), 1u);
  EXPECT_EQ(report["passes"][0]["settings"], "threshold=0.3");
  ASSERT_EQ(report["passes"][0]["strategies"].size(), 1u);
  EXPECT_EQ(report["passes"][0]["strategies"][0]["strategy"], "queue");
  EXPECT_EQ(report["configuration"]["strategy"], "queue");
  EXPECT_LT(report["passes"][0]["edge_pixels"].get<int>(), Report()["passes"][0]["edge_pixels"].get<int>());
}

// Runs `aasim ARGS` in a fresh working directory with its own cache; returns the report.
nlohmann::json RunInFreshDirectory(const std::string& args, const fs::path& scratch) {
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  const std::string command = "cd '" + scratch.string() + "' && XDG_CACHE_HOME='" + (scratch / "cache").string() +
                              "' '" + AASIM_BINARY + "' " + args + " >stdout.txt 2>stderr.txt";
  const int status = std::system(command.c_str());
  const std::string out = ReadText(scratch / "stdout.txt");
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << ReadText(scratch / "stderr.txt");
  const std::string last = "report: " + (scratch / "out/report/report.html").string() + "\n";
  EXPECT_GE(out.size(), last.size()) << out;
  if (out.size() >= last.size()) {
    EXPECT_EQ(out.substr(out.size() - last.size()), last) << out;
  }
  const nlohmann::json report = nlohmann::json::parse(ReadText(scratch / "out/report/report.json"));
  EXPECT_EQ(report["configuration"]["scene"], "builtin:default");
  EXPECT_EQ(report["frames"].size(), std::size(kRunModes));
  EXPECT_TRUE(fs::is_regular_file(scratch / "cache/aasim/ground-truth" /
                                  fs::path(report["ground_truth"]["cache_file"].get<std::string>()).filename()));
  return report;
}

// The default study at --quick size: report under the working directory, cache under
// XDG_CACHE_HOME, every pass of the registry (the full-size run is FullSize.*, label "full").
// The CRAA LUTs are fitted to fewer configurations than the generator's default: their
// generation is not what this test is about, and under the sanitizers it took most of its time.
TEST(CliRun, QuickDefaultStudyWritesItsReportUnderTheWorkingDirectory) {
  const fs::path scratch = fs::temp_directory_path() / ("aasim_cli_run_quick_" + std::to_string(::getpid()));
  const nlohmann::json report = RunInFreshDirectory("run --quick --lut-configurations 20000", scratch);
  EXPECT_EQ(report["configuration"]["width"], cli::kQuickWidth);
  EXPECT_EQ(report["configuration"]["height"], cli::kQuickHeight);
  EXPECT_EQ(report["passes"].size(), PassesTheDefaultModesFeed().size());
  fs::remove_all(scratch);
}

// A pass reading a 2-sample surface runs on the 2S frame when --modes has one, and naming it
// without one is an error.
TEST(CliRun, SmaaS2xRunsOnTheTwoSampleFrame) {
  const fs::path scratch = fs::temp_directory_path() / ("aasim_cli_run_s2x_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  std::vector<std::string> args = SmallStudyRun(scratch, scratch / "out", "2");
  args.insert(args.end(), {"--post", "smaa-s2x"});
  const CommandResult refused = RunAasim(args, scratch);
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_NE(refused.err.find("needs a frame with 2 coverage samples"), std::string::npos) << refused.err;
  args.insert(args.end(), {"--modes", "1S/1Z/1F,2S/2Z/2F", "--pattern", "standard"});
  const CommandResult run = RunAasim(args, scratch);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(ReadText(scratch / "out/report.json"));
  ASSERT_EQ(report["passes"].size(), 1u);
  EXPECT_EQ(report["passes"][0]["input_frame"], "2S/2Z/2F");
  EXPECT_TRUE(report["passes"][0]["strategies_identical"].get<bool>());
  for (const char* layer : {"edges.s0.png", "weights.s1.exr"}) {
    EXPECT_TRUE(fs::is_regular_file(scratch / "out/images/passes/smaa-s2x/queue" / layer)) << layer;
  }
  fs::remove_all(scratch);
}

// The README's first command: `aasim` alone runs the default study (built-in default scene,
// 1920x1080, 256 rays per pixel) into out/report under the working directory. Full size: behind
// the ctest label "full" (tests/CMakeLists.txt), run once in CI.
TEST(FullSize, NoArgumentsRunsTheDefaultStudy) {
  const fs::path scratch = fs::temp_directory_path() / ("aasim_cli_run_default_" + std::to_string(::getpid()));
  const nlohmann::json report = RunInFreshDirectory("", scratch);
  EXPECT_EQ(report["configuration"]["width"], 1920);
  EXPECT_EQ(report["configuration"]["height"], 1080);
  EXPECT_EQ(report["ground_truth"]["samples_per_pixel"], 256);
  EXPECT_EQ(report["passes"].size(), PassesTheDefaultModesFeed().size());
  // The memory guard's estimate covers what the run really held (RUSAGE_CHILDREN: the largest
  // resident set of the waited-for descendants, here the one aasim run).
  std::vector<passes::PassConfig> passConfigs;
  for (const std::string& name : PassesTheDefaultModesFeed()) passConfigs.push_back(passes::ResolvePass(name));
  rusage usage{};
  ASSERT_EQ(::getrusage(RUSAGE_CHILDREN, &usage), 0);
  const std::uint64_t peak = std::uint64_t(usage.ru_maxrss) * 1024u;
  EXPECT_LE(peak, cli::EstimateRunBytes(1920, 1080, cli::ParseEqaaModes(cli::kDefaultModes), passConfigs,
                                        passes::ResolveNames()));
  fs::remove_all(scratch);
}

TEST(CliRunModes, ParsesBothSpellingsAndRefusesTheRest) {
  const std::vector<fmask::EqaaConfig> modes = cli::ParseEqaaModes("8S/4Z/2F,16/8/4,1s/1z/1f");
  ASSERT_EQ(modes.size(), 3u);
  EXPECT_EQ(modes[0], (fmask::EqaaConfig{8, 4, 2}));
  EXPECT_EQ(modes[1], (fmask::EqaaConfig{16, 8, 4}));
  EXPECT_EQ(modes[2], fmask::kSingleSample);
  for (const char* bad : {"", "8S/4Z", "8S/4Z/2F/1", "8X/4Z/2F", "8S//2F", "8S/4Z/2F,", "3S/1Z/1F", "8S/4Z/2F,8/4/2"}) {
    EXPECT_THROW(cli::ParseEqaaModes(bad), CLI::ValidationError) << bad;
  }
}

// --- Every bad input: exit code, one stderr line naming the input, no output directory. ---

std::vector<BadInput> RunBadInputs() {
  const auto fixed = [](std::vector<std::string> args) {
    return [args](const fs::path& scratch) {
      std::vector<std::string> all{"--cache", (scratch / "cache").string()};
      all.insert(all.end(), args.begin(), args.end());
      return all;
    };
  };
  return {
      {"UnknownStrategy", fixed({"--strategy", "sometimes"}), "--strategy", "not in", 2},
      {"BadPassSetting", fixed({"--post", "demo:threshold=-1"}), "--post demo:threshold=-1",
       "threshold=-1 outside (0, 1]", 2},
      {"ModeNotAMode", fixed({"--modes", "8S/4Z/2F,banana"}), "--modes", "'banana' is not an EQAA mode", 2},
      {"ModeIllegal", fixed({"--modes", "4S/4Z/8F"}), "4S/4Z/8F", "1S/1Z/1F (single sample, no FMASK)", 2},
      {"ModeTwice", fixed({"--modes", "8S/4Z/2F,8/4/2"}), "--modes", "named twice", 2},
      {"GroundTruthNotSquare", fixed({"--gt-samples", "15"}), "--gt-samples 15", "perfect square", 2},
      {"UnknownPass", fixed({"--post", "demo,nosuch"}), "--post demo,nosuch", "unknown post pass 'nosuch'", 2},
      {"CacheAndNoCache", fixed({"--no-cache"}), "--no-cache", "contradict", 2},
      {"UnknownProgress", fixed({"--progress", "sometimes"}), "--progress", "not in", 2},
      {"OverMemoryLimit", fixed({"--width", "16384", "--height", "16384"}), "--width 16384", "GiB limit", 2},
      {"UnknownScene", fixed({"--scene", "builtin:nosuch"}), "builtin:nosuch", "unknown", 1},
      {"UnknownGpu", fixed({"--gpu", "nosuch"}), "nosuch", "ps4-class", 1},
      {"UnknownPattern", fixed({"--pattern", "nosuch"}), "nosuch", "unknown sample pattern", 1},
      {"MalformedGltf",
       [](const fs::path& scratch) -> std::vector<std::string> {
         WriteFile(scratch / "broken.gltf", "{ not json");
         return {"--cache", (scratch / "cache").string(), "--scene", (scratch / "broken.gltf").string()};
       },
       "broken.gltf", "", 1},
      {"OutUnderARegularFile",
       [](const fs::path& scratch) -> std::vector<std::string> {
         WriteFile(scratch / "somefile", "x");
         return {"--cache", (scratch / "cache").string(), "--out", (scratch / "somefile" / "out").string()};
       },
       "--out", "cannot create directory: Not a directory", 1},
  };
}

class CliRunBadInputTest : public cli::testing::ScratchDirTest, public ::testing::WithParamInterface<BadInput> {};

TEST_P(CliRunBadInputTest, FailsWithOneLineNamingTheInputAndCreatesNothing) {
  const fs::path out = scratch_ / "out";
  const CommandResult run = ExpectRefused("run", GetParam(), scratch_, out);
  EXPECT_FALSE(fs::exists(out)) << run.err;
  EXPECT_FALSE(fs::exists(scratch_ / "cache")) << "no ground truth is rendered for a refused run";
}

INSTANTIATE_TEST_SUITE_P(CliRun, CliRunBadInputTest, ::testing::ValuesIn(RunBadInputs()),
                         [](const auto& param) { return param.param.name; });

}  // namespace

namespace {

// The main job's SMAA and `aasim post` on the frame the main job post-processed: the same image,
// edges and weights (issue: "the same image through aasim post and through the main job").
TEST_F(CliRunTest, PostOnTheRunsFrameGivesTheRunsSmaaImages) {
  ASSERT_EQ(run_->exitCode, 0) << run_->err;
  const fs::path posted = *scratch_ / "post-smaa";
  const CommandResult post = RunAasim({"post", "--pass", "smaa", "--input",
                                       (Out() / "images/frames/1s-1z-1f/frame.exr").string(), "--threads", "2",
                                       "--out", posted.string()},
                                      *scratch_);
  ASSERT_EQ(post.exitCode, 0) << post.err;
  EXPECT_EQ(ReadText(posted / "output.png"), ReadText(Out() / "images/passes/smaa/output.png"));
  for (const char* layer : {"edges.png", "weights.png", "edges.exr", "weights.exr"}) {
    EXPECT_EQ(ReadText(posted / layer), ReadText(Out() / "images/passes/smaa/stencil" / layer)) << layer;
  }
}

}  // namespace
