// SMAA T2x and 4x (passes/smaa/smaa_temporal.h) over synthetic sequences: the per-frame subsample
// indices of aa-facts §1.8, the resolve's weight, convergence of a static scene to the average of
// the two frames' SMAA outputs, exact reprojection of an integer-shifted plane, and both strategies
// and 1 vs 2 threads over whole sequences.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <oneapi/tbb/global_control.h>

#include "passes/compare.h"
#include "passes/registry.h"
#include "passes/smaa/smaa.h"
#include "passes/smaa/smaa_pipeline.h"
#include "passes/smaa/smaa_temporal.h"
#include "passes/smaa/temporal_resolve.h"
#include "passes_test_util.h"
#include "raster/jitter_schedule.h"
#include "scenes/scene.h"
#include "sim/formats.h"
#include "sim/frame.h"
#include "sim/gpu_config.h"
#include "sim_test_util.h"
#include "study/frame_scene.h"

namespace passes {
namespace {

using testing::Codes;
using testing::GreyImage;

// One synthetic frame: linear colour and its velocity (pixels, current - previous).
struct SyntheticFrame {
  sim::Texture2D<glm::vec4> colour;
  sim::Texture2D<glm::vec2> velocity;
};
using FrameMaker = std::function<SyntheticFrame(int frame)>;

SyntheticFrame MakeFrame(int width, int height, const Codes& code, const std::function<glm::vec2(int, int)>& velocity) {
  SyntheticFrame frame{GreyImage(width, height, code), sim::Texture2D<glm::vec2>("velocity", width, height)};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) frame.velocity.At(x, y) = velocity(x, y);
  }
  return frame;
}

struct T2xSequenceRun {
  std::vector<PassOutput> outputs;
  std::vector<sim::DispatchReport> reports;
};

// Runs `frames` frames through one instance of `spec`.
T2xSequenceRun RunT2xSequence(std::string_view spec, int frames, const FrameMaker& make, Strategy strategy, int threads = 2) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const std::unique_ptr<Pass> pass = ResolvePass(spec).Make();
  T2xSequenceRun run;
  for (int k = 0; k < frames; ++k) {
    const SyntheticFrame frame = make(k);
    const sim::Texture2D<glm::vec4> srgb8 = Srgb8ColourTarget("colour-srgb8", frame.colour);
    run.outputs.push_back(pass->Run(
        machine, {.colour = &frame.colour, .colourSrgb8 = &srgb8, .velocity = &frame.velocity, .frameIndex = k},
        strategy));
  }
  run.reports = machine.Reports();
  return run;
}

int Code(const sim::Texture2D<glm::vec4>& image, int x, int y, int channel = 0) {
  return sim::FloatToSrgb8(image.At(x, y)[channel]);
}

// A smooth texture: neighbouring codes differ by at most 12 (gamma luma 0.047, below SMAA's 0.1
// threshold), so SMAA finds no edge and its output is its input.
int SmoothTexture(int x, int y) {
  return 128 + static_cast<int>(std::lround(40.0 * std::sin(0.3 * x) * std::cos(0.25 * y)));
}

// A moving box over a checkerboard, with the box's velocity: edges everywhere, a disocclusion.
SyntheticFrame T2xMovingBox(int frame) {
  constexpr int kStep = 3;
  const auto inBox = [frame](int x, int y) { return x >= 6 + kStep * frame && x < 18 + kStep * frame && y >= 10 && y < 24; };
  return MakeFrame(
      48, 40, [&](int x, int y) { return inBox(x, y) ? 230 : ((x / 8 + y / 8) % 2 == 0 ? 60 : 180); },
      [&](int x, int y) { return inBox(x, y) ? glm::vec2(kStep, 0) : glm::vec2(0); });
}

// ---- Subsample indices (aa-facts §1.8) ----

