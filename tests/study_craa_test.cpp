// The CRAA resolves in the study: on the pixel-crossing scene (three to eight triangles meeting in
// a pixel, seed 001's case for the LUT) the LUT resolve beats the simple resolve, which beats the
// 1x box; every registered resolve is deterministic across thread counts; the LUT cache.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "eqaa_frame_util.h"
#include "passes/craa/craa_lut_resolve.h"
#include "passes/resolve.h"
#include "sim_test_util.h"
#include "study/study.h"

namespace study {
namespace {

namespace fs = std::filesystem;

// A coarse LUT is enough where only determinism and caching are checked.
constexpr std::int64_t kFewConfigurations = 20000;

const passes::QualityScores& ScoresOf(const Study& study, const std::string& mode, const std::string& resolve) {
  for (const StudyFrame& frame : study.frames) {
    if (fmask::EqaaName(frame.mode) != mode) continue;
    if (resolve == "box") return frame.image.quality.scores;
    for (const StudyResolve& each : frame.resolves) {
      if (each.name == resolve) return each.image.quality.scores;
    }
  }
  throw std::logic_error(mode + " " + resolve + " did not run");
}

// 480x270, 64 rays per pixel: measured edge PSNR 1x box 18.41 dB, simple 18.81, LUT 19.60; PSNR
// 32.88, 33.27, 34.06. The outputs are deterministic, so the margins are exact, not noise.
TEST(StudyCraa, OnPixelCrossingTheLutBeatsTheSimpleResolveWhichBeatsThe1xBox) {
  ExperimentConfig config;
  config.scene = "builtin:pixel-crossing";
  config.width = 480;
  config.height = 270;
  config.modes = {{1, 1, 1}, {8, 8, 1}};
  config.resolves = {"craa-simple", "craa-lut"};
  config.groundTruth.samplesPerPixel = 64;
  config.gpu = std::string(sim::kDefaultGpuName);
  const Study study = RunStudy(LoadStudyInputs(config), config);
  const passes::QualityScores& box1x = ScoresOf(study, "1S/1Z/1F", "box");
  const passes::QualityScores& simple = ScoresOf(study, "8S/8Z/1F", "craa-simple");
  const passes::QualityScores& lut = ScoresOf(study, "8S/8Z/1F", "craa-lut");
  EXPECT_GT(lut.edgePsnr, simple.edgePsnr);
  EXPECT_GT(simple.edgePsnr, box1x.edgePsnr);
  EXPECT_GT(lut.psnr, simple.psnr);
  EXPECT_GT(simple.psnr, box1x.psnr);
  // Without reconstruction a 1F surface is worse than one sample: its stored fragment is the last
  // one drawn over any sample, so it spreads over every pixel it touches.
  EXPECT_LT(ScoresOf(study, "8S/8Z/1F", "box").edgePsnr, box1x.edgePsnr);
  // The EQAA study has a row per frame and resolve, the box first.
  const std::vector<EqaaStudyRow> rows = EqaaStudyRows(study);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[1].resolve, "box");
  EXPECT_EQ(rows[3].resolve, "craa-lut");
  EXPECT_EQ(rows[3].tableBytesRead, rows[3].pixels * 2);  // one 16-bit LUT entry per pixel
  EXPECT_EQ(rows[3].fragmentBytesRead, rows[3].pixels * 5 * 4);  // own + four neighbours, RGBA8
  EXPECT_GT(rows[1].unknown.Total(), 0u);
}

// --compare-policies: every EQAA mode drawn again under each further policy, its frame labelled with
// the policy, resolved like the others; the aliased mode is not redrawn.
TEST(StudyCraa, ComparedPoliciesDrawTheEqaaModesAgain) {
  ExperimentConfig config;
  config.scene = "builtin:default";
  config.width = 96;
  config.height = 64;
  config.modes = {{1, 1, 1}, {8, 4, 1}};
  config.comparedPolicies = {"keep-on-reject"};
  config.resolves = {"craa-simple"};
  config.groundTruth.samplesPerPixel = 4;
  config.gpu = std::string(sim::kDefaultGpuName);
  const Study study = RunStudy(LoadStudyInputs(config), config);
  ASSERT_EQ(study.frames.size(), 3u);
  EXPECT_EQ(study.frames[2].image.label, "8S/4Z/1F keep-on-reject");
  EXPECT_EQ(study.frames[2].policy, "keep-on-reject");
  EXPECT_EQ(study.frames[1].policy, "hraa");
  EXPECT_EQ(study.frames[2].image.folder, "frames/8s-4z-1f-keep-on-reject");
  ASSERT_EQ(study.frames[2].resolves.size(), 1u);
  const std::vector<EqaaStudyRow> rows = EqaaStudyRows(study);
  ASSERT_EQ(rows.size(), 5u);  // 1S box; 8S/4Z/1F box and craa-simple under each policy
  EXPECT_EQ(rows[3].policy, "keep-on-reject");
  EXPECT_EQ(rows[4].resolve, "craa-simple");
}

// Every registered resolve on every legal mode it reads: the same image and counters on 1 and 2
// host threads.
TEST(StudyCraa, EveryResolveIsIdenticalOnOneAndTwoThreads) {
  for (const passes::RegisteredResolve& registered : passes::AllResolves()) {
    for (const fmask::EqaaConfig& mode : {fmask::EqaaConfig{4, 4, 1}, fmask::EqaaConfig{8, 4, 2}, fmask::EqaaConfig{16, 8, 1}}) {
      if (!registered.info().reads(mode)) continue;
      std::vector<sim::Texture2D<glm::vec4>> images;
      std::vector<std::vector<sim::DispatchReport>> reports;
      for (const int threads : {1, 2}) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
        const auto frame = testing_eqaa::RenderBuiltin("pixel-crossing", 96, 64, mode);
        const passes::ResolveContext context{
            .pattern = &frame->pattern, .tableCache = std::nullopt, .tableConfigurations = kFewConfigurations};
        images.push_back(registered.make(context)->Run(frame->machine, frame->pipeline->Eqaa()));
        reports.push_back(frame->machine.TakeReports());
      }
      const auto a = images[0].Texels(), b = images[1].Texels();
      EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << registered.info().name;
      sim::testing::ExpectSameReports(reports[0], reports[1]);
    }
  }
}

