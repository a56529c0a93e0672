// HRAA's temporal part (passes/hraa/): the temporal FLIPQUAD resolve's per-pixel combination,
// convergence on a static scene, the motion-flow and colour-flow tests, the history resampling
// forms on integer shifts, the seed's BFECC experiment, the unsharp mask and determinism. Frames
// are synthetic: an analytic scene sampled at each pixel's sample position of the frame's
// flipquad-split pattern, with the matching velocity.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <oneapi/tbb/global_control.h>

#include <glm/geometric.hpp>

#include "passes/compare.h"
#include "passes/hraa/history_resample.h"
#include "passes/hraa/tfq.h"
#include "passes/registry.h"
#include "passes_test_util.h"
#include "raster/coverage_mask.h"
#include "raster/jitter_schedule.h"
#include "raster_test_util.h"
#include "sim/colour.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"
#include "sim_test_util.h"

namespace passes {
namespace {

using Scene = std::function<glm::vec3(glm::vec2 position)>;       // linear colour at a point (px)
using Motion = std::function<glm::vec2(glm::vec2 position)>;      // velocity (px) of what is there

const raster::JitterSchedule& FlipQuadSplit() {
  static const raster::JitterSchedule schedule =
      raster::JitterSchedule::Make("flipquad-split", raster::MakeBuiltinPattern("standard", 1));
  return schedule;
}

// The position of pixel (x, y)'s one sample in frame k of flipquad-split.
glm::vec2 SamplePosition(int x, int y, int k) {
  const raster::SampleOffset offset = FlipQuadSplit().At(k).Offset(raster::QuadPixelIndex(x, y), 0);
  return {static_cast<float>(x) + 0.5f + static_cast<float>(offset.x) / 16.0f,
          static_cast<float>(y) + 0.5f + static_cast<float>(offset.y) / 16.0f};
}

struct HraaFrame {
  sim::Texture2D<glm::vec4> colour;
  sim::Texture2D<glm::vec2> velocity;
  const raster::SamplePattern* pattern;
  int index;
  mutable std::optional<sim::Texture2D<glm::vec4>> srgb8;  // made by Inputs from the colour

  FrameInputs Inputs() const {
    srgb8 = Srgb8ColourTarget("colour-srgb8", colour);
    return {.colour = &colour, .colourSrgb8 = &*srgb8, .velocity = &velocity, .pattern = pattern, .frameIndex = index};
  }
};

// Frame k: the scene at every pixel's flipquad-split sample (pixel centres when `centres`).
HraaFrame RenderHraa(int width, int height, int k, const Scene& scene, const Motion& motion = {}, bool centres = false) {
  HraaFrame frame{{"colour", width, height, 16}, {"velocity", width, height, 8}, centres ? nullptr : &FlipQuadSplit().At(k), k,
                  std::nullopt};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec2 at = centres ? glm::vec2(x + 0.5f, y + 0.5f) : SamplePosition(x, y, k);
      frame.colour.At(x, y) = glm::vec4(scene(at), 1.0f);
      frame.velocity.At(x, y) = motion ? motion(at) : glm::vec2(0.0f);
    }
  }
  return frame;
}

// What the renderer's RGBA8 sRGB target gives back for a linear value.
float StoredSrgb8(float linear) { return sim::Srgb8ToFloat(sim::FloatToSrgb8(linear)); }
glm::vec3 StoredSrgb8(const glm::vec3& c) { return {StoredSrgb8(c.r), StoredSrgb8(c.g), StoredSrgb8(c.b)}; }

std::unique_ptr<Pass> MakePass(std::string_view spec) {
  const PassConfig config = ResolvePass(spec);
  return config.pass->make(config.settings);
}

sim::Machine MakeMachine() { return sim::Machine(sim::GpuConfigByName("ps4-class")); }

int Validity(const PassOutput& output, int x, int y) {
  return static_cast<int>(testing::LayerValue(testing::LayerNamed(output, "validity"), x, y));
}

// ---- the TFQ resolve ------------------------------------------------------------------------

// A diagonal edge for the phase tests.
glm::vec3 StaticSceneForPhases(glm::vec2 p) { return glm::vec3(p.x + p.y > 11.3f ? 0.8f : 0.1f); }

