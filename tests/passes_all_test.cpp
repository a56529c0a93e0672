// Every registered pass under every strategy it declares, on a rendered frame: the properties the
// study relies on, checked for each pass without the pass writing a test for them (pbrt's
// integrators_test pattern: one parameterised test over the registry).

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <oneapi/tbb/global_control.h>

#include "study/frame_scene.h"
#include "passes/compare.h"
#include "passes/registry.h"
#include "passes/work_set.h"
#include "raster/sample_pattern.h"
#include "scenes/scene.h"
#include "sim/frame.h"
#include "sim_test_util.h"

namespace passes {
namespace {

constexpr int kWidth = 150, kHeight = 94;  // not multiples of 8 or 64: partial groups, waves, quads

struct PassRun {
  PassOutput output;
  std::vector<sim::DispatchReport> reports;
};

// Renders the default scene and runs the pass once under `strategy` with `threads` host threads.
PassRun RunPass(const RegisteredPass& registered, Strategy strategy, int threads, int width = kWidth,
                int height = kHeight) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const scenes::Scene scene = scenes::LoadScene("builtin:default", aspect);
  const study::FrameScene frameScene = study::ToFrameScene(scene, aspect);
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  sim::FrameSettings settings;
  settings.width = width;
  settings.height = height;
  const PassInfo& needs = registered.info();
  if (needs.eqaaSamples != 0) {  // the surface the pass reads, with the standard pattern
    settings.eqaa = {needs.eqaaSamples, needs.eqaaSamples, needs.eqaaSamples};
    settings.pattern = raster::MakeBuiltinPattern("standard", needs.eqaaSamples);
  }
  sim::FramePipeline pipeline(machine, settings);
  pipeline.Render(frameScene.Geometry());
  machine.ClearReports();
  const PassInfo& info = registered.info();
  const std::unique_ptr<Pass> pass = registered.make(PassSettings(info.name, info.settings));
  PassRun run{pass->Run(machine, FrameInputsOf(pipeline), strategy), {}};
  run.reports = machine.Reports();
  return run;
}

const sim::DispatchReport& Studied(const PassRun& run, std::string_view name) {
  for (const sim::DispatchReport& report : run.reports) {
    if (report.name == name) return report;
  }
  throw std::logic_error("no studied dispatch " + std::string(name));
}

class EveryPass : public ::testing::TestWithParam<std::string> {
 protected:
  const RegisteredPass& Pass() const { return PassByName(GetParam()); }
  const PassInfo& Info() const { return Pass().info(); }
};

TEST_P(EveryPass, DeclaresWhatTheStudyNeeds) {
  EXPECT_FALSE(Info().description.empty());
  EXPECT_FALSE(Info().strategies.empty());
  EXPECT_FALSE(Info().studiedDispatches.empty());
  EXPECT_GT(Info().bytesPerPixel, 0u);
  for (const SettingInfo& setting : Info().settings) {
    EXPECT_FALSE(setting.doc.empty()) << setting.name;
    PassSettings settings(Info().name, Info().settings);
    EXPECT_NO_THROW(settings.Set(setting.name, setting.defaultValue)) << setting.name << ": default out of range";
  }
}

// The memory guard adds up the layers the study keeps per strategy run: the declaration must be
// what a run returns.
TEST_P(EveryPass, DeclaresTheBytesOfTheLayersItReturns) {
  const PassRun run = RunPass(Pass(), Info().strategies.front(), 2);
  std::uint64_t bytes = 0;
  for (const PassLayer& layer : run.output.layers) bytes += layer.values.size() * sizeof(float) + layer.codes.size();
  EXPECT_EQ(bytes, Info().layerBytesPerPixel * std::uint64_t(kWidth) * std::uint64_t(kHeight));
}

// Screens smaller than a quad, a group or a search: every pass runs, writes an image of the
// frame's size and agrees with itself across strategies (fxaa-miniengine once failed a region
// check on a screen one pixel high).
TEST_P(EveryPass, RunsOnScreensOfOneToThreePixelsASide) {
  for (const auto& [width, height] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{1, 3}, std::pair{3, 3}}) {
    const PassRun first = RunPass(Pass(), Info().strategies.front(), 2, width, height);
    EXPECT_EQ(first.output.colour.Width(), width);
    EXPECT_EQ(first.output.colour.Height(), height);
    for (const Strategy strategy : Info().strategies) {
      const StrategyDifference difference = CompareOutputs(first.output, RunPass(Pass(), strategy, 2, width, height).output);
      EXPECT_TRUE(difference.Identical()) << width << "x" << height << " " << StrategyName(strategy) << ": "
                                          << difference.Describe();
    }
  }
}

