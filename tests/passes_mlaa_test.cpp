// PS3 MLAA (seed 004; aa-facts §7) on synthetic images whose edges, line shapes and blend
// weights are derived by hand from the talk's tests and the revectorised trapezoid areas:
//   an L, Z or U line of length d blends the pixel n pixels from a turning end by
//   (d - 2n - 1) / (2d) while that pixel lies in the end's half, and the centre pixel of an odd
//   line by 1 / (8d) per turning end (the triangle under the last half pixel).
// Weights are checked to RG16F precision (relative 2^-10: one unit of the 10-bit fraction, as a
// store to a float16 target rounds toward zero, D3D11 §3.2.2); blended colours exactly as 8-bit codes:
// every expected value below lies at least 0.02 codes from a rounding boundary (checked).

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "passes/compare.h"
#include "passes/mlaa/mlaa_kernels.h"
#include "passes/registry.h"
#include "passes_test_util.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"

namespace passes {
namespace {

using testing::Codes;
using testing::GreyImage;

constexpr int kMlaaDark = 40, kMlaaWhite = 221;

struct MlaaRun {
  PassOutput output;

  const PassLayer& Layer(std::string_view name) const { return testing::LayerNamed(output, name); }
  float At(std::string_view layer, int x, int y, int channel) const {
    return testing::LayerValue(Layer(layer), x, y, channel);
  }
  int Code(int x, int y) const { return sim::FloatToSrgb8(output.colour.At(x, y).r); }
};

MlaaRun RunMlaa(std::string_view spec, const sim::Texture2D<glm::vec4>& image,
                Strategy strategy = Strategy::DeferredQueue, const sim::Texture2D<float>* depth = nullptr) {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const sim::Texture2D<glm::vec4> srgb8 = Srgb8ColourTarget("colour-srgb8", image);
  return {ResolvePass(spec).Make()->Run(machine, FrameInputs{.colour = &image, .colourSrgb8 = &srgb8, .depth = depth},
                                        strategy)};
}

sim::Texture2D<float> DepthImage(int width, int height, const std::function<float(int, int)>& depth) {
  sim::Texture2D<float> image("depth", width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) image.At(x, y) = depth(x, y);
  }
  return image;
}

// The 8-bit code a gamma-space blend of `code` towards `other` by `area` stores.
int BlendedCode(int code, int other, double area) {
  const double exact = code + area * (other - code);
  EXPECT_GT(std::fabs(exact - std::floor(exact) - 0.5), 0.02) << "test value too close to a rounding boundary";
  return static_cast<int>(std::lround(exact));
}

// (x, y) -> (R, G) of a weights layer; every pixel not listed has (0, 0).
using Weights = std::map<std::pair<int, int>, std::pair<double, double>>;

void ExpectWeights(const MlaaRun& run, std::string_view layer, const Weights& expected, int width, int height) {
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const auto found = expected.find({x, y});
      const std::pair<double, double> w = found == expected.end() ? std::pair{0.0, 0.0} : found->second;
      EXPECT_NEAR(run.At(layer, x, y, 0), w.first, w.first / 1024.0) << layer << " R at " << x << "," << y;
      EXPECT_NEAR(run.At(layer, x, y, 1), w.second, w.second / 1024.0) << layer << " G at " << x << "," << y;
    }
  }
}

// Where the vertical pass left a pixel alone, its output is the horizontal blend of the input:
// from the pixel above by R and from the pixel below by G. Returns the pixels checked.
int ExpectHorizontalBlends(const MlaaRun& run, const Codes& code, int width, int height) {
  int checked = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (run.At("weights-v", x, y, 0) != 0.0f || run.At("weights-v", x, y, 1) != 0.0f) continue;
      const double up = static_cast<double>(run.At("weights-h", x, y, 0));
      const double down = static_cast<double>(run.At("weights-h", x, y, 1));
      EXPECT_TRUE(up == 0.0 || down == 0.0) << "one edge per pixel in these images";
      int expected = code(x, y);
      if (up > 0.0) expected = BlendedCode(code(x, y), code(x, y - 1), up);
      if (down > 0.0) expected = BlendedCode(code(x, y), code(x, y + 1), down);
      EXPECT_EQ(run.Code(x, y), expected) << x << "," << y;
      ++checked;
    }
  }
  return checked;
}

