// Filmic SMAA's morphological part (seed 000; passes/filmic_smaa/): the edge suppression rule on
// hand-built windows and images, against SMAA 1x's local contrast adaptation where they differ;
// the neighbour agreement that lets no two items of a dispatch write one pixel, on random
// images under both strategies; the strategies' identity on images with edges at every tile
// border; and the output against SMAA 1x and against analytic coverage.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>

#include "passes/compare.h"
#include "passes/filmic_smaa/edge_suppression.h"
#include "passes/registry.h"
#include "passes_test_util.h"
#include "sim/colour.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"

namespace passes {
namespace {

using filmic_smaa::EdgeScores;
using filmic_smaa::LumaWindow;
using filmic_smaa::Side;

// ---- The rule on luma windows ----

LumaWindow WindowOf(const std::function<float(int dx, int dy)>& luma) {
  LumaWindow window;
  for (int dy = filmic_smaa::kWindowMin; dy <= filmic_smaa::kWindowMax; ++dy) {
    for (int dx = filmic_smaa::kWindowMin; dx <= filmic_smaa::kWindowMax; ++dx) window.At(dx, dy) = luma(dx, dy);
  }
  return window;
}

// Columns left of P at 0, P's column at 0.25, the columns right of P at `right`: P's left edge
// scores 0.25 + 0.25 through itself (continued up or down), 2 |right - 0.25| on the parallel line.
float KeptLeftBesideParallel(float right) {
  const LumaWindow window = WindowOf([right](int dx, int) { return dx < 0 ? 0.0f : dx == 0 ? 0.25f : right; });
  return EdgeScores(window, 0.25f).Kept(0, 0, Side::Left);
}

TEST(FilmicSmaaSuppression, APassingScoreEqualToTwiceTheThresholdOrTheNonPassingScoreKeepsTheEdge) {
  EXPECT_EQ(KeptLeftBesideParallel(0.25f), 0.25f);  // no parallel line; passing 0.5 = 2 x threshold
  EXPECT_EQ(KeptLeftBesideParallel(0.5f), 0.25f);   // parallel line scoring 0.5 too: equality keeps
  EXPECT_EQ(KeptLeftBesideParallel(0.5f + 1.0f / 64), 0.0f);  // a stronger parallel line wins
}

TEST(FilmicSmaaSuppression, AnEdgeWhosePatternsScoreUnderTwiceTheThresholdIsSuppressed) {
  // P's left edge has contrast 0.25; every edge meeting its endpoints has 0.125: the best pattern
  // through it scores 0.375, nothing else scores.
  const LumaWindow window = WindowOf([](int dx, int dy) { return dx < 0 ? 0.0f : dy == 0 ? 0.25f : 0.125f; });
  EXPECT_EQ(EdgeScores(window, 0.25f).Kept(0, 0, Side::Left), 0.0f);     // 0.375 < 2 x 0.25
  EXPECT_EQ(EdgeScores(window, 0.125f).Kept(0, 0, Side::Left), 0.25f);   // 0.375 >= 2 x 0.125
  EXPECT_EQ(EdgeScores(window, 0.3125f).Kept(0, 0, Side::Left), 0.0f);   // under the threshold itself
}

// The top edge's patterns are the left edge's transposed: on random windows, the top edge of a
// pixel keeps exactly what the left edge keeps in the transposed window, for every pixel whose
// patterns fit the window.
TEST(FilmicSmaaSuppression, TheTopEdgeRuleIsTheLeftEdgeRuleTransposed) {
  std::mt19937 random(12);
  std::uniform_int_distribution<int> code(0, 4);
  for (int trial = 0; trial < 2000; ++trial) {
    const LumaWindow window = WindowOf([&](int, int) { return static_cast<float>(code(random)) / 8.0f; });
    const LumaWindow transposed = WindowOf([&](int dx, int dy) { return window.At(dy, dx); });
    for (const auto& [ox, oy] : {std::pair{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
      EXPECT_EQ(EdgeScores(window, 0.125f).Kept(ox, oy, Side::Top),
                EdgeScores(transposed, 0.125f).Kept(oy, ox, Side::Left));
    }
  }
}

// ---- The rule on images, against SMAA 1x ----

using testing::Codes;
using testing::GreyImage;


PassOutput RunFilmicPass(std::string_view spec, const sim::Texture2D<glm::vec4>& image, Strategy strategy = Strategy::DeferredQueue) {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const sim::Texture2D<glm::vec4> srgb8 = Srgb8ColourTarget("colour-srgb8", image);
  return ResolvePass(spec).Make()->Run(machine, FrameInputs{.colour = &image, .colourSrgb8 = &srgb8}, strategy);
}

using testing::LayerNamed;
float At(const PassLayer& layer, int x, int y, int channel = 0) { return testing::LayerValue(layer, x, y, channel); }
float LeftEdge(const PassOutput& output, int x, int y) { return At(LayerNamed(output, "edges"), x, y, 0); }

// Seed 000's failure case of local contrast adaptation: a weak edge near a strong one. A weak
// vertical step (40 -> 80) with one bright pixel (240) two rows above the step's right side:
// SMAA's far top-top delta (160) exceeds twice the edge's (40) and drops the edge; no pattern
// through the bright pixel meets the weak edge's endpoints, so the morphological rule keeps it.
TEST(FilmicSmaaSuppression, KeepsAWeakEdgeThatLocalContrastAdaptationDrops) {
  const auto image = GreyImage(12, 10, [](int x, int y) { return x == 5 && y == 2 ? 240 : x >= 5 ? 80 : 40; });
  EXPECT_EQ(LeftEdge(RunFilmicPass("smaa", image), 5, 4), 0.0f);
  EXPECT_EQ(LeftEdge(RunFilmicPass("filmic-smaa", image), 5, 4), 1.0f);
  EXPECT_EQ(LeftEdge(RunFilmicPass("filmic-smaa", image), 5, 7), 1.0f);
}

// And the other way: a weak step (40 -> 80) beside a stronger parallel step (80 -> 140): within
// SMAA's factor 2, so SMAA keeps both; the parallel line's pattern scores higher than any through
// the weak edge, so the morphological rule drops it.
TEST(FilmicSmaaSuppression, DropsAWeakEdgeBesideAStrongerParallelLineThatSmaaKeeps) {
  const auto image = GreyImage(12, 10, [](int x, int) { return x < 5 ? 40 : x == 5 ? 80 : 140; });
  EXPECT_EQ(LeftEdge(RunFilmicPass("smaa", image), 5, 4), 1.0f);
  EXPECT_EQ(LeftEdge(RunFilmicPass("filmic-smaa", image), 5, 4), 0.0f);
  EXPECT_EQ(LeftEdge(RunFilmicPass("filmic-smaa", image), 6, 4), 1.0f);
}

// A weak vertical line crossing a strong horizontal one: right at the crossing the horizontal
// line through the weak edge's top endpoint outscores every pattern through it, so the weak edge
// is dropped there and kept away from the crossing; the strong line is kept across it.
TEST(FilmicSmaaSuppression, AWeakLineIsDroppedWhereItMeetsAStrongerCrossingLine) {
  const auto image = GreyImage(16, 16, [](int x, int y) { return (y < 8 ? 200 : 40) + (x >= 10 ? 30 : 0); });
  const PassOutput output = RunFilmicPass("filmic-smaa", image);
  EXPECT_EQ(LeftEdge(output, 10, 8), 0.0f);
  EXPECT_EQ(LeftEdge(output, 10, 12), 1.0f);
  EXPECT_EQ(LeftEdge(output, 10, 4), 1.0f);
  for (int x = 1; x < 16; ++x) EXPECT_EQ(At(LayerNamed(output, "edges"), x, 8, 1), 1.0f) << x;
}

// ---- Dual edge blending: one writer per pixel per dispatch ----

// Random images: grey noise of a few levels (edges everywhere, every tie), and blocks of random
// size (long lines, corners, 1-px features). Sizes not multiples of 8 put partial groups at the
// right and bottom.
sim::Texture2D<glm::vec4> RandomFilmicImage(unsigned seed, bool blocks) {
  std::mt19937 random(seed);
  const int width = 37 + static_cast<int>(seed % 5), height = 29 + static_cast<int>(seed % 7);
  std::uniform_int_distribution<int> level(0, 4);
  if (!blocks) return GreyImage(width, height, [&](int, int) { return 40 + 40 * level(random); });
  std::vector<int> codes(static_cast<std::size_t>(width * height), 40);
  std::uniform_int_distribution<int> x0(0, width - 1), y0(0, height - 1), side(1, 9);
  for (int block = 0; block < 30; ++block) {
    const int bx = x0(random), by = y0(random), bw = side(random), bh = side(random), code = 40 + 40 * level(random);
    for (int y = by; y < std::min(height, by + bh); ++y) {
      for (int x = bx; x < std::min(width, bx + bw); ++x) codes[static_cast<std::size_t>(y * width + x)] = code;
    }
  }
  return GreyImage(width, height, [&](int x, int y) { return codes[static_cast<std::size_t>(y * width + x)]; });
}

// A vertical item at P writes P and its left neighbour; a horizontal one P and the pixel above.
// Counts, per pixel and dispatch, the items that may write it.
void ExpectOneWriterPerPixel(const PassOutput& output, const std::string& label) {
  const PassLayer& items = LayerNamed(output, "items");
  const PassLayer& edges = LayerNamed(output, "edges");
  for (int y = 0; y < items.height; ++y) {
    for (int x = 0; x < items.width; ++x) {
      const auto item = [&](int ix, int iy) {
        return ix < items.width && iy < items.height ? static_cast<int>(At(items, ix, iy)) : 0;
      };
      const int vertical = (item(x, y) == 1) + (item(x + 1, y) == 1);
      const int horizontal = (item(x, y) == 2) + (item(x, y + 1) == 2);
      ASSERT_LE(vertical, 1) << label << " pixel (" << x << ", " << y << ")";
      ASSERT_LE(horizontal, 1) << label << " pixel (" << x << ", " << y << ")";
      // An item runs on a kept edge: the left one for a vertical item, the top one for a horizontal.
      if (item(x, y) != 0) {
        ASSERT_EQ(At(edges, x, y, item(x, y) - 1), 1.0f) << label << " (" << x << ", " << y << ")";
      }
    }
  }
}

TEST(FilmicSmaaDualEdges, NoPixelIsWrittenByTwoItemsOfOneDispatch) {
  std::uint64_t items = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    for (const bool blocks : {false, true}) {
      const auto image = RandomFilmicImage(seed, blocks);
      for (const Strategy strategy : kAllStrategies) {
        const PassOutput output = RunFilmicPass("filmic-smaa", image, strategy);
        ExpectOneWriterPerPixel(output, "seed " + std::to_string(seed) + (blocks ? " blocks " : " noise ") +
                                            std::string(StrategyName(strategy)));
        items += output.workItems;
      }
    }
  }
  EXPECT_GT(items, 1000u) << "the images must give the rule work";
}

// Without the agreement both sides of a one-pixel line would run a vertical item and both would
// write the line's pixel: the left one wins the tie, the right one gives its item up (its edge
// stays for the searches).
TEST(FilmicSmaaDualEdges, OfTwoAdjacentEqualEdgesTheLeftOneKeepsItsItem) {
  const auto image = GreyImage(16, 12, [](int x, int) { return x == 7 ? 200 : 40; });
  const PassOutput output = RunFilmicPass("filmic-smaa", image);
  for (int y = 0; y < 12; ++y) {
    EXPECT_EQ(At(LayerNamed(output, "items"), 7, y), 1.0f) << y;
    EXPECT_EQ(At(LayerNamed(output, "items"), 8, y), 0.0f) << y;
    EXPECT_EQ(LeftEdge(output, 8, y), 1.0f) << y;
  }
}

// The LDS tile's apron and gathers against the pixel form's loads, on images with edges at every
// group border.
TEST(FilmicSmaaDualEdges, StrategiesAreBitIdenticalOnRandomImages) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    for (const bool blocks : {false, true}) {
      const auto image = RandomFilmicImage(seed, blocks);
      const StrategyDifference difference =
          CompareOutputs(RunFilmicPass("filmic-smaa", image, Strategy::StencilCulled), RunFilmicPass("filmic-smaa", image));
      EXPECT_TRUE(difference.Identical()) << "seed " << seed << ": " << difference.Describe();
    }
  }
}

// ---- Output ----

// Exact coverage of a pixel by a shape, by 64x64 supersampling.
double FilmicCoverage(int x, int y, const std::function<bool(double, double)>& inside) {
  int hits = 0;
  for (int j = 0; j < 64; ++j) {
    for (int i = 0; i < 64; ++i) hits += inside(x + (i + 0.5) / 64, y + (j + 0.5) / 64);
  }
  return hits / 4096.0;
}

struct Errors {
  double aliased = 0.0, smaa = 0.0, filmic = 0.0;
  double largestCodeDifference = 0.0, meanCodeDifference = 0.0;  // filmic against SMAA 1x, 8-bit codes
};

// White shape on black: L1 errors against the true coverage, and filmic's output against SMAA's.
Errors ErrorsOf(int width, int height, const std::function<bool(double, double)>& inside) {
  const auto image = GreyImage(width, height, [&](int x, int y) { return inside(x + 0.5, y + 0.5) ? 255 : 0; });
  const PassOutput smaa = RunFilmicPass("smaa", image), filmic = RunFilmicPass("filmic-smaa", image);
  Errors errors;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double truth = FilmicCoverage(x, y, inside);
      errors.aliased += std::fabs(static_cast<double>(image.At(x, y).r) - truth);
      errors.smaa += std::fabs(static_cast<double>(smaa.colour.At(x, y).r) - truth);
      errors.filmic += std::fabs(static_cast<double>(filmic.colour.At(x, y).r) - truth);
      const double codes = std::abs(sim::FloatToSrgb8(smaa.colour.At(x, y).r) - sim::FloatToSrgb8(filmic.colour.At(x, y).r));
      errors.largestCodeDifference = std::max(errors.largestCodeDifference, codes);
      errors.meanCodeDifference += codes / (width * height);
    }
  }
  return errors;
}