// The timing estimate's instruction counts say where they come from (KernelInfo::source).
TEST_P(EveryPass, EveryKernelCitesTheSourceOfItsInstructionCount) {
  for (const Strategy strategy : Info().strategies) {
    for (const sim::DispatchReport& report : RunPass(Pass(), strategy, 2).reports) {
      EXPECT_FALSE(report.kernel.source.empty()) << report.name << " [" << StrategyName(strategy) << "]";
      EXPECT_LE(report.time.totalValuHalvedMicroseconds, report.time.totalMicroseconds) << report.name;
      EXPECT_GE(report.time.totalValuDoubledMicroseconds, report.time.totalMicroseconds) << report.name;
    }
  }
}

TEST_P(EveryPass, StrategiesGiveBitIdenticalOutputs) {
  const std::vector<Strategy>& strategies = Info().strategies;
  const PassRun first = RunPass(Pass(), strategies.front(), 2);
  EXPECT_GT(first.output.workItems, 0u) << "the frame must give the pass work, or identity proves nothing";
  for (std::size_t i = 1; i < strategies.size(); ++i) {
    const StrategyDifference difference = CompareOutputs(first.output, RunPass(Pass(), strategies[i], 2).output);
    EXPECT_TRUE(difference.Identical()) << StrategyName(strategies[i]) << ": " << difference.Describe();
  }
}

TEST_P(EveryPass, OneAndTwoThreadsGiveIdenticalImagesAndCounters) {
  for (const Strategy strategy : Info().strategies) {
    const PassRun one = RunPass(Pass(), strategy, 1);
    const PassRun two = RunPass(Pass(), strategy, 2);
    EXPECT_TRUE(CompareOutputs(one.output, two.output).Identical()) << StrategyName(strategy);
    sim::testing::ExpectSameReports(one.reports, two.reports);
  }
}

// A pass keeps its render targets from frame to frame: a second frame through the same instance
// gives what a fresh instance gives (nothing of the first frame leaks into the second).
TEST_P(EveryPass, AnInstanceReusedForASecondFrameGivesWhatAFreshOneGives) {
  if (Info().temporal) GTEST_SKIP() << "a temporal pass keeps history on purpose";
  const float aspect = static_cast<float>(kWidth) / kHeight;
  const study::FrameScene frameScene = study::ToFrameScene(scenes::LoadScene("builtin:default", aspect), aspect);
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  sim::FrameSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  if (Info().eqaaSamples != 0) {
    settings.eqaa = {Info().eqaaSamples, Info().eqaaSamples, Info().eqaaSamples};
    settings.pattern = raster::MakeBuiltinPattern("standard", Info().eqaaSamples);
  }
  sim::FramePipeline pipeline(machine, settings);
  pipeline.Render(frameScene.Geometry());
  // The second frame: the first mirrored, so its edges lie elsewhere.
  sim::Texture2D<glm::vec4> mirrored("mirrored", kWidth, kHeight, 4);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) mirrored.At(x, y) = pipeline.Colour().At(kWidth - 1 - x, y);
  }
  const sim::Texture2D<glm::vec4> mirroredSrgb8 = Srgb8ColourTarget("mirrored-srgb8", mirrored);
  FrameInputs second = FrameInputsOf(pipeline);
  second.colour = &mirrored;
  second.colourSrgb8 = &mirroredSrgb8;
  for (const Strategy strategy : Info().strategies) {
    const std::unique_ptr<passes::Pass> reused = Pass().make(PassSettings(Info().name, Info().settings));
    reused->Run(machine, FrameInputsOf(pipeline), strategy);
    const PassOutput again = reused->Run(machine, second, strategy);
    const PassOutput fresh = Pass().make(PassSettings(Info().name, Info().settings))->Run(machine, second, strategy);
    EXPECT_TRUE(CompareOutputs(fresh, again).Identical()) << StrategyName(strategy) << ": "
                                                          << CompareOutputs(fresh, again).Describe();
  }
}