double Turning(int d, int n) { return (d - 2.0 * n - 1.0) / (2.0 * d); }
double OddCentre(int d) { return 1.0 / (8.0 * d); }

// ---- Edge detection (seed 004 "Relative Thresholding", bonus slide) ----

TEST(MlaaEdgeTest, TheDiscontinuityTestIsStrictAgainstTheSmallerThreshold) {
  mlaa::Config config;
  config.scale = 0.25f;
  config.lowerBound = 0.0f;
  // T(0.5) = 0.125 is the smaller threshold; a difference equal to it is no discontinuity.
  EXPECT_FALSE(mlaa::IsEdge(config, glm::vec3(0.5f), glm::vec3(0.625f), false));
  EXPECT_TRUE(mlaa::IsEdge(config, glm::vec3(0.5f), glm::vec3(0.63f), false));
  // The largest channel difference decides: green differs by 0.2 > 0.125.
  EXPECT_TRUE(mlaa::IsEdge(config, glm::vec3(0.5f, 0.5f, 0.5f), glm::vec3(0.5f, 0.7f, 0.5f), false));
  // The lower bound holds in the dark: T = max(0.1, 0.25 x 0.02).
  config.lowerBound = 0.1f;
  EXPECT_FALSE(mlaa::IsEdge(config, glm::vec3(0.0f), glm::vec3(0.02f, 0.09f, 0.0f), false));
  EXPECT_TRUE(mlaa::IsEdge(config, glm::vec3(0.0f), glm::vec3(0.02f, 0.11f, 0.0f), false));
}

TEST(MlaaEdgeTest, PredicationScalesTheRelativeThresholdAndLowersItAtDepthEdges) {
  mlaa::Config config;
  config.thresholding = mlaa::Thresholding::Predicated;
  const glm::vec3 a(0.5f), b(0.6f);  // T = min(0.1, 0.12) = 0.1 with scale 0.2
  EXPECT_FLOAT_EQ(mlaa::PairThreshold(config, a, b, false), 0.2f);   // x 2
  EXPECT_FLOAT_EQ(mlaa::PairThreshold(config, a, b, true), 0.05f);   // x 2 x (1 - 0.75)
  EXPECT_TRUE(mlaa::DepthEdge(config, 0.5f, 0.52f));    // 0.02 > max(0.01, 0.005)
  EXPECT_FALSE(mlaa::DepthEdge(config, 0.9f, 0.909f));  // 0.009 <= max(0.01, 0.009)
}

// Columns x < 8 and x >= 8 in two codes; the edges-h layer's G marks the edge right of x = 7.
float VerticalStepEdge(std::string_view spec, int left, int right, const sim::Texture2D<float>* depth = nullptr) {
  const auto image = GreyImage(16, 4, [&](int x, int) { return x < 8 ? left : right; });
  return RunMlaa(spec, image, Strategy::DeferredQueue, depth).At("edges-h", 7, 1, 1);
}

TEST(MlaaEdges, RelativeThresholdingFindsADarkEdgeThatAbsoluteMisses) {
  // Codes 10 and 25: difference 15/255 = 0.059; absolute 0.1 misses it; relative T =
  // max(0.04, 0.2 x 25/255 = 0.020) = 0.04 finds it.
  EXPECT_EQ(VerticalStepEdge("mlaa-absolute", 10, 25), 0.0f);
  EXPECT_EQ(VerticalStepEdge("mlaa", 10, 25), 1.0f);
  // ... and misses a bright one absolute finds ("inverted sensitivity"): 200 and 235 differ by
  // 0.137 > 0.1, but T = min(0.2 x 200/255, 0.2 x 235/255) = 0.157.
  EXPECT_EQ(VerticalStepEdge("mlaa-absolute", 200, 235), 1.0f);
  EXPECT_EQ(VerticalStepEdge("mlaa", 200, 235), 0.0f);
}