// Frames A, B, A, B of a hand-made image per phase: with N-2 = N and no motion, every pixel is
// 1/4 [A(x,y) + A(x+1,y) + B(x,y) + B(x,y+1)] (tfq.h), the right and bottom neighbours clamped.
TEST(PassesHraa, TfqResolveAveragesTheFourFlipQuadPointsOfTwoFrames) {
  const int w = 16, h = 12;
  const auto a = [](int x, int y) { return glm::vec3(0.05f + 0.05f * static_cast<float>((x * 7 + y * 3) % 17), 0.3f, 0.1f * static_cast<float>(y % 5)); };
  const auto b = [](int x, int y) { return glm::vec3(0.9f - 0.04f * static_cast<float>((x * 5 + y * 11) % 19), 0.6f, 0.08f * static_cast<float>(x % 7)); };
  const auto image = [&](int k) {
    HraaFrame frame{{"colour", w, h, 16}, {"velocity", w, h, 8}, &FlipQuadSplit().At(k), k, std::nullopt};
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) frame.colour.At(x, y) = glm::vec4(k % 2 == 0 ? a(x, y) : b(x, y), 1.0f);
    }
    frame.velocity.Fill(glm::vec2(0.0f));
    return frame;
  };
  sim::Machine machine = MakeMachine();
  const std::unique_ptr<Pass> pass = MakePass("tfq");
  for (int k = 0; k < 4; ++k) {
    const PassOutput output = pass->Run(machine, image(k).Inputs(), Strategy::StencilCulled);
    const int expectValidity = k == 0 ? 0 : k == 1 ? static_cast<int>(hraa::TfqValidity::ColourLimited)
                                                   : static_cast<int>(hraa::TfqValidity::Accepted);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        ASSERT_EQ(Validity(output, x, y), expectValidity) << k << " " << x << "," << y;
        if (k < 2) continue;
        const int right = std::min(x + 1, w - 1), below = std::min(y + 1, h - 1);
        const glm::vec3 expected = 0.25f * (StoredSrgb8(a(x, y)) + StoredSrgb8(a(right, y)) + StoredSrgb8(b(x, y)) + StoredSrgb8(b(x, below)));
        for (int c = 0; c < 3; ++c) {
          ASSERT_NEAR(output.colour.At(x, y)[c], expected[c], 2e-3f * expected[c] + 1e-6f) << k << " " << x << "," << y;
        }
      }
    }
  }
}

// Two frames of the same half (schedule "none" repeats one pattern) do not complete the pattern:
// the second frame interpolates from itself as frame 0 does, and a new sequence starts over.
TEST(PassesHraa, APreviousFrameOfTheSamePhaseIsNoHistory) {
  const int w = 12, h = 10;
  sim::Machine machine = MakeMachine();
  const std::unique_ptr<Pass> pass = MakePass("tfq");
  HraaFrame first = RenderHraa(w, h, 0, StaticSceneForPhases);
  const PassOutput zero = pass->Run(machine, first.Inputs(), Strategy::StencilCulled);
  first.index = 1;  // frame 1 drawn with frame 0's pattern
  const PassOutput again = pass->Run(machine, first.Inputs(), Strategy::StencilCulled);
  EXPECT_EQ(Validity(again, 3, 3), static_cast<int>(hraa::TfqValidity::NoHistory));
  EXPECT_TRUE(CompareOutputs(zero, again).Identical());
  const HraaFrame second = RenderHraa(w, h, 1, StaticSceneForPhases);
  EXPECT_EQ(Validity(pass->Run(machine, second.Inputs(), Strategy::StencilCulled), 3, 3),
            static_cast<int>(hraa::TfqValidity::ColourLimited));  // A then B: history, no N-2 yet
  first.index = 0;  // a new sequence
  EXPECT_TRUE(CompareOutputs(zero, pass->Run(machine, first.Inputs(), Strategy::StencilCulled)).Identical());
}

// A disc and a slanted edge, white on black.
glm::vec3 StaticScene(glm::vec2 p) {
  const glm::vec2 d = p - glm::vec2(14.3f, 13.7f);
  const bool inside = glm::dot(d, d) < 8.2f * 8.2f || p.y > 0.31f * p.x + 24.6f;
  return glm::vec3(inside ? 1.0f : 0.0f);
}

