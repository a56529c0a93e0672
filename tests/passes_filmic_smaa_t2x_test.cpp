// Filmic SMAA T2x (passes/filmic_smaa/filmic_t2x.h) over synthetic sequences: the FPS-aware
// history weight, a disocclusion without a ghost, and both strategies
// and 1 vs 2 threads over a sequence with temporal edges.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <oneapi/tbb/global_control.h>

#include "passes/compare.h"
#include "passes/filmic_smaa/filmic_t2x.h"
#include "passes/registry.h"
#include "passes_test_util.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"
#include "sim_test_util.h"

namespace passes {
namespace {

using testing::GreyImage;

struct FilmicFrame {
  sim::Texture2D<glm::vec4> colour;
  sim::Texture2D<float> depth;
  sim::Texture2D<glm::vec2> velocity;
};

constexpr int kFilmicWidth = 48, kFilmicHeight = 40, kStep = 4, kBackground = 60;

bool InFilmicBox(int frame, int x, int y) { return x >= 8 + kStep * frame && x < 20 + kStep * frame && y >= 10 && y < 24; }

// A box moving right by 4 px per frame, nearer than the background; `background(x, y, k)` gives
// the background's codes, `box(k)` the box's.
FilmicFrame FilmicBoxFrame(int k, const std::function<int(int, int, int)>& background, const std::function<int(int)>& box) {
  FilmicFrame frame{GreyImage(kFilmicWidth, kFilmicHeight, [&](int x, int y) { return InFilmicBox(k, x, y) ? box(k) : background(x, y, k); }),
              sim::Texture2D<float>("depth", kFilmicWidth, kFilmicHeight), sim::Texture2D<glm::vec2>("velocity", kFilmicWidth, kFilmicHeight)};
  for (int y = 0; y < kFilmicHeight; ++y) {
    for (int x = 0; x < kFilmicWidth; ++x) {
      frame.depth.At(x, y) = InFilmicBox(k, x, y) ? 0.3f : 0.8f;
      frame.velocity.At(x, y) = InFilmicBox(k, x, y) ? glm::vec2(kStep, 0) : glm::vec2(0);
    }
  }
  return frame;
}

struct FilmicSequenceRun {
  std::vector<PassOutput> outputs;
  std::vector<sim::DispatchReport> reports;
};

FilmicSequenceRun RunFilmicSequence(std::string_view spec, int frames, const std::function<FilmicFrame(int)>& make, Strategy strategy,
                int threads = 2, double frameSeconds = 1.0 / 60.0) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const std::unique_ptr<Pass> pass = ResolvePass(spec).Make();
  FilmicSequenceRun run;
  for (int k = 0; k < frames; ++k) {
    const FilmicFrame frame = make(k);
    // The t2x schedule's jitter (aa-facts §1.8, y down).
    const glm::vec2 jitter = k % 2 == 0 ? glm::vec2(0.25f) : glm::vec2(-0.25f);
    const sim::Texture2D<glm::vec4> srgb8 = Srgb8ColourTarget("colour-srgb8", frame.colour);
    run.outputs.push_back(pass->Run(machine,
                                    {.colour = &frame.colour, .colourSrgb8 = &srgb8, .depth = &frame.depth,
                                     .velocity = &frame.velocity,
                                     .frameIndex = k, .jitter = jitter, .frameSeconds = frameSeconds},
                                    strategy));
  }
  run.reports = machine.Reports();
  return run;
}

int Code(const PassOutput& output, int x, int y) { return sim::FloatToSrgb8(output.colour.At(x, y).r); }

TEST(FilmicSmaaT2x, TheHistoryWeightIsExpOfMinusDtOverTauAtTwoFrameRates) {
  // tau = 0.158 s: exp(-(1/60) / 0.158) = 0.89989, exp(-(1/30) / 0.158) = 0.80980.
  EXPECT_NEAR(filmic_smaa::HistoryWeight(1.0 / 60.0, 0.158), 0.89989, 1e-5);
  EXPECT_NEAR(filmic_smaa::HistoryWeight(1.0 / 30.0, 0.158), 0.80980, 1e-5);
  // Two frames at 60 fps keep what one frame at 30 fps keeps.
  EXPECT_NEAR(std::pow(filmic_smaa::HistoryWeight(1.0 / 60.0, 0.158), 2.0), filmic_smaa::HistoryWeight(1.0 / 30.0, 0.158),
              1e-6);
}

// A flickering box (its code changes every frame) and T2x's alternating subsample indices leave
// temporal edges. On frame 1 (the first with history) the filtered pixels are
// out = r + a (h - r) with r the supersampled frame and h the clamped, filtered history: the
// same r and h at every frame rate, so (out(dt) - r) / (out(2 dt) - r) = exp(-dt / tau) /
// exp(-2 dt / tau). A third run with a tiny tau (a ~ 6e-8) gives r. Other pixels do not depend on
// the frame time.
int FlickeringBox(int k) { return k % 3 == 0 ? 200 : (k % 3 == 1 ? 235 : 170); }
int Checker(int x, int y, int) { return (x / 6 + y / 6) % 2 == 0 ? kBackground : 150; }

TEST(FilmicSmaaT2x, TheFilteredPixelsKeepExpOfMinusDtOverTauOfTheHistoryAtTwoFrameRates) {
  const auto make = [](int k) { return FilmicBoxFrame(k, Checker, FlickeringBox); };
  constexpr double kTau = 0.158;
  const FilmicSequenceRun fast = RunFilmicSequence("filmic-smaa-t2x", 2, make, Strategy::StencilCulled, 2, 1.0 / 60.0);
  const FilmicSequenceRun slow = RunFilmicSequence("filmic-smaa-t2x", 2, make, Strategy::StencilCulled, 2, 1.0 / 30.0);
  const FilmicSequenceRun current = RunFilmicSequence("filmic-smaa-t2x:convergence_time=0.001", 2, make, Strategy::StencilCulled);
  const double expectedRatio = std::exp(-(1.0 / 60.0) / kTau) / std::exp(-(1.0 / 30.0) / kTau);
  const PassLayer& edges = testing::LayerNamed(fast.outputs[1], "temporal-edges");
  ASSERT_EQ(edges.Floats(), testing::LayerNamed(slow.outputs[1], "temporal-edges").Floats());
  int checked = 0;
  for (int y = 0; y < kFilmicHeight; ++y) {
    for (int x = 0; x < kFilmicWidth; ++x) {
      const glm::vec4 f = fast.outputs[1].colour.At(x, y), s = slow.outputs[1].colour.At(x, y);
      const glm::vec4 r = current.outputs[1].colour.At(x, y);
      if (testing::LayerValue(edges, x, y) == 0.0f) {
        EXPECT_EQ(f, s) << x << "," << y;
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        if (std::fabs(s[c] - r[c]) < 0.05f) continue;  // too little history to measure through RGBA16F
        EXPECT_NEAR((f[c] - r[c]) / (s[c] - r[c]), expectedRatio, 0.02) << x << "," << y << " channel " << c;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 10);
}

// The box uncovers the flat background behind it: on the first frame after the disocclusion (and
// after it) those pixels show the background, no trace of the box (the velocity weight and the
// depth test reject the previous frames there). Pixels 2-4 px behind the box's trailing edge,
// whose 2x2 depth block the box covered in the previous frame.
TEST(FilmicSmaaT2x, ADisocclusionLeavesNoGhostFromItsFirstFrame) {
  const auto make = [](int k) { return FilmicBoxFrame(k, [](int, int, int) { return kBackground; }, [](int) { return 230; }); };
  for (const Strategy strategy : kAllStrategies) {
    const FilmicSequenceRun run = RunFilmicSequence("filmic-smaa-t2x", 6, make, strategy);
    for (int k = 1; k < 6; ++k) {
      for (int disoccludedAt = 1; disoccludedAt <= k; ++disoccludedAt) {
        for (const int x : {4 + kStep * disoccludedAt, 5 + kStep * disoccludedAt}) {
          for (const int y : {11, 16, 22}) {
            EXPECT_EQ(Code(run.outputs[static_cast<std::size_t>(k)], x, y), kBackground)
                << StrategyName(strategy) << " frame " << k << " pixel " << x << "," << y << " (uncovered at frame "
                << disoccludedAt << ")";
          }
        }
      }
    }
  }
}

TEST(FilmicSmaaT2x, StrategiesAndThreadsGiveIdenticalImagesAndCountersOverASequence) {
  const auto make = [](int k) { return FilmicBoxFrame(k, Checker, FlickeringBox); };
  const FilmicSequenceRun stencil = RunFilmicSequence("filmic-smaa-t2x", 5, make, Strategy::StencilCulled);
  const FilmicSequenceRun queue = RunFilmicSequence("filmic-smaa-t2x", 5, make, Strategy::DeferredQueue);
  const FilmicSequenceRun queueOne = RunFilmicSequence("filmic-smaa-t2x", 5, make, Strategy::DeferredQueue, 1);
  std::uint64_t temporalItems = 0;
  for (std::size_t k = 0; k < stencil.outputs.size(); ++k) {
    EXPECT_TRUE(CompareOutputs(stencil.outputs[k], queue.outputs[k]).Identical())
        << k << ": " << CompareOutputs(stencil.outputs[k], queue.outputs[k]).Describe();
    EXPECT_TRUE(CompareOutputs(queue.outputs[k], queueOne.outputs[k]).Identical()) << k;
    for (const float v : testing::LayerNamed(stencil.outputs[k], "temporal-edges").Floats()) temporalItems += v != 0.0f;
  }
  EXPECT_GT(temporalItems, 0u);
  sim::testing::ExpectSameReports(queue.reports, queueOne.reports);
}

}  // namespace
}  // namespace passes
