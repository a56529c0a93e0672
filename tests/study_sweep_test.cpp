// Sweep axes (study::PlanPasses): a pass setting run at each value as entries of their own, with
// the value set, its sweep point on the entry and on every dispatch record, and every bad axis
// refused before anything runs.

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include "passes/registry.h"
#include "study/study.h"

namespace study {
namespace {

ExperimentConfig TwoPasses() {
  ExperimentConfig config;
  config.passes = {passes::ResolvePass("smaa"), passes::ResolvePass("fxaa")};
  return config;
}

double Setting(const passes::PassConfig& pass, std::string_view key) {
  for (std::size_t i = 0; i < pass.settings.Schema().size(); ++i) {
    if (pass.settings.Schema()[i].name == key) return pass.settings.Values()[i];
  }
  return -1.0;
}

TEST(StudySweep, EachValueIsAPassEntryWithTheValueSet) {
  ExperimentConfig config = TwoPasses();
  config.sweeps = {{"smaa", "threshold", {0.05, 0.2}}};
  const std::vector<PlannedPass> planned = PlanPasses(config);
  ASSERT_EQ(planned.size(), 3u);
  EXPECT_EQ(planned[0].sweepPoint, "threshold=0.05");
  EXPECT_EQ(Setting(planned[0].config, "threshold"), 0.05);
  EXPECT_EQ(planned[1].sweepPoint, "threshold=0.2");
  EXPECT_EQ(Setting(planned[1].config, "threshold"), 0.2);
  EXPECT_EQ(planned[2].config.Info().name, "fxaa");
  EXPECT_EQ(planned[2].sweepPoint, "");
  EXPECT_EQ(SweepSlug(planned[1].sweepPoint), "threshold-0.2");
}

TEST(StudySweep, BadAxesAreRefusedNamingTheAxis) {
  const std::vector<std::pair<SweepAxis, std::string>> cases = {
      {{"cmaa2", "threshold", {0.1}}, "sweep cmaa2:threshold: cmaa2 is not a pass of the run"},
      {{"smaa", "threshold", {}}, "sweep smaa:threshold: no values"},
      {{"smaa", "threshold", {0.1, 0.1}}, "sweep smaa:threshold: 0.1 is given twice"},
      {{"smaa", "nope", {0.1}}, "unknown setting 'nope'"},
      {{"smaa", "threshold", {7.0}}, "threshold"}};
  for (const auto& [axis, message] : cases) {
    ExperimentConfig config = TwoPasses();
    config.sweeps = {axis};
    try {
      PlanPasses(config);
      ADD_FAILURE() << "accepted " << axis.pass << ":" << axis.setting;
    } catch (const std::exception& error) {
      EXPECT_NE(std::string(error.what()).find(message), std::string::npos) << error.what();
    }
  }
  ExperimentConfig twice = TwoPasses();
  twice.sweeps = {{"smaa", "threshold", {0.1}}, {"smaa", "max_search_steps", {8}}};
  EXPECT_THROW(PlanPasses(twice), std::invalid_argument);
}

// A higher SMAA threshold keeps fewer edge pixels: the sweep's entries follow their values.
TEST(StudySweep, TheStudyRunsEveryPointAndLabelsItsDispatches) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  ExperimentConfig config;
  config.width = 96;
  config.height = 64;
  config.gpu = "ps4-class";
  config.modes = {{1, 1, 1}};
  config.resolves = {};
  config.passes = {passes::ResolvePass("smaa")};
  config.sweeps = {{"smaa", "threshold", {0.02, 0.1, 0.3}}};
  config.groundTruth.samplesPerPixel = 4;
  const Study study = RunStudy(LoadStudyInputs(config), config);
  ASSERT_EQ(study.passes.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(study.passes[i].image.folder, "passes/smaa/" + SweepSlug(study.passes[i].sweepPoint));
    EXPECT_EQ(study.passes[i].Label(), "smaa " + study.passes[i].sweepPoint);
    for (const StudyPassRun& run : study.passes[i].runs) {
      for (std::size_t d = run.firstDispatch; d < run.endDispatch; ++d) {
        EXPECT_EQ(study.dispatches[d].sweepPoint, study.passes[i].sweepPoint);
      }
    }
    if (i > 0) {
      EXPECT_GE(study.passes[i - 1].workItems, study.passes[i].workItems);
    }
  }
  EXPECT_GT(study.passes[0].workItems, study.passes[2].workItems);
}

}  // namespace
}  // namespace study