// The mean absolute difference of two images' red channels.
double MeanAbs(const sim::Texture2D<glm::vec4>& image, const std::function<float(int, int)>& reference) {
  double sum = 0.0;
  for (int y = 0; y < image.Height(); ++y) {
    for (int x = 0; x < image.Width(); ++x) sum += std::abs(static_cast<double>(image.At(x, y).r - reference(x, y)));
  }
  return sum / (image.Width() * image.Height());
}

// Box-filtered 16 x 16 supersampling of a pixel.
float Supersampled(const Scene& scene, int x, int y) {
  float sum = 0.0f;
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) sum += scene({x + (i + 0.5f) / 16.0f, y + (j + 0.5f) / 16.0f}).r;
  }
  return sum / 256.0f;
}

// The FLIPQUAD resolve of the scene's own points: the value temporal FLIPQUAD supersamples to.
float FlipQuadValue(const Scene& scene, int x, int y, int w, int h) {
  constexpr int left = 0, top = 1;  // frame 0 draws the left-edge points, frame 1 the top-edge ones
  const int right = std::min(x + 1, w - 1), below = std::min(y + 1, h - 1);
  return 0.25f * (scene(SamplePosition(x, y, left)).r + scene(SamplePosition(right, y, left)).r +
                  scene(SamplePosition(x, y, top)).r + scene(SamplePosition(x, below, top)).r);
}

// Static scene under flipquad-split: from frame 2 tfq gives FLIPQUAD's 4-sample value, and hraa's
// history converges to it; both are closer to the 16x16 supersampled image than one sample is.
TEST(PassesHraa, AStaticSceneConvergesTowardTheSupersampledValue) {
  const int w = 32, h = 32;
  sim::Machine machine = MakeMachine();
  const std::unique_ptr<Pass> tfq = MakePass("tfq");
  const std::unique_ptr<Pass> hraa = MakePass("hraa");
  const auto truth = [&](int x, int y) { return Supersampled(StaticScene, x, y); };
  const auto flipquad = [&](int x, int y) { return FlipQuadValue(StaticScene, x, y, w, h); };
  double oneSample = 0.0, tfqError = 0.0;
  std::vector<double> hraaToFlipQuad;
  for (int k = 0; k < 40; ++k) {
    const HraaFrame frame = RenderHraa(w, h, k, StaticScene);
    if (k == 0) oneSample = MeanAbs(frame.colour, truth);
    const PassOutput t = tfq->Run(machine, frame.Inputs(), Strategy::StencilCulled);
    const PassOutput o = hraa->Run(machine, frame.Inputs(), Strategy::StencilCulled);
    if (k >= 2) {
      EXPECT_LT(MeanAbs(t.colour, flipquad), 1e-3) << "frame " << k;
      tfqError = MeanAbs(t.colour, truth);
    }
    hraaToFlipQuad.push_back(MeanAbs(o.colour, flipquad));
  }
  std::printf("static scene: 1 sample %.4f, tfq %.4f mean |error| against 16x16; hraa to FLIPQUAD %.4f (frame 0) -> %.5f (frame 39)\n",
              oneSample, tfqError, hraaToFlipQuad.front(), hraaToFlipQuad.back());
  EXPECT_LT(tfqError, 0.7 * oneSample);
  EXPECT_LT(hraaToFlipQuad.back(), 2e-3);
  EXPECT_LT(hraaToFlipQuad.back(), 0.1 * hraaToFlipQuad.front());
}

// ---- the validity tests ---------------------------------------------------------------------

constexpr float kBoxSpeed = 2.0f;  // px per frame, +x
glm::vec3 Background(glm::vec2 p) { return {0.35f + 0.1f * std::sin(p.x / 6.0f), 0.4f, 0.3f + 0.1f * std::cos(p.y / 5.0f)}; }
bool InHraaBox(glm::vec2 p, int k) {
  const float x0 = 6.0f + kBoxSpeed * static_cast<float>(k);
  return p.x >= x0 && p.x < x0 + 10.0f && p.y >= 11.0f && p.y < 21.0f;
}
constexpr glm::vec3 kHraaBoxColour{0.9f, 0.05f, 0.05f};