// The straight edges of tests/passes_smaa_test.cpp (SmaaQuality): the horizontal items run SMAA's
// own searches on SMAA's edges, so the result is no worse than no AA (measured L1 errors, aliased /
// SMAA / filmic: slope 1/3 25.6 / 14.2 / 12.9, 1/5 24.7 / 9.3 / 9.9, 1/8 24.0 / 3.6 / 4.3,
// 1/13 24.8 / 3.1 / 3.5).
TEST(FilmicSmaaQuality, ShallowStraightEdgesAreNoWorseThanNoAntiAliasing) {
  for (const double slope : {1.0 / 3, 1.0 / 5, 1.0 / 8, 1.0 / 13}) {
    const Errors e = ErrorsOf(96, 48, [slope](double x, double y) { return y > 8.37 + slope * x; });
    EXPECT_LE(e.filmic, e.aliased) << "slope " << slope << ": SMAA " << e.smaa << ", filmic " << e.filmic;
  }
}

// A stair step of slope 1/4: the output stays close to SMAA 1x's (measured: at most 15 codes
// apart, 0.09 codes on average; L1 error 13.2 against SMAA's 12.4). The first pixel of each run
// has a left and a top edge of equal contrast and runs only the left one (ties go left).
TEST(FilmicSmaaQuality, AStairStepComesCloseToSmaa) {
  const Errors e = ErrorsOf(96, 48, [](double x, double y) { return y > 8.37 + 0.25 * x; });
  EXPECT_LE(e.largestCodeDifference, 16.0);
  EXPECT_LE(e.meanCodeDifference, 0.25);
  EXPECT_LE(e.filmic, 1.1 * e.smaa) << "aliased " << e.aliased << ", SMAA " << e.smaa;
}

}  // namespace
}  // namespace passes