TEST(StudyCraa, TheLutIsCachedPerPatternAndReadBack) {
  const fs::path cache = fs::temp_directory_path() / ("aasim_lut_cache_" + std::to_string(::getpid()));
  fs::remove_all(cache);
  const raster::SamplePattern pattern = raster::MakeBuiltinPattern("eqaa", 4);
  const passes::craa::CraaLut made = passes::craa::CachedCraaLut(pattern, cache, kFewConfigurations);
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(cache)) files.push_back(entry.path());
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(passes::craa::CachedCraaLut(pattern, cache, kFewConfigurations), made);
  EXPECT_EQ(made, passes::craa::GenerateCraaLut(pattern, passes::craa::WithConfigurations({}, kFewConfigurations)));
  // Another pattern of the same count gets its own file.
  passes::craa::CachedCraaLut(raster::MakeBuiltinPattern("rotated-grid", 4), cache, kFewConfigurations);
  EXPECT_EQ(std::distance(fs::directory_iterator(cache), fs::directory_iterator{}), 2);
  // A damaged cache file is an error naming it, not a silent regeneration.
  std::ofstream(files.front(), std::ios::trunc) << "{\"schema\": 1}";
  try {
    passes::craa::CachedCraaLut(pattern, cache, kFewConfigurations);
    ADD_FAILURE() << "a damaged cache file was accepted";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find(files.front().string()), std::string::npos) << error.what();
  }
  fs::remove_all(cache);
}

}  // namespace
}  // namespace study