HraaFrame HraaBoxFrame(int w, int h, int k) {
  return RenderHraa(w, h, k, [k](glm::vec2 p) { return InHraaBox(p, k) ? kHraaBoxColour : Background(p); },
                [k](glm::vec2 p) { return InHraaBox(p, k) ? glm::vec2(kBoxSpeed, 0.0f) : glm::vec2(0.0f); });
}

// The pixels the box left in frame k: box in k - 1 at the pixel's sample, background now.
std::vector<glm::ivec2> Disoccluded(int w, int h, int k) {
  std::vector<glm::ivec2> pixels;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (InHraaBox(SamplePosition(x, y, k - 1), k - 1) && !InHraaBox(SamplePosition(x, y, k), k)) pixels.emplace_back(x, y);
    }
  }
  return pixels;
}

// A pixel none of whose resolve's samples (its FLIPQUAD points and the tent's neighbours, within
// [x - 1, x + 2)) lies in the box of frame k: its true value is the background's.
bool ClearOfTheBox(glm::ivec2 p, int k) { return static_cast<float>(p.x + 2) <= 6.0f + kBoxSpeed * static_cast<float>(k); }

// A box moving 2 px per frame over a static background: the strip it uncovers fails the motion
// flow (the N-1 sample there is the box) and is interpolated from frame N, so no ghost from the
// frame it is uncovered (N = 1 frame), for tfq and for hraa. With both tests off, the box ghosts.
TEST(PassesHraa, MotionFlowRejectsADisoccludedRegion) {
  const int w = 48, h = 32;
  sim::Machine machine = MakeMachine();
  const std::unique_ptr<Pass> tfq = MakePass("tfq");
  const std::unique_ptr<Pass> hraa = MakePass("hraa");
  const std::unique_ptr<Pass> unchecked = MakePass("tfq:motion_threshold=64,colour_threshold=1");
  float worstTfq = 0.0f, worstHraa = 0.0f;
  double ghost = 0.0;  // mean |red - background| without the tests, from frame 2 (N-2 exists)
  int checked = 0, ghosted = 0;
  for (int k = 0; k < 8; ++k) {
    const HraaFrame frame = HraaBoxFrame(w, h, k);
    const PassOutput t = tfq->Run(machine, frame.Inputs(), Strategy::StencilCulled);
    const PassOutput o = hraa->Run(machine, frame.Inputs(), Strategy::StencilCulled);
    const PassOutput u = unchecked->Run(machine, frame.Inputs(), Strategy::StencilCulled);
    if (k == 0) continue;
    const std::vector<glm::ivec2> uncovered = Disoccluded(w, h, k);
    ASSERT_FALSE(uncovered.empty());
    for (const glm::ivec2 p : uncovered) {
      EXPECT_EQ(Validity(t, p.x, p.y), static_cast<int>(hraa::TfqValidity::MotionRejected)) << k << " " << p.x << "," << p.y;
      if (!ClearOfTheBox(p, k)) continue;
      ++checked;
      const float truth = Background(glm::vec2(p) + 0.5f).r;
      worstTfq = std::max(worstTfq, std::abs(t.colour.At(p.x, p.y).r - truth));
      worstHraa = std::max(worstHraa, std::abs(o.colour.At(p.x, p.y).r - truth));
      if (k < 2) continue;
      ghost += static_cast<double>(std::abs(u.colour.At(p.x, p.y).r - truth));
      ++ghosted;
    }
  }
  std::printf("disocclusion (%d pixels): worst |red - background| tfq %.4f, hraa %.4f; without the tests %.4f on average\n",
              checked, static_cast<double>(worstTfq), static_cast<double>(worstHraa), ghost / ghosted);
  EXPECT_GT(checked, 50);
  EXPECT_LT(worstTfq, 0.03f);
  EXPECT_LT(worstHraa, 0.03f);
  EXPECT_GT(ghost / ghosted, 0.15);
}