TEST(MlaaEdges, PredicationFindsAnEdgeThatOnlyTheDepthShows) {
  // Codes 100 and 115: difference 0.059 < relative T = 0.2 x 100/255 = 0.078.
  const auto step = DepthImage(16, 4, [](int x, int) { return x < 8 ? 0.5f : 0.6f; });
  const auto flat = DepthImage(16, 4, [](int, int) { return 0.5f; });
  EXPECT_EQ(VerticalStepEdge("mlaa", 100, 115, &step), 0.0f);
  EXPECT_EQ(VerticalStepEdge("mlaa-predicated", 100, 115, &flat), 0.0f);
  // At the depth step the threshold is 0.078 x 2 x 0.25 = 0.039.
  EXPECT_EQ(VerticalStepEdge("mlaa-predicated", 100, 115, &step), 1.0f);
  // Away from depth edges predication is less sensitive: 100 and 130 (0.118) is a relative
  // edge but not a predicated one (0.157).
  EXPECT_EQ(VerticalStepEdge("mlaa", 100, 130, &flat), 1.0f);
  EXPECT_EQ(VerticalStepEdge("mlaa-predicated", 100, 130, &flat), 0.0f);
}

// ---- Feature splitting (seed 004 "Color Gradients") ----

// Grey 130 above row 4; below it 200 left of x = 8 and 60 from x = 8: one horizontal edge across
// the image whose gradient (on the channel sum) rises left of x = 8 and falls right of it, with a
// vertical edge 200|60 turning down from its middle.
constexpr int kSplitA = 130, kSplitB = 200, kSplitC = 60;
int SplitCode(int x, int y) { return y < 4 ? kSplitA : x < 8 ? kSplitB : kSplitC; }

TEST(MlaaFeatureSplitting, ALineIsSplitWhereTheGradientChangesSign) {
  const auto image = GreyImage(16, 8, SplitCode);
  // Split: two L shapes of length 8 turning down at x = 8 (the 200|60 edge in row 4), blending
  // row 4 towards row 3 by (8 - 2n - 1) / 16 at n pixels from x = 8.
  const MlaaRun split = RunMlaa("mlaa", image);
  Weights expected;
  for (int n = 0; n < 4; ++n) {
    expected[{7 - n, 4}] = {Turning(8, n), 0.0};
    expected[{8 + n, 4}] = {Turning(8, n), 0.0};
  }
  ExpectWeights(split, "weights-h", expected, 16, 8);
  EXPECT_EQ(ExpectHorizontalBlends(split, SplitCode, 16, 8), 16 * 8);
  EXPECT_EQ(split.Code(7, 4), 169);  // 200 - 7/16 x 70 = 169.375
  EXPECT_EQ(split.Code(8, 4), 91);   // 60 + 7/16 x 70 = 90.625
  // Unsplit: one line from border to border, no turning end, nothing blended.
  const MlaaRun whole = RunMlaa("mlaa:feature_splitting=0", image);
  ExpectWeights(whole, "weights-h", {}, 16, 8);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 16; ++x) EXPECT_EQ(whole.Code(x, y), SplitCode(x, y)) << x << "," << y;
  }
}

TEST(MlaaBlend, LinearBlendMixesDecodedValuesInsteadOfTheGammaCodes) {
  const auto image = GreyImage(16, 8, SplitCode);
  const MlaaRun run = RunMlaa("mlaa:linear_blend=1", image);
  const auto linear = [](int code) { return sim::Srgb8ToFloat(static_cast<std::uint8_t>(code)); };
  // (7, 4) takes 7/16 of the grey above it, mixed as linear light and encoded once.
  const float mixed = linear(kSplitB) + 7.0f / 16.0f * (linear(kSplitA) - linear(kSplitB));
  EXPECT_EQ(run.Code(7, 4), sim::FloatToSrgb8(mixed));
  EXPECT_NE(run.Code(7, 4), 169);  // the gamma-code blend
  EXPECT_EQ(run.At("weights-h", 7, 4, 0), 7.0f / 16.0f);
}

