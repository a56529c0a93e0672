// SMAA 1TX (passes/smaa/smaa_1tx.h): the spatial-contrast history formula on hand-computed
// pixels, through the formula and through the pass, and both strategies over a sequence.

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cmath>
#include <memory>
#include <vector>

#include "passes/compare.h"
#include "passes/registry.h"
#include "passes/smaa/smaa_1tx.h"
#include "passes_test_util.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"
#include "sim_test_util.h"

namespace passes {
namespace {

using testing::GreyImage;

TEST(SmaaOneTx, TheFormulaMatchesHandComputedValues) {
  // Diagonal taps 0.2, 0.4, 0.3, 0.5 (mean 0.35, range [0.2, 0.5]); centre 0.45; history 0.9,
  // clamped to 0.5. w_k = |0.35 - 0.45| = 0.1; frames = 2 * 0.9 + 6 * 0.1 = 2.4; w = 1 / 2.4.
  // c = 0.5 (1 - w) + 0.45 w.
  const glm::vec3 diagonals[4] = {glm::vec3(0.2f), glm::vec3(0.4f), glm::vec3(0.3f), glm::vec3(0.5f)};
  const double w = 1.0 / 2.4;
  EXPECT_NEAR(smaa::SpatialContrastBlend(glm::vec3(0.45f), diagonals, glm::vec3(0.9f), 2.0f, 6.0f).x,
              0.5 * (1.0 - w) + 0.45 * w, 1e-6);
  // A flat neighbourhood keeps 1 / K_lowfreq of the frame (history inside the range).
  const glm::vec3 flat[4] = {glm::vec3(0.2f), glm::vec3(0.6f), glm::vec3(0.2f), glm::vec3(0.6f)};
  EXPECT_NEAR(smaa::SpatialContrastBlend(glm::vec3(0.4f), flat, glm::vec3(0.5f), 2.0f, 6.0f).y, 0.45, 1e-6);
  // Full contrast (w_k = 1) keeps 1 / K_hifreq: more history where contrast is high.
  const glm::vec3 dark[4] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
  EXPECT_NEAR(smaa::SpatialContrastBlend(glm::vec3(1.0f), dark, glm::vec3(0.3f), 2.0f, 6.0f).z, 1.0 / 6.0, 1e-6)
      << "w_k = 1: frames = 6, history clamped to the taps' range [0, 0]";
  const glm::vec3 wide[4] = {glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(0.0f), glm::vec3(1.0f)};
  EXPECT_NEAR(smaa::SpatialContrastBlend(glm::vec3(1.0f), wide, glm::vec3(0.2f), 2.0f, 6.0f).x,
              0.2 * (1.0 - 1.0 / 4.0) + 1.0 / 4.0, 1e-6)
      << "w_k = 0.5: frames = 4";
}

struct Smaa1txSequenceRun {
  std::vector<PassOutput> outputs;
  std::vector<sim::DispatchReport> reports;
};

Smaa1txSequenceRun Run1txSequence(const std::vector<sim::Texture2D<glm::vec4>>& frames, Strategy strategy, int threads = 2) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const std::unique_ptr<Pass> pass = ResolvePass("smaa-1tx").Make();
  sim::Texture2D<glm::vec2> still("velocity", frames.front().Width(), frames.front().Height());
  Smaa1txSequenceRun run;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const sim::Texture2D<glm::vec4> srgb8 = Srgb8ColourTarget("colour-srgb8", frames[k]);
    run.outputs.push_back(pass->Run(
        machine, {.colour = &frames[k], .colourSrgb8 = &srgb8, .velocity = &still, .frameIndex = static_cast<int>(k)},
        strategy));
  }
  run.reports = machine.Reports();
  return run;
}

std::vector<PassOutput> RunFrames(const std::vector<sim::Texture2D<glm::vec4>>& frames, Strategy strategy) {
  return Run1txSequence(frames, strategy).outputs;
}

// Frame 0 uniform code 100; frame 1 the same with one pixel at 120 (below SMAA's threshold, so SMAA
// passes both through). At that pixel the four diagonal taps each average it with three 100s.
TEST(SmaaOneTx, ABrightPixelBlendsWithItsClampedHistoryByHand) {
  const std::vector<sim::Texture2D<glm::vec4>> frames = {
      GreyImage(16, 16, [](int, int) { return 100; }),
      GreyImage(16, 16, [](int x, int y) { return x == 8 && y == 8 ? 120 : 100; })};
  const std::vector<PassOutput> outputs = RunFrames(frames, Strategy::StencilCulled);
  const double lo = static_cast<double>(sim::Srgb8ToFloat(100)), hi = static_cast<double>(sim::Srgb8ToFloat(120));
  const double tap = (hi + 3.0 * lo) / 4.0;         // every diagonal tap; the range is [tap, tap]
  const double contrast = std::fabs(tap - hi);      // w_k
  const double w = 1.0 / (2.0 * (1.0 - contrast) + 6.0 * contrast);
  const double expected = tap * (1.0 - w) + hi * w;  // history 100 clamped up to the tap
  EXPECT_EQ(sim::FloatToSrgb8(outputs[1].colour.At(8, 8).r), sim::FloatToSrgb8(static_cast<float>(expected)));
  EXPECT_NE(sim::FloatToSrgb8(static_cast<float>(expected)), 120) << "the history must show";
  // Frame 0 has no history: its own SMAA output, clamped to its taps, is the history: flat 100.
  EXPECT_EQ(sim::FloatToSrgb8(outputs[0].colour.At(3, 4).g), 100);
}

std::vector<sim::Texture2D<glm::vec4>> MovingStripes() {
  std::vector<sim::Texture2D<glm::vec4>> frames;
  for (int k = 0; k < 4; ++k) {
    frames.push_back(GreyImage(40, 32, [k](int x, int y) { return (x + 2 * k) / 5 % 2 == 0 && y > 6 ? 210 : 50; }));
  }
  return frames;
}

TEST(SmaaOneTx, StrategiesGiveIdenticalImagesOverASequence) {
  const std::vector<sim::Texture2D<glm::vec4>> frames = MovingStripes();
  const std::vector<PassOutput> stencil = RunFrames(frames, Strategy::StencilCulled);
  const std::vector<PassOutput> queue = RunFrames(frames, Strategy::DeferredQueue);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    EXPECT_GT(stencil[k].workItems, 0u);
    EXPECT_TRUE(CompareOutputs(stencil[k], queue[k]).Identical()) << k << ": " << CompareOutputs(stencil[k], queue[k]).Describe();
  }
}

TEST(SmaaOneTx, OneAndTwoThreadsGiveIdenticalImagesAndCountersOverASequence) {
  const std::vector<sim::Texture2D<glm::vec4>> frames = MovingStripes();
  for (const Strategy strategy : kAllStrategies) {
    const Smaa1txSequenceRun one = Run1txSequence(frames, strategy, 1), two = Run1txSequence(frames, strategy, 2);
    for (std::size_t k = 0; k < frames.size(); ++k) {
      EXPECT_TRUE(CompareOutputs(one.outputs[k], two.outputs[k]).Identical()) << StrategyName(strategy) << " " << k;
    }
    sim::testing::ExpectSameReports(one.reports, two.reports);
  }
}

}  // namespace
}  // namespace passes
