// UE4 temporal AA (passes/taa_ue4/): convergence of a static jittered scene to its supersampled
// value within a derived bound, exact reprojection of a plane translated by whole pixels, the
// rejection of disoccluded history, responsive pixels, the anti-flicker rule, and determinism
// over a sequence.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <oneapi/tbb/global_control.h>

#include "passes/compare.h"
#include "passes/taa_ue4/taa_ue4.h"
#include "passes/taa_ue4/taa_ue4_math.h"
#include "passes_test_util.h"
#include "raster/jitter_schedule.h"
#include "sim/gpu_config.h"
#include "sim_test_util.h"

namespace passes::taa_ue4 {
namespace {

// One synthetic frame: every target the pass reads.
struct TaaFrame {
  sim::Texture2D<glm::vec4> colour;
  sim::Texture2D<float> depth;
  sim::Texture2D<glm::vec2> velocity;
  sim::Texture2D<std::uint32_t> objectId;
  glm::vec2 jitter{0.0f};
  int index = 0;

  TaaFrame(int w, int h)
      : colour("colour", w, h, 16), depth("depth", w, h, 4, 0.9f), velocity("velocity", w, h, 8), objectId("id", w, h, 4) {}
  FrameInputs Inputs() const {
    return {.colour = &colour, .depth = &depth, .normal = nullptr, .objectId = &objectId, .velocity = &velocity,
            .eqaa = nullptr, .pattern = nullptr, .frameIndex = index, .jitter = jitter};
  }
};

glm::vec2 HaltonJitter(int frame) {
  static const raster::JitterSchedule schedule =
      raster::JitterSchedule::Make("halton8", raster::MakeBuiltinPattern("standard", 1));
  return PatternJitter(schedule.At(frame));
}

std::unique_ptr<Pass> MakeTaa(const std::vector<std::pair<std::string_view, double>>& values = {}) {
  PassSettings settings(Info().name, Info().settings);
  for (const auto& [key, value] : values) settings.Set(key, value);
  return Make(settings);
}

struct TaaSequence {
  std::vector<PassOutput> outputs;
  std::vector<sim::DispatchReport> reports;
};

// Runs `frames` frames made by `make(index)` through one instance.
TaaSequence RunTaaSequence(Pass& pass, int frames, const std::function<TaaFrame(int)>& make,
                     Strategy strategy = Strategy::StencilCulled) {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  TaaSequence sequence;
  for (int t = 0; t < frames; ++t) {
    const TaaFrame frame = make(t);
    sequence.outputs.push_back(pass.Run(machine, frame.Inputs(), strategy));
  }
  sequence.reports = machine.Reports();
  return sequence;
}

std::uint64_t CounterSum(const std::vector<sim::DispatchReport>& reports, std::string_view name) {
  std::uint64_t sum = 0;
  for (const sim::DispatchReport& report : reports) {
    for (const sim::PassCounter& counter : report.passCounters) {
      if (counter.name == name) sum += counter.value;
    }
  }
  return sum;
}

// ---- convergence ----

constexpr int kTaaSide = 32;
constexpr float kTaaDark = 0.2f, kTaaBright = 0.8f;

// Two vertical edges at non-integer positions (or, transposed, horizontal ones): a band of
// bright between them.
float Band(glm::vec2 p, bool transposed) {
  const float u = transposed ? p.y : p.x;
  return u >= 13.3f && u < 22.75f ? kTaaBright : kTaaDark;
}

TaaFrame JitteredBand(int t, bool transposed) {
  TaaFrame frame(kTaaSide, kTaaSide);
  frame.index = t;
  frame.jitter = HaltonJitter(t);
  for (int y = 0; y < kTaaSide; ++y) {
    for (int x = 0; x < kTaaSide; ++x) {
      const float v = Band(glm::vec2(x, y) + 0.5f + frame.jitter, transposed);
      frame.colour.At(x, y) = glm::vec4(v, v, v, 1.0f);
    }
  }
  return frame;
}

// What the pass takes as the current frame at pixel (x, y) of frame t without luma weights: the
// pixel's own sample, or the Gaussian reconstruction of its 3x3 (in double).
double CurrentValue(const TaaFrame& frame, int x, int y, bool reconstruction) {
  if (!reconstruction) return static_cast<double>(frame.colour.At(x, y).r);
  double sum = 0.0, weights = 0.0;
  for (int oy = -1; oy <= 1; ++oy) {
    for (int ox = -1; ox <= 1; ++ox) {
      const double dx = ox + static_cast<double>(frame.jitter.x), dy = oy + static_cast<double>(frame.jitter.y);
      const double w = std::exp(-2.29 * (dx * dx + dy * dy));
      sum += w * static_cast<double>(frame.colour.At(std::clamp(x + ox, 0, kTaaSide - 1), std::clamp(y + oy, 0, kTaaSide - 1)).r);
      weights += w;
    }
  }
  return sum / weights;
}

// The exponential blend out_t = out_{t-1} + alpha (x_t - out_{t-1}), started at out_0 = x_0, on an
// input of period n = 8 (the Halton schedule):
//   transient: |out_F - s_F| <= (1 - alpha)^F |x_0 - s_0| <= (1 - alpha)^F R, with s the periodic
//     steady state and R the pixel's range of x over the period;
//   bias: s_t = alpha / (1 - (1 - alpha)^n) sum_k (1 - alpha)^k x_{t-k} (seed 002 "Exponential
//     smoothing"), so |s_t - mean| <= R / 2 * sum_k |w_k - 1/n| (the weights w_k sum to 1);
//   storage: each frame's RGBA16_FLOAT store rounds toward zero (D3D11 §3.2.2, sim/formats.cpp),
//     losing less than one ulp (2^-11 below 1), and the blend shrinks past errors by (1 - alpha),
//     so they add up to less than 2^-11 / alpha (0.012 at alpha 0.04), always downwards: once
//     alpha |x - h| is below an ulp the store gives h back and the average stalls low.
double Tolerance(double range, int frames, double alpha) {
  constexpr int kPeriod = 8;
  const double scale = alpha / (1.0 - std::pow(1.0 - alpha, kPeriod));
  double spread = 0.0;
  for (int k = 0; k < kPeriod; ++k) spread += std::abs(scale * std::pow(1.0 - alpha, k) - 1.0 / kPeriod);
  return std::pow(1.0 - alpha, frames) * range + 0.5 * spread * range + std::ldexp(1.0, -11) / alpha + 1e-5;
}

void ExpectConvergence(bool reconstruction, bool transposed) {
  constexpr int kFrames = 120;
  constexpr double kAlpha = 0.04;
  // Without luma weights and anti-flicker the blend is the plain exponential average the bound is
  // derived for. The shaped-box clip stays on when the current frame is the own sample: a pixel
  // straddling a band edge has both levels in its '+' at every jitter, and the others never vary,
  // so it only ever undoes the store's rounding. The Gaussian-reconstructed average can leave the
  // raw samples' box, so that case runs unconstrained.
  const std::unique_ptr<Pass> pass =
      MakeTaa({{"luma_weight", 0}, {"anti_flicker", 0}, {"reconstruction", reconstruction ? 1 : 0},
               {"constraint", reconstruction ? 0 : 2}});
  const TaaSequence run = RunTaaSequence(*pass, kFrames + 1, [&](int t) { return JitteredBand(t, transposed); });
  std::vector<TaaFrame> period;
  for (int t = 0; t < 8; ++t) period.push_back(JitteredBand(t, transposed));
  double firstWorst = 0.0, lastWorst = 0.0;
  int varying = 0;
  for (int y = 0; y < kTaaSide; ++y) {
    for (int x = 0; x < kTaaSide; ++x) {
      double mean = 0.0, lo = 1e9, hi = -1e9;
      for (const TaaFrame& frame : period) {
        const double v = CurrentValue(frame, x, y, reconstruction);
        mean += v / 8.0;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      varying += hi - lo > 0.1 ? 1 : 0;
      const double first = std::abs(static_cast<double>(run.outputs.front().colour.At(x, y).r) - mean);
      const double last = std::abs(static_cast<double>(run.outputs.back().colour.At(x, y).r) - mean);
      firstWorst = std::max(firstWorst, first);
      lastWorst = std::max(lastWorst, last);
      EXPECT_LE(last, Tolerance(hi - lo, kFrames, kAlpha)) << x << "," << y << " range " << hi - lo;
    }
  }
  // The bound means something: frame 0 (no history) is far off on the edge pixels.
  EXPECT_GE(varying, 2 * kTaaSide);  // the two straddling columns at least
  EXPECT_GT(firstWorst, 0.1);
  EXPECT_LT(lastWorst, 0.05);
}

TEST(PassesTaaUe4, AStaticSceneConvergesToItsSupersampledValue) {
  for (const bool transposed : {false, true}) {
    ExpectConvergence(false, transposed);
    ExpectConvergence(true, transposed);
  }
}

// With luma weights, anti-flicker and the shaped-box clip on, the blend is no longer a plain
// exponential average (bright samples count less, weights drop near the box's faces), so no
// closed-form bound: the error on the edge pixels against the supersampled value still falls to
// under half of frame 0's. (With the Gaussian reconstruction on too, frame 0 of this scene is
// already within 0.01 of the reconstruction's supersampled value; the derived bound above covers
// it.)
TEST(PassesTaaUe4, WithWeightsAndClippingTheErrorFallsAsFramesAccumulate) {
  const std::unique_ptr<Pass> pass = MakeTaa({{"reconstruction", 0}});
  const TaaSequence run = RunTaaSequence(*pass, 121, [](int t) { return JitteredBand(t, false); });
  std::vector<TaaFrame> period;
  for (int t = 0; t < 8; ++t) period.push_back(JitteredBand(t, false));
  const auto edgeError = [&](const PassOutput& output) {
    double sum = 0.0;
    int pixels = 0;
    for (int y = 0; y < kTaaSide; ++y) {
      for (int x = 0; x < kTaaSide; ++x) {
        double mean = 0.0, lo = 1.0, hi = 0.0;
        for (const TaaFrame& frame : period) {
          const double v = CurrentValue(frame, x, y, false);
          mean += v / 8.0;
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
        if (hi == lo) continue;
        sum += std::abs(static_cast<double>(output.colour.At(x, y).r) - mean);
        ++pixels;
      }
    }
    return sum / pixels;
  };
  const double first = edgeError(run.outputs[0]), mid = edgeError(run.outputs[40]), last = edgeError(run.outputs[120]);
  EXPECT_LT(mid, first);
  EXPECT_LT(last, 0.5 * first) << first << " " << mid << " " << last;
}

// ---- reprojection ----

constexpr int kPlaneW = 48, kPlaneH = 32;

// A texture of k/64 values (exact in half floats) on a plane.
glm::vec4 PlaneTexel(int u, int v) {
  const auto m = [](int a, int n) { return ((a % n) + n) % n; };
  return {static_cast<float>(m(u * 7 + v * 13, 17)) / 64.0f + 0.25f, static_cast<float>(m(u * 3 + v * 5, 11)) / 64.0f,
          static_cast<float>(m(u + v * 2, 5)) / 64.0f + 0.5f, 1.0f};
}

TaaFrame TranslatedPlane(int t, glm::ivec2 shift, glm::vec2 reportedVelocity) {
  TaaFrame frame(kPlaneW, kPlaneH);
  frame.index = t;
  for (int y = 0; y < kPlaneH; ++y) {
    for (int x = 0; x < kPlaneW; ++x) {
      frame.colour.At(x, y) = PlaneTexel(x - t * shift.x, y - t * shift.y);
      frame.velocity.At(x, y) = reportedVelocity;
      frame.depth.At(x, y) = 0.5f;
    }
  }
  return frame;
}

// The current frame is the history shifted by the velocity: the 5-tap filter at a whole-pixel
// offset returns the history texel, which equals the current sample, inside any box, and the
// blend h + beta (c - h) gives it back bit for bit. Off the screen the current sample is taken.
// So every output is the translated texture exactly, at every pixel, frame after frame (the
// Gaussian reconstruction off, so the current frame is the texel itself).
TEST(PassesTaaUe4, VelocityReprojectionOfATranslatingPlaneIsExactForWholePixelShifts) {
  for (const glm::ivec2 shift : {glm::ivec2(2, 1), glm::ivec2(-1, 3), glm::ivec2(0, -2)}) {
    const std::unique_ptr<Pass> pass = MakeTaa({{"reconstruction", 0}});
    const TaaSequence run = RunTaaSequence(*pass, 6, [&](int t) { return TranslatedPlane(t, shift, glm::vec2(shift)); });
    for (int t = 0; t < 6; ++t) {
      const TaaFrame expected = TranslatedPlane(t, shift, glm::vec2(shift));
      for (int y = 0; y < kPlaneH; ++y) {
        for (int x = 0; x < kPlaneW; ++x) {
          ASSERT_EQ(run.outputs[static_cast<std::size_t>(t)].colour.At(x, y), expected.colour.At(x, y))
              << "shift " << shift.x << "," << shift.y << " frame " << t << " at " << x << "," << y;
        }
      }
    }
  }
  // The same motion reported as no motion smears: the history no longer matches.
  const std::unique_ptr<Pass> pass = MakeTaa({{"reconstruction", 0}});
  const TaaSequence run = RunTaaSequence(*pass, 3, [](int t) { return TranslatedPlane(t, {2, 1}, glm::vec2(0.0f)); });
  int wrong = 0;
  const TaaFrame expected = TranslatedPlane(2, {2, 1}, glm::vec2(0.0f));
  for (int y = 0; y < kPlaneH; ++y) {
    for (int x = 0; x < kPlaneW; ++x) wrong += run.outputs[2].colour.At(x, y) != expected.colour.At(x, y) ? 1 : 0;
  }
  EXPECT_GT(wrong, kPlaneW * kPlaneH / 2);
}

// ---- disocclusion ----

constexpr int kBoxSide = 6;
constexpr glm::vec3 kTaaBoxColour{0.9f, 0.5f, 0.1f};

// A 6x6 box moving right 2 px per frame over a flat background; the box is nearer.
TaaFrame TaaMovingBox(int t, bool texturedBackground = false) {
  TaaFrame frame(40, 24);
  frame.index = t;
  for (int y = 0; y < 24; ++y) {
    for (int x = 0; x < 40; ++x) {
      const float background = texturedBackground ? 0.15f + 0.1f * static_cast<float>((x * 3 + y * 5) % 4) : kTaaDark;
      frame.colour.At(x, y) = glm::vec4(glm::vec3(background), 1.0f);
      if (x >= 4 + 2 * t && x < 4 + 2 * t + kBoxSide && y >= 9 && y < 9 + kBoxSide) {
        frame.colour.At(x, y) = glm::vec4(kTaaBoxColour, 1.0f);
        frame.velocity.At(x, y) = {2.0f, 0.0f};
        frame.depth.At(x, y) = 0.3f;
        frame.objectId.At(x, y) = 7;
      }
    }
  }
  return frame;
}

// Chebyshev distance from (x, y) to frame t's box.
int DistanceToBox(int t, int x, int y) {
  const int x0 = 4 + 2 * t, y0 = 9;
  const int dx = std::max({x0 - x, x - (x0 + kBoxSide - 1), 0}), dy = std::max({y0 - y, y - (y0 + kBoxSide - 1), 0});
  return std::max(dx, dy);
}

// Pixels two or more away from the box's current footprint see only background in their 3x3,
// so the shaped box is the background colour alone and the box's old colour is clipped to it:
// no ghost from the first frame after the box leaves (N = 1). Within one pixel the box is in the
// neighbourhood (and its velocity dilated onto the pixel), so it is not checked.
TEST(PassesTaaUe4, ADisocclusionLeavesNoGhost) {
  constexpr int kFrames = 10;
  const std::unique_ptr<Pass> pass = MakeTaa();
  const TaaSequence run = RunTaaSequence(*pass, kFrames, [](int t) { return TaaMovingBox(t); });
  EXPECT_GT(CounterSum(run.reports, "taa-ue4/history_clipped"), 0u);
  for (int t = 1; t < kFrames; ++t) {
    for (int y = 0; y < 24; ++y) {
      for (int x = 0; x < 40; ++x) {
        if (DistanceToBox(t, x, y) < 2) continue;
        const glm::vec4 out = run.outputs[static_cast<std::size_t>(t)].colour.At(x, y);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(out[c], kTaaDark, 1e-3f) << "frame " << t << " at " << x << "," << y;
      }
    }
  }
  // Unconstrained, the trail keeps the box's colour (what the test would see without the clip).
  const std::unique_ptr<Pass> unconstrained = MakeTaa({{"constraint", 0}});
  const TaaSequence ghosted = RunTaaSequence(*unconstrained, kFrames, [](int t) { return TaaMovingBox(t); });
  EXPECT_GT(ghosted.outputs.back().colour.At(5, 11).r, kTaaDark + 0.02f);
}

// ---- responsive pixels and anti-flicker ----

TEST(PassesTaaUe4, ResponsivePixelsTakeTheResponsiveWeight) {
  const auto make = [](int t) {
    TaaFrame frame(16, 16);
    frame.index = t;
    for (int y = 0; y < 16; ++y) {
      for (int x = 0; x < 16; ++x) {
        frame.objectId.At(x, y) = x < 8 ? 7 : 3;
        const float v = t == 0 ? kTaaDark : 0.6f;
        frame.colour.At(x, y) = glm::vec4(v, v, v, 1.0f);
      }
    }
    return frame;
  };
  const std::unique_ptr<Pass> pass =
      MakeTaa({{"responsive_object", 7}, {"constraint", 0}, {"luma_weight", 0}, {"reconstruction", 0}});
  const TaaSequence run = RunTaaSequence(*pass, 2, make);
  EXPECT_NEAR(run.outputs[1].colour.At(3, 5).r, kTaaDark + 0.8f * (0.6f - kTaaDark), 1e-3f);   // responsive_alpha 0.8
  EXPECT_NEAR(run.outputs[1].colour.At(12, 5).r, kTaaDark + 0.04f * (0.6f - kTaaDark), 1e-3f);  // alpha 0.04
  EXPECT_EQ(CounterSum(run.reports, "taa-ue4/responsive_pixels"), 8u * 16u);
}

TEST(PassesTaaUe4, AntiFlickerLowersTheCurrentWeightTowardsTheBoxFaces) {
  EXPECT_FLOAT_EQ(AntiFlickerAlpha(0.04f, 0.5f, 0.0f, 1.0f, 1.0f), 0.04f);   // centre: alpha
  EXPECT_FLOAT_EQ(AntiFlickerAlpha(0.04f, 1.0f, 0.0f, 1.0f, 1.0f), 0.0f);    // face, full strength
  EXPECT_FLOAT_EQ(AntiFlickerAlpha(0.04f, 0.0f, 0.0f, 1.0f, 0.5f), 0.02f);   // face, half strength
  EXPECT_FLOAT_EQ(AntiFlickerAlpha(0.04f, 0.25f, 0.0f, 1.0f, 1.0f), 0.04f * 0.6f);  // 3 * 0.25 / 1.25
  EXPECT_FLOAT_EQ(AntiFlickerAlpha(0.04f, 0.3f, 0.3f, 0.3f, 1.0f), 0.04f);   // a flat box
  EXPECT_FLOAT_EQ(AntiFlickerAlpha(0.04f, 0.9f, 0.0f, 1.0f, 0.0f), 0.04f);   // off
  // Luma-weighted blend: equal weights give alpha; a brighter current sample counts less.
  EXPECT_FLOAT_EQ(CurrentShare(0.04f, 0.5f, 0.5f), 0.04f);
  EXPECT_LT(CurrentShare(0.04f, 0.25f, 0.5f), 0.04f);
  EXPECT_FLOAT_EQ(ReconstructionWeight({1.0f, 0.0f}), std::exp(-2.29f));
}

// A bright line 0.3 px wide, hit by the jittered samples in 2 of the 8 frames: clipping pulls
// the history to the dark box on the frames that miss it and the hits push it back up, a
// sawtooth (seed 002 "Flickering"). The anti-flicker rule lowers the current weight where the
// history sits near a face of the box, so the frame-to-frame change of the output is smaller.
TEST(PassesTaaUe4, AntiFlickerReducesTheFlickerOfASubPixelLine) {
  const auto make = [](int t) {
    TaaFrame frame(kTaaSide, kTaaSide);
    frame.index = t;
    frame.jitter = HaltonJitter(t);
    for (int y = 0; y < kTaaSide; ++y) {
      for (int x = 0; x < kTaaSide; ++x) {
        const float u = static_cast<float>(x) + 0.5f + frame.jitter.x;
        const float v = u >= 13.3f && u < 13.6f ? kTaaBright : kTaaDark;
        frame.colour.At(x, y) = glm::vec4(v, v, v, 1.0f);
      }
    }
    return frame;
  };
  const auto flicker = [&](double strength) {
    const std::unique_ptr<Pass> pass = MakeTaa({{"anti_flicker", strength}});
    const TaaSequence run = RunTaaSequence(*pass, 120, make);
    double sum = 0.0;
    for (std::size_t t = 64; t < run.outputs.size(); ++t) {
      for (int x = 11; x <= 15; ++x) {
        sum += std::abs(static_cast<double>(run.outputs[t].colour.At(x, 16).r - run.outputs[t - 1].colour.At(x, 16).r));
      }
    }
    return sum;
  };
  const double with = flicker(1.0), without = flicker(0.0);
  EXPECT_LT(with, 0.8 * without) << with << " vs " << without;
}

// ---- determinism ----

TEST(PassesTaaUe4, OneAndTwoThreadsGiveIdenticalSequences) {
  const auto make = [](int t) {
    TaaFrame frame = TaaMovingBox(t, true);
    frame.jitter = HaltonJitter(t);
    return frame;
  };
  const auto runWith = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    const std::unique_ptr<Pass> pass = MakeTaa({{"responsive_object", 7}});
    return RunTaaSequence(*pass, 8, make);
  };
  const TaaSequence one = runWith(1), two = runWith(2);
  ASSERT_EQ(one.outputs.size(), two.outputs.size());
  for (std::size_t t = 0; t < one.outputs.size(); ++t) {
    EXPECT_TRUE(CompareOutputs(one.outputs[t], two.outputs[t]).Identical()) << "frame " << t;
  }
  sim::testing::ExpectSameReports(one.reports, two.reports);
}

}  // namespace
}  // namespace passes::taa_ue4