// A static scene whose square lights up in frame 4: N and N-2 differ there, so the N-1 sample
// (still dark) is limited by N's 3x3 box: inside the square that box is the lit colour alone.
// Without the colour test the pixel is half dark.
TEST(PassesHraa, ColourFlowLimitsAChangedSample) {
  const int w = 24, h = 24;
  const auto scene = [](int k) {
    return [k](glm::vec2 p) {
      const bool lit = k >= 4 && p.x >= 8.0f && p.x < 16.0f && p.y >= 8.0f && p.y < 16.0f;
      return glm::vec3(lit ? 1.0f : 0.2f);
    };
  };
  sim::Machine machine = MakeMachine();
  const std::unique_ptr<Pass> tfq = MakePass("tfq");
  const std::unique_ptr<Pass> unchecked = MakePass("tfq:colour_threshold=1");
  std::optional<PassOutput> limited, accepted;
  for (int k = 0; k < 5; ++k) {
    const HraaFrame frame = RenderHraa(w, h, k, scene(k));
    limited = tfq->Run(machine, frame.Inputs(), Strategy::StencilCulled);
    accepted = unchecked->Run(machine, frame.Inputs(), Strategy::StencilCulled);
  }
  for (int y = 10; y < 14; ++y) {
    for (int x = 10; x < 14; ++x) {
      EXPECT_EQ(Validity(*limited, x, y), static_cast<int>(hraa::TfqValidity::ColourLimited)) << x << "," << y;
      EXPECT_NEAR(limited->colour.At(x, y).r, 1.0f, 1e-3f) << x << "," << y;
      EXPECT_EQ(Validity(*accepted, x, y), static_cast<int>(hraa::TfqValidity::Accepted)) << x << "," << y;
      EXPECT_NEAR(accepted->colour.At(x, y).r, 0.5f * (1.0f + StoredSrgb8(0.2f)), 1e-3f) << x << "," << y;
    }
  }
  EXPECT_EQ(Validity(*limited, 2, 2), static_cast<int>(hraa::TfqValidity::Accepted));  // unchanged there
}

// The unsharp option: out = max(0, c + s (c - (c / 2 + sum of the 4 neighbours / 8))) of the
// plain resolve (tfq.h), checked against the plain pass's output.
TEST(PassesHraa, UnsharpMaskIsTheHalfPixelBoxSubtractedFromTheResolve) {
  const int w = 32, h = 32;
  sim::Machine machine = MakeMachine();
  const std::unique_ptr<Pass> plain = MakePass("tfq");
  const std::unique_ptr<Pass> sharp = MakePass("tfq:unsharp=0.8");
  for (int k = 0; k < 3; ++k) {
    const HraaFrame frame = RenderHraa(w, h, k, StaticScene);
    const PassOutput p = plain->Run(machine, frame.Inputs(), Strategy::StencilCulled);
    const PassOutput s = sharp->Run(machine, frame.Inputs(), Strategy::StencilCulled);
    const auto at = [&](int x, int y) { return p.colour.At(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1)).r; };
    int overshoots = 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const float c = at(x, y);
        const float blurred = 0.5f * c + 0.125f * (at(x - 1, y) + at(x + 1, y) + at(x, y - 1) + at(x, y + 1));
        const float expected = std::max(0.0f, c + 0.8f * (c - blurred));
        ASSERT_NEAR(s.colour.At(x, y).r, expected, 2e-3f * std::abs(expected) + 1e-6f) << k << " " << x << "," << y;
        overshoots += expected > 1.0f ? 1 : 0;
      }
    }
    EXPECT_GT(overshoots, 0) << "the edges must be sharpened";
  }
}

// ---- the acceptance metric ------------------------------------------------------------------