TEST(SmaaT2x, SubsampleIndicesFollowTheFrameParity) {
  EXPECT_EQ(smaa::T2xSubsampleIndices(0), glm::vec4(1, 1, 1, 0));
  EXPECT_EQ(smaa::T2xSubsampleIndices(1), glm::vec4(2, 2, 2, 0));
  EXPECT_EQ(smaa::T2xSubsampleIndices(6), glm::vec4(1, 1, 1, 0));
  EXPECT_EQ(smaa::T2xSubsampleIndices(7), glm::vec4(2, 2, 2, 0));
  using Pair = std::array<glm::vec4, 2>;
  EXPECT_EQ(smaa::FourXSubsampleIndices(0), (Pair{glm::vec4(5, 3, 1, 3), glm::vec4(4, 6, 2, 3)}));
  EXPECT_EQ(smaa::FourXSubsampleIndices(1), (Pair{glm::vec4(3, 5, 1, 4), glm::vec4(6, 4, 2, 4)}));
  EXPECT_EQ(smaa::FourXSubsampleIndices(2), smaa::FourXSubsampleIndices(0));
}

// SMAA 1x on `image` with the given subsample indices, into an RGBA8 sRGB target.
sim::Texture2D<glm::vec4> Smaa1xWith(const sim::Texture2D<glm::vec4>& image, glm::vec4 indices,
                                     sim::Texture2D<glm::vec4>* weights = nullptr) {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const PassSettings settings("smaa", smaa::Info<smaa::Variant::Luma>().settings);
  smaa::Smaa1x smaa("expected", smaa::ConfigOf(smaa::Variant::Luma, settings), {"e/edges", "e/weights", "e/blend"});
  smaa.SetSubsampleIndices(indices);
  const sim::Texture2D<glm::vec4> colour = Srgb8ColourTarget("expected/colour", image);
  sim::Texture2D<glm::vec4> target("expected/output", image.Width(), image.Height(), sim::Format::RGBA8Srgb);
  const smaa::Smaa1x::Frame frame =
      smaa.Run(machine, Strategy::StencilCulled, colour, nullptr, target, smaa::Blend::Replace);
  if (weights != nullptr) *weights = frame.targets.weights;
  return target;
}

// A slanted edge sampled at the t2x schedule's jitter: (+0.25, +0.25) px on even frames,
// (-0.25, -0.25) on odd ones (y down).
sim::Texture2D<glm::vec4> SlantedEdge(int frame) {
  const double j = frame % 2 == 0 ? 0.25 : -0.25;
  return GreyImage(32, 32, [j](int x, int y) { return x + 0.5 + j > 0.4 * (y + 0.5 + j) + 10.0 ? 200 : 40; });
}

TEST(SmaaT2x, EachFrameRunsSmaa1xWithItsFramesSubsampleIndices) {
  const T2xSequenceRun run = RunT2xSequence("smaa-t2x", 2, [](int k) { return MakeFrame(32, 32, [&](int x, int y) {
    return Code(SlantedEdge(k), x, y); }, [](int, int) { return glm::vec2(0); }); }, Strategy::DeferredQueue);
  int differing = 0;
  for (int k = 0; k < 2; ++k) {
    sim::Texture2D<glm::vec4> weights("w", 1, 1);
    Smaa1xWith(SlantedEdge(k), smaa::T2xSubsampleIndices(k), &weights);
    sim::Texture2D<glm::vec4> other("w", 1, 1);
    Smaa1xWith(SlantedEdge(k), smaa::T2xSubsampleIndices(k + 1), &other);
    const PassLayer& layer = testing::LayerNamed(run.outputs[static_cast<std::size_t>(k)], "weights");
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 32; ++x) {
        for (int c = 0; c < 4; ++c) {
          ASSERT_EQ(testing::LayerValue(layer, x, y, c), weights.Get(x, y)[c]) << k << " " << x << "," << y;
          differing += weights.Get(x, y)[c] != other.Get(x, y)[c];
        }
      }
    }
  }
  EXPECT_GT(differing, 0) << "the indices must matter on this image, or the test proves nothing";
}

