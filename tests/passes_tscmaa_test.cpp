// TSCMAA (passes/tscmaa/): the TAA touches only its candidates (every other pixel is CMAA2's,
// preset tscmaa, bit for bit), the candidates are the chosen share of CMAA2's, frame 0 is CMAA2's
// image, the history blend on a known step, and both strategies and thread counts agree over a
// sequence.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>
#include <oneapi/tbb/global_control.h>

#include "passes/cmaa2/cmaa2.h"
#include "passes/compare.h"
#include "passes/temporal/colour_box.h"
#include "passes/tscmaa/tscmaa.h"
#include "passes_test_util.h"
#include "sim/colour.h"
#include "sim/gpu_config.h"
#include "sim_test_util.h"

namespace passes::tscmaa {
namespace {

using testing::LayerNamed;
using testing::LayerValue;

constexpr int kTscmaaSide = 48;
constexpr int kTscmaaFrames = 6;

struct TscmaaFrame {
  sim::Texture2D<glm::vec4> colour{"colour", kTscmaaSide, kTscmaaSide, 16};
  sim::Texture2D<glm::vec2> velocity{"velocity", kTscmaaSide, kTscmaaSide, 8};
  int index = 0;
  mutable std::optional<sim::Texture2D<glm::vec4>> srgb8;  // made by Inputs from the colour
  FrameInputs Inputs() const {
    srgb8 = Srgb8ColourTarget("colour-srgb8", colour);
    return {.colour = &colour, .colourSrgb8 = &*srgb8, .depth = nullptr, .normal = nullptr, .objectId = nullptr, .velocity = &velocity,
            .eqaa = nullptr, .pattern = nullptr, .frameIndex = index, .jitter = {}};
  }
};

// A disk moving 0.4 px per frame to the right (its velocity on its pixels) in front of a
// background with a diagonal stripe: curved and staircase edges, sub-pixel motion.
TscmaaFrame MovingDisk(int t) {
  TscmaaFrame frame;
  frame.index = t;
  const glm::vec2 centre(20.0f + 0.4f * static_cast<float>(t), 24.0f);
  for (int y = 0; y < kTscmaaSide; ++y) {
    for (int x = 0; x < kTscmaaSide; ++x) {
      const glm::vec2 p(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const bool stripe = std::abs(p.x - 0.6f * p.y - 30.0f) < 2.0f;
      frame.colour.At(x, y) = stripe ? glm::vec4(0.1f, 0.6f, 0.2f, 1.0f) : glm::vec4(0.05f, 0.1f, 0.2f, 1.0f);
      const glm::vec2 d = p - centre;
      if (d.x * d.x + d.y * d.y < 11.3f * 11.3f) {
        frame.colour.At(x, y) = glm::vec4(0.9f, 0.8f, 0.3f, 1.0f);
        frame.velocity.At(x, y) = {0.4f, 0.0f};
      }
    }
  }
  return frame;
}

std::unique_ptr<Pass> MakeCmaa2Tscmaa() {
  PassSettings settings(cmaa2::Info().name, cmaa2::Info().settings);
  settings.Set("threshold", 1.0 / 22.0);
  settings.Set("local_contrast_adaptation", 0.5);
  return cmaa2::Make(settings);
}

std::unique_ptr<Pass> MakeTscmaa() { return Make(PassSettings(Info().name, Info().settings)); }

struct TscmaaSequence {
  std::vector<PassOutput> outputs;
  std::vector<sim::DispatchReport> reports;
};

TscmaaSequence RunTscmaaSequence(Pass& pass, Strategy strategy, const std::function<TscmaaFrame(int)>& make = MovingDisk) {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  TscmaaSequence sequence;
  for (int t = 0; t < kTscmaaFrames; ++t) sequence.outputs.push_back(pass.Run(machine, make(t).Inputs(), strategy));
  sequence.reports = machine.Reports();
  return sequence;
}

TEST(PassesTscmaa, TheTaaTouchesOnlyItsCandidatesAndFrameZeroIsCmaa2) {
  for (const Strategy strategy : kAllStrategies) {
    const std::unique_ptr<Pass> tscmaa = MakeTscmaa();
    const TscmaaSequence run = RunTscmaaSequence(*tscmaa, strategy);
    sim::Machine machine(sim::GpuConfigByName("ps4-class"));
    int candidates = 0, taaCandidates = 0, changed = 0;
    for (int t = 0; t < kTscmaaFrames; ++t) {
      const PassOutput& out = run.outputs[static_cast<std::size_t>(t)];
      // CMAA2 is spatial: a fresh instance per frame gives its image of that frame.
      const PassOutput cmaa = MakeCmaa2Tscmaa()->Run(machine, MovingDisk(t).Inputs(), strategy);
      const PassLayer& cmaaCandidates = LayerNamed(cmaa, "candidates");
      const PassLayer& taa = LayerNamed(out, "taa-candidates");
      for (int y = 0; y < kTscmaaSide; ++y) {
        for (int x = 0; x < kTscmaaSide; ++x) {
          const bool isCandidate = LayerValue(cmaaCandidates, x, y) != 0.0f;
          const bool isTaa = LayerValue(taa, x, y) != 0.0f;
          ASSERT_EQ(isTaa, isCandidate && ChosenForTaa(x, y, 0.5)) << t << ": " << x << "," << y;
          candidates += isCandidate ? 1 : 0;
          taaCandidates += isTaa ? 1 : 0;
          if (!isTaa || t == 0) {
            ASSERT_EQ(out.colour.At(x, y), cmaa.colour.At(x, y)) << "frame " << t << " at " << x << "," << y;
          } else {
            changed += out.colour.At(x, y) != cmaa.colour.At(x, y) ? 1 : 0;
          }
        }
      }
    }
    // The check above is not vacuous: there are candidates, about half are TAA's, and the TAA
    // changes some of them.
    EXPECT_GT(candidates, 100);
    EXPECT_NEAR(static_cast<double>(taaCandidates) / candidates, 0.5, 0.1);
    EXPECT_GT(changed, 20) << StrategyName(strategy);
  }
}

TEST(PassesTscmaa, TheChosenShareIsTheFractionOnAnyShape) {
  int grid = 0, diagonal = 0, row = 0;
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) grid += ChosenForTaa(x, y, 0.5) ? 1 : 0;
    diagonal += ChosenForTaa(y, y, 0.5) ? 1 : 0;
    row += ChosenForTaa(y, 7, 0.5) ? 1 : 0;
  }
  EXPECT_NEAR(grid / 65536.0, 0.5, 0.01);
  EXPECT_NEAR(diagonal / 256.0, 0.5, 0.1);
  EXPECT_NEAR(row / 256.0, 0.5, 0.1);
  for (int i = 0; i < 1000; ++i) {
    EXPECT_FALSE(ChosenForTaa(i, 3 * i, 0.0));
    EXPECT_TRUE(ChosenForTaa(i, 3 * i, 1.0));
  }
}

// A static scene whose colour steps once: on every TAA candidate the output is
// lerp(current, history, 0.8) with the history clipped towards the current colour against the
// variance box of CMAA2's 3x3 in YCoCg (brute force here from CMAA2's image and the shared box
// helpers), within the 8-bit sRGB store's rounding.
TEST(PassesTscmaa, CandidatesBlendEightTenthsOfTheVarianceClippedHistory) {
  const auto make = [](int t) {
    TscmaaFrame frame = MovingDisk(0);
    frame.index = t;
    frame.velocity.Fill({0.0f, 0.0f});
    // Frame 1 on: the background brighter (the edges stay where they are).
    if (t >= 1) {
      for (glm::vec4& texel : frame.colour.Texels()) {
        if (texel.r < 0.5f) texel = glm::vec4(glm::vec3(texel) * 1.6f, 1.0f);
      }
    }
    return frame;
  };
  const std::unique_ptr<Pass> tscmaa = MakeTscmaa();
  const TscmaaSequence run = RunTscmaaSequence(*tscmaa, Strategy::DeferredQueue, make);
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const PassOutput cmaa1 = MakeCmaa2Tscmaa()->Run(machine, make(1).Inputs(), Strategy::DeferredQueue);
  const PassLayer& taa = LayerNamed(run.outputs[1], "taa-candidates");
  int clipped = 0, unclipped = 0;
  for (int y = 0; y < kTscmaaSide; ++y) {
    for (int x = 0; x < kTscmaaSide; ++x) {
      if (LayerValue(taa, x, y) == 0.0f) continue;
      const glm::vec3 c(cmaa1.colour.At(x, y)), h(run.outputs[0].colour.At(x, y));
      const temporal::ColourBox box = temporal::VarianceBox(
          temporal::MomentsOf(temporal::Neighbourhood::Box3x3,
                              [&](glm::ivec2 o) {
                                return sim::RgbToYCoCg(glm::vec3(cmaa1.colour.At(std::clamp(x + o.x, 0, kTscmaaSide - 1),
                                                                                 std::clamp(y + o.y, 0, kTscmaaSide - 1))));
                              }),
          1.0f);
      const glm::vec3 hy = sim::RgbToYCoCg(h);
      const glm::vec3 clip = temporal::ClipTowards(hy, box, temporal::ClampToBox(sim::RgbToYCoCg(c), box));
      (clip == hy ? unclipped : clipped) += 1;
      const glm::vec3 expected = c + (sim::YCoCgToRgb(clip) - c) * 0.8f;
      EXPECT_LT(glm::length(glm::vec3(run.outputs[1].colour.At(x, y)) - expected), 0.006f) << x << "," << y;
    }
  }
  // Both cases occur, and the blend is told apart from the current colour (unclipped, the
  // history is 0.8 of the way back to the darker frame 0).
  EXPECT_GT(clipped, 10);
  EXPECT_GT(unclipped, 10);
}

TEST(PassesTscmaa, StrategiesGiveBitIdenticalSequences) {
  const std::unique_ptr<Pass> stencil = MakeTscmaa(), queue = MakeTscmaa();
  const TscmaaSequence a = RunTscmaaSequence(*stencil, Strategy::StencilCulled), b = RunTscmaaSequence(*queue, Strategy::DeferredQueue);
  for (std::size_t t = 0; t < a.outputs.size(); ++t) {
    const StrategyDifference difference = CompareOutputs(a.outputs[t], b.outputs[t]);
    EXPECT_TRUE(difference.Identical()) << "frame " << t << ": " << difference.Describe();
    EXPECT_GT(a.outputs[t].workItems, 0u);
  }
}

TEST(PassesTscmaa, OneAndTwoThreadsGiveIdenticalSequences) {
  for (const Strategy strategy : kAllStrategies) {
    const auto runWith = [&](int threads) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
      const std::unique_ptr<Pass> pass = MakeTscmaa();
      return RunTscmaaSequence(*pass, strategy);
    };
    const TscmaaSequence one = runWith(1), two = runWith(2);
    for (std::size_t t = 0; t < one.outputs.size(); ++t) {
      EXPECT_TRUE(CompareOutputs(one.outputs[t], two.outputs[t]).Identical()) << "frame " << t;
    }
    sim::testing::ExpectSameReports(one.reports, two.reports);
  }
}

}  // namespace
}  // namespace passes::tscmaa