// The history weight of hraa.h, recomputed on the host from the stored images: with no motion and
// bilinear resampling frame 1's history is frame 0's colour (float16), its window frame 1's 3x3.
TEST(PassesHraa, AcceptanceMetricWeighsTheHistoryByItsDistanceFromTheFreshWindow) {
  const int w = 20, h = 14;
  raster::testing::Random rng(7);
  std::vector<glm::vec3> first, second;
  for (int i = 0; i < w * h; ++i) {
    first.emplace_back(rng.Uniform(0, 1), rng.Uniform(0, 1), rng.Uniform(0, 1));
    // A third of the pixels keep their colour, the others move a little or a lot.
    const double step = i % 3 == 0 ? 0.0 : i % 3 == 1 ? 0.05 : 0.6;
    second.push_back(glm::clamp(first.back() + glm::vec3(static_cast<float>(rng.Uniform(-step, step))), 0.0f, 1.0f));
  }
  const auto frame = [&](int k, const std::vector<glm::vec3>& colours) {
    HraaFrame f{{"colour", w, h, 16}, {"velocity", w, h, 8}, nullptr, k, std::nullopt};
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) f.colour.At(x, y) = glm::vec4(colours[static_cast<std::size_t>(y * w + x)], 1.0f);
    }
    f.velocity.Fill(glm::vec2(0.0f));
    return f;
  };
  sim::Machine machine = MakeMachine();
  const std::unique_ptr<Pass> pass = MakePass("hraa:tfq=0,resample=0,feedback_mean=0.7,feedback_bound=0.9,falloff=3");
  pass->Run(machine, frame(0, first).Inputs(), Strategy::StencilCulled);
  const PassOutput output = pass->Run(machine, frame(1, second).Inputs(), Strategy::StencilCulled);
  const PassLayer& feedback = testing::LayerNamed(output, "feedback");
  const auto stored = [&](const std::vector<glm::vec3>& colours, int x, int y) {
    return StoredSrgb8(colours[static_cast<std::size_t>(std::clamp(y, 0, h - 1) * w + std::clamp(x, 0, w - 1))]);
  };
  int inside = 0, outside = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const glm::vec3 history(sim::Quantize(sim::Format::RGBA16Float, glm::vec4(stored(first, x, y), 1.0f)));
      glm::vec3 mean(0.0f), lo(1e9f), hi(-1e9f);
      for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
          const glm::vec3 c = sim::RgbToYCoCg(stored(second, x + i, y + j));
          mean += c / 9.0f;
          lo = glm::min(lo, c);
          hi = glm::max(hi, c);
        }
      }
      const glm::vec3 hy = sim::RgbToYCoCg(history);
      float t = 0.0f;
      for (int c = 0; c < 3; ++c) {
        const float range = hy[c] >= mean[c] ? hi[c] - mean[c] : mean[c] - lo[c];
        t = std::max(t, std::abs(hy[c] - mean[c]) / (range + 1.0f / 256.0f));
      }
      const float beta = t <= 1.0f ? 0.7f + 0.2f * t : 0.9f * std::exp(-3.0f * (t - 1.0f));
      (t <= 1.0f ? inside : outside) += 1;
      ASSERT_NEAR(testing::LayerValue(feedback, x, y), beta, 2e-3f) << x << "," << y << " t " << t;
      const glm::vec3 current = stored(second, x, y);
      const glm::vec3 expected = current + beta * (history - current);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(output.colour.At(x, y)[c], expected[c], 2e-3f) << x << "," << y;
    }
  }
  EXPECT_GT(inside, 20);  // both branches of the weight are exercised
  EXPECT_GT(outside, 20);
}

// ---- history resampling ---------------------------------------------------------------------

// Runs one resampling of `history` through `velocity` on the machine: what the TAA kernel reads.
sim::Texture2D<glm::vec4> Resampled(hraa::Resampling mode, const sim::Texture2D<glm::vec4>& history,
                                    const sim::Texture2D<glm::vec2>& velocity) {
  sim::Machine machine = MakeMachine();
  hraa::HistoryResampler resampler;
  resampler.Prepare(machine, mode, history, velocity);
  sim::Texture2D<glm::vec4> out("out", history.Width(), history.Height(), 16);
  sim::Dispatch d("test/fetch", {});
  const hraa::HistoryFetch fetch = resampler.Bind(d, mode, history);
  const sim::TextureView<glm::vec2> motion = d.Read(velocity);
  const sim::RwTextureView<glm::vec4> target = d.ReadWrite(out);
  machine.FullScreen(d, {.width = history.Width(), .height = history.Height()}, [&](sim::PixelLane& lane) {
    target.Store(lane, lane.x, lane.y, fetch(lane, lane.x, lane.y, motion.Load(lane, lane.x, lane.y)));
  });
  return out;
}

sim::Texture2D<glm::vec4> RandomHistory(int w, int h) {
  sim::Texture2D<glm::vec4> history("history", w, h, sim::Format::RGBA16Float);
  raster::testing::Random rng(15);
  for (glm::vec4& texel : history.Texels()) {
    texel = sim::Quantize(sim::Format::RGBA16Float, glm::vec4(rng.Uniform(0, 1), rng.Uniform(0, 1), rng.Uniform(0, 1), 1.0f));
  }
  return history;
}