// ---- L, Z and U shapes (Reshetov 2009; aa-facts §7) ----

TEST(MlaaShapes, AnLBlendsTheHalfNearItsTurningEnd) {
  // Dark below row 5 from x = 4 to the right border: a line of 12 turning down at its left end,
  // open at the border.
  const Codes code = [](int x, int y) { return x >= 4 && y >= 5 ? kMlaaDark : kMlaaWhite; };
  const auto image = GreyImage(16, 10, code);
  const MlaaRun run = RunMlaa("mlaa", image);
  Weights expected;
  for (int n = 0; n < 6; ++n) expected[{4 + n, 5}] = {Turning(12, n), 0.0};
  ExpectWeights(run, "weights-h", expected, 16, 10);
  EXPECT_GE(ExpectHorizontalBlends(run, code, 16, 10), 16 * 10 - 16);
}

TEST(MlaaShapes, AZBlendsBothHalvesOnOppositeSides) {
  // A staircase: dark from row 6 left of x = 4, from row 5 for x in [4, 12), from row 4 after.
  // The line on the row 4|5 boundary (length 8) turns down at x = 4 and up at x = 12: a Z. The
  // steps' lines of length 4 are L shapes.
  const Codes code = [](int x, int y) { return y >= (x < 4 ? 6 : x < 12 ? 5 : 4) ? kMlaaDark : kMlaaWhite; };
  const auto image = GreyImage(16, 10, code);
  const MlaaRun run = RunMlaa("mlaa", image);
  Weights expected;
  for (int n = 0; n < 4; ++n) {
    expected[{4 + n, 5}] = {Turning(8, n), 0.0};   // lower row, left half: from above
    expected[{11 - n, 4}] = {0.0, Turning(8, n)};  // upper row, right half: from below
  }
  for (int n = 0; n < 2; ++n) {
    expected[{3 - n, 5}] = {0.0, Turning(4, n)};
    expected[{12 + n, 4}] = {Turning(4, n), 0.0};
  }
  ExpectWeights(run, "weights-h", expected, 16, 10);
  EXPECT_GE(ExpectHorizontalBlends(run, code, 16, 10), 16 * 10 - 24);
}

TEST(MlaaShapes, AUBlendsBothHalvesOnOneSideAndAnOddCentreByTwoTriangles) {
  // Dark from row 5, and from row 4 on x in [4, 11): a plateau of 7 whose line turns down at both
  // ends. Its neighbours on the row 4|5 boundary are L shapes of 4 and 5 turning up.
  const Codes code = [](int x, int y) { return y >= 5 || (x >= 4 && x < 11 && y >= 4) ? kMlaaDark : kMlaaWhite; };
  const auto image = GreyImage(16, 10, code);
  const MlaaRun run = RunMlaa("mlaa", image);
  Weights expected;
  for (int n = 0; n < 3; ++n) {
    expected[{4 + n, 4}] = {Turning(7, n), 0.0};
    expected[{10 - n, 4}] = {Turning(7, n), 0.0};
  }
  expected[{7, 4}] = {2.0 * OddCentre(7), 0.0};
  expected[{3, 4}] = {0.0, Turning(4, 0)};
  expected[{2, 4}] = {0.0, Turning(4, 1)};
  expected[{11, 4}] = {0.0, Turning(5, 0)};
  expected[{12, 4}] = {0.0, Turning(5, 1)};
  expected[{13, 4}] = {0.0, OddCentre(5)};
  ExpectWeights(run, "weights-h", expected, 16, 10);
  EXPECT_GE(ExpectHorizontalBlends(run, code, 16, 10), 16 * 10 - 24);
}