// ---- The resolve (SMAAResolvePS, aa-facts §1.8) ----

TEST(SmaaT2xResolve, WeightFormulaMatchesHandComputedValues) {
  // Equal velocities: half the previous frame.
  EXPECT_FLOAT_EQ(smaa::ResolveWeight(0.3f, 0.3f, 30.0f), 0.5f);
  // |v_cur| = 0.0101, |v_prev| = 0.01 UV: delta = 1e-4, sqrt 0.01, 1 - 0.3 = 0.7, weight 0.35.
  EXPECT_NEAR(smaa::ResolveWeight(std::sqrt(5.0f * 0.0101f), std::sqrt(5.0f * 0.01f), 30.0f), 0.35f, 1e-5f);
  // |v| = 0.01 against a still pixel: sqrt(0.01) * 30 = 3, saturated to no history.
  EXPECT_EQ(smaa::ResolveWeight(std::sqrt(5.0f * 0.01f), 0.0f, 30.0f), 0.0f);
  // A zero scale keeps the average whatever the velocities.
  EXPECT_EQ(smaa::ResolveWeight(1.0f, 0.0f, 0.0f), 0.5f);
}

// Two flat frames (no edges: SMAA passes them through), frame 1 moving by 0.05 px: the output is
// lerp(current, previous, w) with w computed by hand from the 8-bit packed velocity lengths.
TEST(SmaaT2xResolve, TheOutputBlendsWithTheHandComputedWeight) {
  constexpr int kSize = 64, kFirst = 100, kSecond = 200;
  const auto flat = [](int k) {
    return MakeFrame(kSize, kSize, [k](int, int) { return k == 0 ? kFirst : kSecond; },
                     [k](int, int) { return k == 0 ? glm::vec2(0) : glm::vec2(0.05f, 0.0f); });
  };
  // v_uv = 0.05 / 64 = 7.8125e-4 (exact in RG16F); a = sqrt(5 v) = 0.0625 -> 8-bit code 16;
  // previous a = 0. delta = (16/255)^2 / 5; w = 0.5 (1 - 30 sqrt(delta)).
  const double a = 16.0 / 255.0;
  const double w = 0.5 * (1.0 - 30.0 * std::sqrt(a * a / 5.0));
  ASSERT_GT(w, 0.05);
  ASSERT_LT(w, 0.1);
  const double current = static_cast<double>(sim::Srgb8ToFloat(kSecond));
  const double previous = static_cast<double>(sim::Srgb8ToFloat(kFirst));
  const int expected = sim::FloatToSrgb8(static_cast<float>(current + w * (previous - current)));
  for (const char* spec : {"smaa-t2x", "smaa-t2x:reprojection=0"}) {
    const T2xSequenceRun run = RunT2xSequence(spec, 2, flat, Strategy::StencilCulled);
    const int average = sim::FloatToSrgb8(static_cast<float>(0.5 * (current + previous)));
    ASSERT_NE(expected, average);
    const bool reprojection = std::string_view(spec) == "smaa-t2x";
    for (const auto& [x, y] : {std::pair{0, 0}, std::pair{31, 17}, std::pair{63, 63}}) {
      EXPECT_EQ(Code(run.outputs[1].colour, x, y), reprojection ? expected : average) << spec;
    }
  }
}