constexpr hraa::Resampling kHraaModes[] = {hraa::Resampling::Bilinear, hraa::Resampling::MacCormack, hraa::Resampling::Bfecc,
                                       hraa::Resampling::GpuBfecc};

// With a whole-pixel motion every bilinear tap lands on a texel centre, the back-and-forth error
// is zero and each form returns the shifted history bit for bit (away from the clamped borders).
TEST(PassesHraa, EveryResamplingIsExactForIntegerShifts) {
  const int w = 64, h = 64;  // powers of two: (p + 0.5) / size and back are exact
  const sim::Texture2D<glm::vec4> history = RandomHistory(w, h);
  for (const glm::vec2 shift : {glm::vec2(3, -2), glm::vec2(-1, 4), glm::vec2(0, 0)}) {
    sim::Texture2D<glm::vec2> velocity("velocity", w, h, sim::Format::RG16Float, shift);
    for (const hraa::Resampling mode : kHraaModes) {
      const sim::Texture2D<glm::vec4> out = Resampled(mode, history, velocity);
      for (int y = 5; y < h - 5; ++y) {
        for (int x = 5; x < w - 5; ++x) {
          const glm::vec4 expected = history.At(x - static_cast<int>(shift.x), y - static_cast<int>(shift.y));
          ASSERT_EQ(std::memcmp(&out.At(x, y), &expected, sizeof(glm::vec4)), 0)
              << hraa::ResamplingName(mode) << " shift " << shift.x << "," << shift.y << " at " << x << "," << y;
        }
      }
    }
  }
}

// For a linear projection GPU BFECC is MacCormack (history_resample.h); BFECC is not.
TEST(PassesHraa, GpuBfeccEqualsMacCormackForAUniformSubPixelMotion) {
  const int w = 48, h = 40;
  const sim::Texture2D<glm::vec4> history = RandomHistory(w, h);
  const sim::Texture2D<glm::vec2> velocity("velocity", w, h, sim::Format::RG16Float, glm::vec2(0.375f, -0.25f));
  const sim::Texture2D<glm::vec4> mac = Resampled(hraa::Resampling::MacCormack, history, velocity);
  const sim::Texture2D<glm::vec4> gpu = Resampled(hraa::Resampling::GpuBfecc, history, velocity);
  const sim::Texture2D<glm::vec4> bfecc = Resampled(hraa::Resampling::Bfecc, history, velocity);
  float worstGpu = 0.0f, worstBfecc = 0.0f;
  for (int y = 4; y < h - 4; ++y) {
    for (int x = 4; x < w - 4; ++x) {
      worstGpu = std::max(worstGpu, std::abs(mac.At(x, y).r - gpu.At(x, y).r));
      worstBfecc = std::max(worstBfecc, std::abs(mac.At(x, y).r - bfecc.At(x, y).r));
    }
  }
  EXPECT_LT(worstGpu, 4e-3f);  // float16 storage of the intermediates
  EXPECT_GT(worstBfecc, 2e-2f);
}

// ---- seed 001's experiment: an exponential history continuously resampled over 30 frames ----

// A grating moving at varying sub-pixel speeds (px per frame, +x and +y, cycling).
constexpr glm::vec2 kSpeeds[] = {{0.3f, 0.15f}, {0.45f, 0.25f}, {0.2f, 0.4f}, {0.6f, 0.1f}, {0.35f, 0.3f}};
constexpr int kExperimentFrames = 30;

float Grating(glm::vec2 p) {
  constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;
  return 0.5f + 0.2f * (std::sin(kTwoPi * p.x / 4.5f) + std::sin(kTwoPi * p.y / 5.5f));
}

struct Retained {
  double contrast;  // RMS about the mean of the output over that of the exact image
  double error;     // RMS of output - exact image
};