TEST_P(EveryPass, TheWorkSetShapeIsTheSameUnderEveryStrategy) {
  std::optional<WorkSetShape> first;
  for (const Strategy strategy : Info().strategies) {
    const WorkSetShape shape = RunPass(Pass(), strategy, 2).output.workSet;
    EXPECT_LE(shape.quads, shape.pixels);
    EXPECT_LE(shape.pixels, 4 * shape.quads);
    EXPECT_LE(shape.tiles, shape.quads);
    EXPECT_LE(shape.quads, 16 * shape.tiles);
    if (first) {
      EXPECT_EQ(shape, *first) << StrategyName(strategy);
    }
    first = shape;
  }
}

// A pass with two consumes (Filmic SMAA's vertical and horizontal edges) studies both: together
// they run one active lane per work item, plus the dummy items a padded queue adds (MiniEngine
// FXAA pads each queue to whole waves, aa-facts §3): fewer than one wave's worth per queue. A
// pass that runs its work set per screen region (MiniEngine's quadrants) runs each studied
// dispatch once per region: all of them count.
TEST_P(EveryPass, TheStudiedDispatchesRunOneActiveLanePerWorkItem) {
  for (const Strategy strategy : Info().strategies) {
    const PassRun run = RunPass(Pass(), strategy, 2);
    std::uint64_t active = 0, queues = 0;
    for (const std::string_view name : Info().studiedDispatches) {
      ASSERT_NO_THROW(Studied(run, name));
      for (const sim::DispatchReport& studied : run.reports) {
        if (studied.name != name) continue;
        ++queues;
        active += studied.lanes.lanesActive;
        if (strategy == Strategy::DeferredQueue) {
          // A queue consumer packs its items densely: ceil(N / 64) waves, no lane wasted but the last wave's.
          EXPECT_EQ(studied.lanes.waves, (studied.lanes.lanesActive + sim::kWaveLanes - 1) / sim::kWaveLanes) << name;
          EXPECT_EQ(studied.kind, sim::DispatchKind::IndirectCompute) << name;
        }
      }
    }
    EXPECT_EQ(active, run.output.workItems + run.output.paddingItems) << StrategyName(strategy);
    if (strategy == Strategy::StencilCulled) {
      EXPECT_EQ(run.output.paddingItems, 0u);
    }
    EXPECT_LT(run.output.paddingItems, queues * sim::kWaveLanes) << StrategyName(strategy);
  }
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryPass, ::testing::ValuesIn(PassNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           // Test names are identifiers: "smaa-colour" runs as Registry/EveryPass.X/smaa_colour.
                           std::string name = param.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace passes

namespace passes {
namespace {

TEST(WorkSetShape, CountsThePixelsAndTheQuadsAndTilesTheyTouch) {
  const int width = 20, height = 11;  // partial quads and tiles at the right and bottom
  std::vector<std::uint8_t> marked(static_cast<std::size_t>(width * height), 0);
  const auto mark = [&](int x, int y) { marked[static_cast<std::size_t>(y * width + x)] = 1; };
  mark(0, 0);
  mark(1, 1);    // same quad, same tile
  mark(2, 0);    // next quad, same tile
  mark(19, 10);  // the last partial quad and tile
  mark(8, 0);    // second tile column
  EXPECT_EQ(ShapeOf(marked, width, height), (WorkSetShape{.pixels = 5, .quads = 4, .tiles = 3}));
}

}  // namespace
}  // namespace passes