TEST(MlaaShapes, TheSearchLimitLeavesAnEndOpen) {
  // The L of AnLBlendsTheHalfNearItsTurningEnd traced 4 px per side: from x = 4 the line seems
  // to be 1 + 4 long with an open right end, from x = 5 it seems 2 + 4 long.
  const auto image = GreyImage(16, 10, [](int x, int y) { return x >= 4 && y >= 5 ? kMlaaDark : kMlaaWhite; });
  const MlaaRun run = RunMlaa("mlaa:max_search=4", image);
  EXPECT_NEAR(run.At("weights-h", 4, 5, 0), Turning(5, 0), 1e-3);
  EXPECT_NEAR(run.At("weights-h", 5, 5, 0), Turning(6, 1), 1e-3);
}

// ---- Symmetries ----

// Grey levels on 3x5 blocks and a disc: lines of many lengths, shapes and gradient classes.
int Blocks(int x, int y) {
  const int dx = x - 13, dy = y - 11;
  if (dx * dx + dy * dy < 64) return 30;
  return 40 + ((x / 3) * 37 + (y / 5) * 91) % 180;
}

template <typename Map>
void ExpectMirrored(const MlaaRun& run, const MlaaRun& mirrored, int width, int height, Map map, bool swapV, bool swapH) {
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const auto [mx, my] = map(x, y);
      EXPECT_EQ(mirrored.Code(mx, my), run.Code(x, y)) << x << "," << y;
      for (int c = 0; c < 2; ++c) {
        EXPECT_EQ(mirrored.At("weights-h", mx, my, swapH ? 1 - c : c), run.At("weights-h", x, y, c)) << x << "," << y;
        EXPECT_EQ(mirrored.At("weights-v", mx, my, swapV ? 1 - c : c), run.At("weights-v", x, y, c)) << x << "," << y;
      }
    }
  }
}

TEST(MlaaSymmetry, MirroringTheImageMirrorsTheResultBitForBit) {
  constexpr int kW = 29, kH = 23;
  const auto image = GreyImage(kW, kH, Blocks);
  const auto flippedX = GreyImage(kW, kH, [](int x, int y) { return Blocks(kW - 1 - x, y); });
  const auto flippedY = GreyImage(kW, kH, [](int x, int y) { return Blocks(x, kH - 1 - y); });
  for (const char* spec : {"mlaa-absolute", "mlaa", "mlaa:feature_splitting=0"}) {
    SCOPED_TRACE(spec);
    const MlaaRun run = RunMlaa(spec, image);
    EXPECT_GT(run.output.workItems, 100u);
    ExpectMirrored(run, RunMlaa(spec, flippedX), kW, kH, [](int x, int y) { return std::pair{kW - 1 - x, y}; }, true,
                   false);
    ExpectMirrored(run, RunMlaa(spec, flippedY), kW, kH, [](int x, int y) { return std::pair{x, kH - 1 - y}; }, false,
                   true);
  }
}

// A vertical line between grey (100, 100, 100) on the left and, on the right, (160, 100, 100)
// above row 8 (the channel sum rises by 60) and (130, 70, 100) from row 8 (the sum does not
// change): a flat gradient is a class of its own, so the line splits at row 8 in the image and
// in its mirror (a two-class rule would give the mirrored rows one class and not split).
glm::ivec3 FlatSplitCodes(int x, int y) {
  if (x < 4) return {100, 100, 100};
  return y < 8 ? glm::ivec3(160, 100, 100) : glm::ivec3(130, 70, 100);
}

sim::Texture2D<glm::vec4> ColourImage(int width, int height, const std::function<glm::ivec3(int, int)>& codes) {
  sim::Texture2D<glm::vec4> image("input", width, height, 16);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::ivec3 c = codes(x, y);
      image.At(x, y) = {sim::Srgb8ToFloat(static_cast<std::uint8_t>(c.r)), sim::Srgb8ToFloat(static_cast<std::uint8_t>(c.g)),
                        sim::Srgb8ToFloat(static_cast<std::uint8_t>(c.b)), 1.0f};
    }
  }
  return image;
}

