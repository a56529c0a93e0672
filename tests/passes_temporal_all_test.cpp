// Every registered temporal pass over a rendered sequence (study::SequenceRenderer, the pass's own
// jitter schedule, a turning wheel): the properties the sequence study relies on, checked for each
// pass without the pass writing a test for them: strategies bit-identical on every frame, 1 and 2
// host threads identical over the whole sequence, history read and written (counted as bytes of
// textures named "history...") from the second frame on, and history that changes the output.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <oneapi/tbb/global_control.h>

#include "passes/compare.h"
#include "passes/registry.h"
#include "raster/jitter_schedule.h"
#include "scenes/scene.h"
#include "sim_test_util.h"
#include "study/sequence.h"

namespace passes {
namespace {

constexpr int kTemporalWidth = 70, kTemporalHeight = 46;  // not multiples of 8: partial groups and quads
constexpr int kTemporalFrames = 4;

struct TemporalFrameRun {
  PassOutput output;
  std::vector<sim::DispatchReport> reports;
};

// The pass over kTemporalFrames frames of the wheel, one instance for the sequence; with `freshLast`, a
// fresh instance also runs the last frame (its output is appended after the sequence's).
std::vector<TemporalFrameRun> RunRegisteredSequence(const RegisteredPass& registered, Strategy strategy, int threads,
                                  bool freshLast = false) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const PassInfo& info = registered.info();
  const float aspect = static_cast<float>(kTemporalWidth) / static_cast<float>(kTemporalHeight);
  const scenes::Scene scene = scenes::LoadScene("builtin:wheel", aspect);
  const study::FrameScene frame = study::ToFrameScene(scene, aspect);
  const int samples = std::max(1, raster::JitterScheduleSamples(info.jitter));
  sim::FrameSettings settings;
  settings.width = kTemporalWidth;
  settings.height = kTemporalHeight;
  settings.eqaa = {samples, samples, samples};
  settings.pattern = raster::MakeBuiltinPattern("standard", samples);
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  study::SequenceConfig config;
  config.frames = kTemporalFrames;
  study::SequenceRenderer renderer(machine, scene, frame, settings,
                                   raster::JitterSchedule::Make(info.jitter, settings.pattern), config);
  const std::unique_ptr<Pass> pass = registered.make(PassSettings(info.name, info.settings));
  std::vector<TemporalFrameRun> runs;
  for (int k = 0; k < kTemporalFrames; ++k) {
    renderer.Render(k);
    machine.ClearReports();
    TemporalFrameRun run{pass->Run(machine, renderer.Inputs(), strategy), {}};
    run.reports = machine.TakeReports();
    runs.push_back(std::move(run));
  }
  if (freshLast) {
    const std::unique_ptr<Pass> fresh = registered.make(PassSettings(info.name, info.settings));
    runs.push_back({fresh->Run(machine, renderer.Inputs(), strategy), machine.TakeReports()});
  }
  return runs;
}

std::uint64_t HistoryBytes(const std::vector<sim::DispatchReport>& reports) {
  std::uint64_t bytes = 0;
  for (const sim::DispatchReport& report : reports) {
    for (const sim::ResourceTraffic& traffic : report.resources) {
      if (passes::IsHistoryResource(traffic.name)) bytes += traffic.bytesRead + traffic.bytesWritten;
    }
  }
  return bytes;
}

std::vector<std::string> TemporalPassNames() {
  std::vector<std::string> names;
  for (const RegisteredPass& pass : AllPasses()) {
    if (pass.info().temporal) names.emplace_back(pass.info().name);
  }
  return names;
}

class EveryTemporalPass : public ::testing::TestWithParam<std::string> {
 protected:
  const RegisteredPass& Pass() const { return PassByName(GetParam()); }
  const PassInfo& Info() const { return Pass().info(); }
};

TEST_P(EveryTemporalPass, DeclaresAScheduleThatDrawsWhatItReads) {
  const int samples = raster::JitterScheduleSamples(Info().jitter);  // throws for an unknown name
  if (Info().eqaaSamples != 0) {
    EXPECT_EQ(samples, Info().eqaaSamples);
  }
}

TEST_P(EveryTemporalPass, StrategiesGiveBitIdenticalOutputsOnEveryFrame) {
  const std::vector<Strategy>& strategies = Info().strategies;
  const std::vector<TemporalFrameRun> first = RunRegisteredSequence(Pass(), strategies.front(), 2);
  for (std::size_t s = 1; s < strategies.size(); ++s) {
    const std::vector<TemporalFrameRun> other = RunRegisteredSequence(Pass(), strategies[s], 2);
    for (int k = 0; k < kTemporalFrames; ++k) {
      const StrategyDifference difference = CompareOutputs(first[k].output, other[k].output);
      EXPECT_TRUE(difference.Identical()) << StrategyName(strategies[s]) << " frame " << k << ": " << difference.Describe();
    }
  }
}

TEST_P(EveryTemporalPass, OneAndTwoThreadsGiveTheSameSequence) {
  for (const Strategy strategy : Info().strategies) {
    const std::vector<TemporalFrameRun> one = RunRegisteredSequence(Pass(), strategy, 1), two = RunRegisteredSequence(Pass(), strategy, 2);
    for (int k = 0; k < kTemporalFrames; ++k) {
      EXPECT_TRUE(CompareOutputs(one[k].output, two[k].output).Identical()) << StrategyName(strategy) << " frame " << k;
      sim::testing::ExpectSameReports(one[k].reports, two[k].reports);
    }
  }
}

TEST_P(EveryTemporalPass, ReadsAndWritesItsHistoryOnTheMachine) {
  const std::vector<TemporalFrameRun> runs = RunRegisteredSequence(Pass(), Info().strategies.front(), 2);
  for (int k = 1; k < kTemporalFrames; ++k) EXPECT_GT(HistoryBytes(runs[k].reports), 0u) << "frame " << k;
}

// The last frame through a fresh instance (no history) differs from the same frame at the end of
// the sequence: the history is used.
TEST_P(EveryTemporalPass, HistoryChangesTheOutput) {
  const std::vector<TemporalFrameRun> runs = RunRegisteredSequence(Pass(), Info().strategies.front(), 2, true);
  const PassOutput &sequenced = runs[kTemporalFrames - 1].output, &fresh = runs[kTemporalFrames].output;
  EXPECT_NE(std::vector<glm::vec4>(sequenced.colour.Texels().begin(), sequenced.colour.Texels().end()),
            std::vector<glm::vec4>(fresh.colour.Texels().begin(), fresh.colour.Texels().end()));
}

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(EveryTemporalPass);
INSTANTIATE_TEST_SUITE_P(Registry, EveryTemporalPass, ::testing::ValuesIn(TemporalPassNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace passes