// A static scene: every output from frame 1 on is the average of the two frames' SMAA 1x outputs
// (each with its subsample indices); frame 0, without a previous frame, is its own SMAA output.
TEST(SmaaT2x, AStaticSceneConvergesToTheAverageOfTheTwoFramesSmaaOutputs) {
  const sim::Texture2D<glm::vec4> even = Smaa1xWith(SlantedEdge(0), smaa::T2xSubsampleIndices(0));
  const sim::Texture2D<glm::vec4> odd = Smaa1xWith(SlantedEdge(1), smaa::T2xSubsampleIndices(1));
  const T2xSequenceRun run = RunT2xSequence("smaa-t2x", 4, [](int k) { return MakeFrame(32, 32, [&](int x, int y) {
    return Code(SlantedEdge(k), x, y); }, [](int, int) { return glm::vec2(0); }); }, Strategy::StencilCulled);
  const auto decoded = [](const sim::Texture2D<glm::vec4>& t, int x, int y) {
    return sim::Decode(sim::Format::RGBA8Srgb, t.Get(x, y));
  };
  int edgePixels = 0;
  for (int k = 0; k < 4; ++k) {
    const sim::Texture2D<glm::vec4>& current = k % 2 == 0 ? even : odd;
    const sim::Texture2D<glm::vec4>& previous = k % 2 == 0 ? odd : even;
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 32; ++x) {
        const glm::vec4 mine = decoded(current, x, y);
        const glm::vec4 expected =
            k == 0 ? mine
                   : sim::Decode(sim::Format::RGBA8Srgb,
                                 sim::Quantize(sim::Format::RGBA8Srgb, smaa::Lerp(mine, decoded(previous, x, y), 0.5f)));
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(run.outputs[static_cast<std::size_t>(k)].colour.At(x, y)[c], expected[c]) << k << " " << x << "," << y;
        }
        edgePixels += k == 1 && decoded(even, x, y) != decoded(odd, x, y);
      }
    }
  }
  EXPECT_GT(edgePixels, 20) << "the two frames must differ, or the average proves nothing";
}

// A smooth textured plane moving by (2, 1) px per frame with that velocity: the previous frame's
// output fetched at p - v is the same surface point, so inside the image the output is exactly the
// frame; without reprojection it blends two shifted images.
TEST(SmaaT2x, VelocityReprojectionOfAnIntegerShiftedPlaneIsExact) {
  constexpr int kSize = 40, kDx = 2, kDy = 1;
  const auto plane = [](int k) {
    return MakeFrame(kSize, kSize, [k](int x, int y) { return SmoothTexture(x - kDx * k, y - kDy * k); },
                     [](int, int) { return glm::vec2(kDx, kDy); });
  };
  const T2xSequenceRun reprojected = RunT2xSequence("smaa-t2x", 4, plane, Strategy::DeferredQueue);
  const T2xSequenceRun averaged = RunT2xSequence("smaa-t2x:reprojection=0", 4, plane, Strategy::DeferredQueue);
  int differing = 0;
  for (int k = 1; k < 4; ++k) {
    const SyntheticFrame frame = plane(k);
    for (int y = kDy; y < kSize; ++y) {
      for (int x = kDx; x < kSize; ++x) {
        ASSERT_EQ(Code(reprojected.outputs[static_cast<std::size_t>(k)].colour, x, y), Code(frame.colour, x, y))
            << k << " " << x << "," << y;
        differing += Code(averaged.outputs[static_cast<std::size_t>(k)].colour, x, y) != Code(frame.colour, x, y);
      }
    }
  }
  EXPECT_GT(differing, 100);
}

// ---- Strategies and threads over a sequence ----

TEST(SmaaT2x, StrategiesGiveIdenticalImagesOverASequence) {
  for (const char* spec : {"smaa-t2x", "smaa-t2x:reprojection=0"}) {
    const T2xSequenceRun stencil = RunT2xSequence(spec, 5, T2xMovingBox, Strategy::StencilCulled);
    const T2xSequenceRun queue = RunT2xSequence(spec, 5, T2xMovingBox, Strategy::DeferredQueue);
    for (std::size_t k = 0; k < stencil.outputs.size(); ++k) {
      EXPECT_GT(stencil.outputs[k].workItems, 0u);
      const StrategyDifference difference = CompareOutputs(stencil.outputs[k], queue.outputs[k]);
      EXPECT_TRUE(difference.Identical()) << spec << " frame " << k << ": " << difference.Describe();
    }
  }
}