Retained RunExperiment(int resample) {
  const int w = 64, h = 64;
  sim::Machine machine = MakeMachine();
  const std::unique_ptr<Pass> pass = MakePass("hraa:preset=exponential,resample=" + std::to_string(resample));
  glm::vec2 shift(0.0f);
  std::optional<PassOutput> output;
  for (int k = 0; k < kExperimentFrames; ++k) {
    const glm::vec2 v = k == 0 ? glm::vec2(0.0f) : kSpeeds[static_cast<std::size_t>(k) % std::size(kSpeeds)];
    shift += v;
    const HraaFrame frame = RenderHraa(w, h, k, [&](glm::vec2 p) { return glm::vec3(Grating(p - shift)); },
                               [&](glm::vec2) { return v; }, true);
    output = pass->Run(machine, frame.Inputs(), Strategy::StencilCulled);
  }
  // The window the clamped left and top borders have not reached after 30 frames of motion.
  double sumOut = 0, sumExact = 0, n = 0;
  for (int y = 20; y < 56; ++y) {
    for (int x = 20; x < 56; ++x) {
      sumOut += static_cast<double>(output->colour.At(x, y).r);
      sumExact += static_cast<double>(Grating(glm::vec2(x + 0.5f, y + 0.5f) - shift));
      ++n;
    }
  }
  double varOut = 0, varExact = 0, err = 0;
  for (int y = 20; y < 56; ++y) {
    for (int x = 20; x < 56; ++x) {
      const double exact = static_cast<double>(Grating(glm::vec2(x + 0.5f, y + 0.5f) - shift));
      const double out = static_cast<double>(output->colour.At(x, y).r);
      varOut += (out - sumOut / n) * (out - sumOut / n);
      varExact += (exact - sumExact / n) * (exact - sumExact / n);
      err += (out - exact) * (out - exact);
    }
  }
  return {std::sqrt(varOut / varExact), std::sqrt(err / n)};
}

TEST(PassesHraa, BfeccDiffusesLessThanBilinearOverThirtyFramesOfSubPixelMotion) {
  std::vector<Retained> results;
  for (int mode = 0; mode < 4; ++mode) {
    results.push_back(RunExperiment(mode));
    std::printf("BFECC experiment, %s: retained contrast %.3f, RMS error %.4f\n",
                std::string(hraa::ResamplingName(static_cast<hraa::Resampling>(mode))).c_str(), results.back().contrast,
                results.back().error);
  }
  // Every second-order form keeps more contrast; MacCormack and GPU BFECC (the transported
  // correction) also halve the error, the seed's BFECC only lowers it (history_resample.h).
  for (int mode = 1; mode < 4; ++mode) {
    const Retained& result = results[static_cast<std::size_t>(mode)];
    EXPECT_GT(result.contrast, results[0].contrast + 0.2) << mode;
    EXPECT_LT(result.error, (mode == 2 ? 1.0 : 0.6) * results[0].error) << mode;
  }
}

// ---- determinism ----------------------------------------------------------------------------

struct HraaSequenceRun {
  std::vector<PassOutput> outputs;
  std::vector<std::vector<sim::DispatchReport>> reports;
};

HraaSequenceRun RunHraaSequence(std::string_view spec, int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const int w = 70, h = 45;  // partial quads, tiles and waves
  sim::Machine machine = MakeMachine();
  const std::unique_ptr<Pass> pass = MakePass(spec);
  HraaSequenceRun run;
  for (int k = 0; k < 6; ++k) {
    run.outputs.push_back(pass->Run(machine, HraaBoxFrame(w, h, k).Inputs(), Strategy::StencilCulled));
    run.reports.push_back(machine.Reports());
    machine.ClearReports();
  }
  return run;
}

TEST(PassesHraa, OneAndTwoThreadsGiveIdenticalSequences) {
  for (const std::string_view spec : {"hraa:unsharp=0.5", "hraa:resample=1", "hraa:resample=2", "hraa:preset=taa,resample=0", "tfq"}) {
    const HraaSequenceRun one = RunHraaSequence(spec, 1), two = RunHraaSequence(spec, 2);
    for (std::size_t k = 0; k < one.outputs.size(); ++k) {
      EXPECT_TRUE(CompareOutputs(one.outputs[k], two.outputs[k]).Identical()) << spec << " frame " << k;
      sim::testing::ExpectSameReports(one.reports[k], two.reports[k]);
    }
  }
}

}  // namespace
}  // namespace passes