TEST(MlaaSymmetry, AFlatGradientIsAClassOfItsOwnSoAMirroredLineSplitsAlike) {
  const auto image = ColourImage(8, 16, FlatSplitCodes);
  const auto mirrored = ColourImage(8, 16, [](int x, int y) { return FlatSplitCodes(7 - x, y); });
  const MlaaRun run = RunMlaa("mlaa", image);
  // Two L's of 8 turning right at row 8 (the 160|130 edge in column 4): column 4 takes 7/16 of
  // the grey at rows 7 and 8.
  EXPECT_EQ(run.At("weights-v", 4, 7, 0), 7.0f / 16.0f);
  EXPECT_EQ(run.At("weights-v", 4, 8, 0), 7.0f / 16.0f);
  ExpectMirrored(run, RunMlaa("mlaa", mirrored), 8, 16, [](int x, int y) { return std::pair{7 - x, y}; }, true, false);
}

TEST(MlaaSymmetry, TransposingAnImageOfOneLineDirectionTransposesTheResult) {
  // The horizontal pass runs first, so a transposed image is a transposed result only where one
  // pass does all the work: the feature-splitting image, whose vertical line has no turning end.
  const auto image = GreyImage(16, 8, SplitCode);
  const auto transposed = GreyImage(8, 16, [](int x, int y) { return SplitCode(y, x); });
  const MlaaRun run = RunMlaa("mlaa", image), other = RunMlaa("mlaa", transposed);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 16; ++x) {
      EXPECT_EQ(other.Code(y, x), run.Code(x, y)) << x << "," << y;
      for (int c = 0; c < 2; ++c) {
        EXPECT_EQ(other.At("weights-v", y, x, c), run.At("weights-h", x, y, c)) << x << "," << y;
        EXPECT_EQ(other.At("weights-h", y, x, c), run.At("weights-v", x, y, c)) << x << "," << y;
      }
    }
  }
  EXPECT_EQ(other.At("weights-v", 4, 7, 0), 7.0f / 16.0f);  // the transposed L's first pixel
}

// ---- Worst case and strategies ----

TEST(MlaaWorstCase, ACheckerboardPutsEveryPixelInBothWorkSetsAndBlendsNothing) {
  // Every boundary is an edge; with splitting every line is one pixel long (the gradient class
  // alternates), without it every line runs border to border; either way every end is crossed on
  // both sides or open, so no end turns.
  constexpr int kW = 24, kH = 18;
  const Codes code = [](int x, int y) { return (x + y) % 2 == 0 ? 0 : 255; };
  const auto image = GreyImage(kW, kH, code);
  for (const char* spec : {"mlaa", "mlaa:feature_splitting=0", "mlaa-absolute"}) {
    for (const Strategy strategy : kAllStrategies) {
      const MlaaRun run = RunMlaa(spec, image, strategy);
      EXPECT_EQ(run.output.workItems, 2u * kW * kH) << spec;
      for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) ASSERT_EQ(run.Code(x, y), code(x, y)) << spec << " " << x << "," << y;
      }
    }
  }
}

TEST(MlaaStrategies, EveryPresetGivesBitIdenticalOutputsUnderBothStrategies) {
  const auto image = GreyImage(29, 23, Blocks);
  const auto depth = DepthImage(29, 23, [](int x, int y) { return x + y < 25 ? 0.3f : 0.6f; });
  for (const char* spec : {"mlaa-absolute", "mlaa", "mlaa-predicated"}) {
    const MlaaRun stencil = RunMlaa(spec, image, Strategy::StencilCulled, &depth);
    const MlaaRun queue = RunMlaa(spec, image, Strategy::DeferredQueue, &depth);
    EXPECT_GT(queue.output.workItems, 0u) << spec;
    const StrategyDifference difference = CompareOutputs(stencil.output, queue.output);
    EXPECT_TRUE(difference.Identical()) << spec << ": " << difference.Describe();
  }
}

}  // namespace
}  // namespace passes