TEST(SmaaT2x, OneAndTwoThreadsGiveIdenticalImagesAndCountersOverASequence) {
  for (const Strategy strategy : kAllStrategies) {
    const T2xSequenceRun one = RunT2xSequence("smaa-t2x", 4, T2xMovingBox, strategy, 1);
    const T2xSequenceRun two = RunT2xSequence("smaa-t2x", 4, T2xMovingBox, strategy, 2);
    for (std::size_t k = 0; k < one.outputs.size(); ++k) {
      EXPECT_TRUE(CompareOutputs(one.outputs[k], two.outputs[k]).Identical()) << StrategyName(strategy) << " " << k;
    }
    sim::testing::ExpectSameReports(one.reports, two.reports);
  }
}

// The history is a machine resource: the resolve reads both targets' bytes.
TEST(SmaaT2x, TheResolveReadsTheHistoryTargetsBytes) {
  const T2xSequenceRun run = RunT2xSequence("smaa-t2x", 2, T2xMovingBox, Strategy::StencilCulled);
  std::uint64_t historyBytes = 0;
  for (const sim::DispatchReport& report : run.reports) {
    if (report.name != "smaa-t2x/resolve") continue;
    for (const sim::ResourceTraffic& resource : report.resources) {
      if (resource.name.rfind("smaa-t2x/history", 0) == 0) historyBytes += resource.bytesRead;
    }
  }
  // Two frames, each reading a 4-byte texel of the current and the previous target per pixel.
  EXPECT_EQ(historyBytes, 2u * 2u * 4u * 48u * 40u);
}

// ---- 4x: S2x per frame on a rendered 2-sample surface ----

T2xSequenceRun RunFourX(Strategy strategy, int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  constexpr int kWidth = 64, kHeight = 40;
  const float aspect = static_cast<float>(kWidth) / kHeight;
  const study::FrameScene scene = study::ToFrameScene(scenes::LoadScene("builtin:default", aspect), aspect);
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const raster::JitterSchedule schedule = raster::JitterSchedule::Make("4x", raster::MakeBuiltinPattern("standard", 2));
  sim::FrameSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.eqaa = {2, 2, 2};
  settings.pattern = schedule.At(0);
  sim::FramePipeline pipeline(machine, settings);
  const std::unique_ptr<Pass> pass = ResolvePass("smaa-4x").Make();
  T2xSequenceRun run;
  for (int k = 0; k < 3; ++k) {
    pipeline.Render(scene.Geometry(), {.pattern = &schedule.At(k), .frameIndex = k});
    machine.ClearReports();
    run.outputs.push_back(pass->Run(machine, FrameInputsOf(pipeline), strategy));
    const std::vector<sim::DispatchReport> reports = machine.Reports();
    run.reports.insert(run.reports.end(), reports.begin(), reports.end());
  }
  return run;
}

TEST(SmaaFourX, StrategiesAndThreadsGiveIdenticalImagesAndCountersOverASequence) {
  const T2xSequenceRun stencil = RunFourX(Strategy::StencilCulled, 2);
  const T2xSequenceRun queue = RunFourX(Strategy::DeferredQueue, 2);
  const T2xSequenceRun queueOneThread = RunFourX(Strategy::DeferredQueue, 1);
  for (std::size_t k = 0; k < stencil.outputs.size(); ++k) {
    EXPECT_GT(stencil.outputs[k].workItems, 0u);
    EXPECT_TRUE(CompareOutputs(stencil.outputs[k], queue.outputs[k]).Identical()) << k;
    EXPECT_TRUE(CompareOutputs(queue.outputs[k], queueOneThread.outputs[k]).Identical()) << k;
  }
  sim::testing::ExpectSameReports(queue.reports, queueOneThread.reports);
  // Frame 1's sample runs use the second frame's indices: its weights differ from frame 0's on a
  // static scene.
  EXPECT_NE(testing::LayerNamed(stencil.outputs[0], "weights.s0").Floats(),
            testing::LayerNamed(stencil.outputs[1], "weights.s0").Floats());
}

}  // namespace
}  // namespace passes
