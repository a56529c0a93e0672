// CMAA2 v2.3 (aa-facts §4; passes/cmaa2/): the R11G11B10 E4 packing against its value-domain
// definition, the edge rule and the candidate test on hand-built windows, golden images with
// hand-derived expectations (a straight step, an L corner, a Z step of known length), symmetry,
// the presets, in-place writes of changed pixels only, and the checkerboard worst case against
// the list capacities.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "passes/cmaa2/cmaa2_kernels.h"
#include "passes/cmaa2/e4_colour.h"
#include "passes/compare.h"
#include "passes/registry.h"
#include "passes_test_util.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"

namespace passes {
namespace {

using testing::Codes;
using testing::GreyImage;

// ---- R11G11B10 E4 ----

// The E4 value nearest to half `h` (ties away from zero), found in the value domain: the
// representable neighbours are the halves with the field's dropped low bits cleared.
float NearestE4(std::uint16_t h, int droppedBits) {
  const auto step = static_cast<std::uint16_t>(1u << droppedBits);
  const auto below = static_cast<std::uint16_t>(h & ~(step - 1u));
  const auto above = static_cast<std::uint16_t>(below + step);
  const double value = static_cast<double>(sim::HalfToFloat(h)), low = static_cast<double>(sim::HalfToFloat(below)),
               high = static_cast<double>(sim::HalfToFloat(above));
  return static_cast<float>(value - low < high - value ? low : high);
}

// Every half in [0, 2) whose rounding stays below 2 (the format's range; the packing's carry out of
// the field at the top wraps, unreachable for LDR colours <= 1): each channel unpacks to the
// nearest value its 7 (R, G) or 6 (B) mantissa bits hold.
TEST(Cmaa2E4Colour, EveryHalfBelowTwoPacksToTheNearestRepresentableValuePerChannel) {
  for (std::uint16_t h = 0; h < 0x3FF8; ++h) {
    const float x = sim::HalfToFloat(h);
    ASSERT_EQ(cmaa2::UnpackR11G11B10E4(cmaa2::PackR11G11B10E4({x, 0, 0})).r, NearestE4(h, 3)) << h;
    ASSERT_EQ(cmaa2::UnpackR11G11B10E4(cmaa2::PackR11G11B10E4({0, x, 0})).g, NearestE4(h, 3)) << h;
    if (h < 0x3FF0) {
      ASSERT_EQ(cmaa2::UnpackR11G11B10E4(cmaa2::PackR11G11B10E4({0, 0, x})).b, NearestE4(h, 4)) << h;
    }
  }
}

TEST(Cmaa2E4Colour, FieldsSitWhereTheFormulaPutsThem) {
  // 1.0 is half 0x3C00: R (0x3C00 + 4) >> 3 = 0x780 in bits 0..10, G 0x780 in bits 11..21, B
  // (0x3C00 + 8) >> 4 = 0x3C0 in bits 22..31.
  EXPECT_EQ(cmaa2::PackR11G11B10E4({1, 0, 0}), 0x780u);
  EXPECT_EQ(cmaa2::PackR11G11B10E4({0, 1, 0}), 0x780u << 11);
  EXPECT_EQ(cmaa2::PackR11G11B10E4({0, 0, 1}), 0x3C0u << 22);
  EXPECT_EQ(cmaa2::PackR11G11B10E4({-1, 0, 0}), 0u);  // clamped to 0
  // Every 8-bit sRGB colour survives within half a step of 7 (6) mantissa bits.
  for (int code = 0; code < 256; ++code) {
    const float x = sim::Srgb8ToFloat(static_cast<std::uint8_t>(code));
    const glm::vec3 back = cmaa2::UnpackR11G11B10E4(cmaa2::PackR11G11B10E4({x, x, x}));
    EXPECT_LE(std::fabs(back.r - x), x * 0x1p-8f + 0x1p-24f) << code;
    EXPECT_LE(std::fabs(back.b - x), x * 0x1p-7f + 0x1p-24f) << code;
  }
}

// ---- Edges and candidates ----

std::uint32_t EdgeBits(const std::function<float(int, int)>& luma, float threshold = 0.07f, float lca = 0.10f) {
  return cmaa2::EdgesOf(luma, cmaa2::Config{.edgeThreshold = threshold, .localContrastAdaptation = lca});
}

TEST(Cmaa2Edges, AStepGivesTheEdgeOnItsSideOnly) {
  EXPECT_EQ(EdgeBits([](int dx, int) { return dx > 0 ? 1.0f : 0.0f; }), cmaa2::kEdgeRight);
  EXPECT_EQ(EdgeBits([](int dx, int) { return dx < 0 ? 1.0f : 0.0f; }), cmaa2::kEdgeLeft);
  EXPECT_EQ(EdgeBits([](int, int dy) { return dy > 0 ? 1.0f : 0.0f; }), cmaa2::kEdgeBelow);
  EXPECT_EQ(EdgeBits([](int, int dy) { return dy < 0 ? 1.0f : 0.0f; }), cmaa2::kEdgeAbove);
  EXPECT_EQ(EdgeBits([](int dx, int dy) { return dx == 0 && dy == 0 ? 1.0f : 0.0f; }), 0xFu);
}

TEST(Cmaa2Edges, TheThresholdIsStrict) {
  const auto step = [](float contrast) { return [=](int dx, int) { return dx > 0 ? contrast : 0.0f; }; };
  EXPECT_EQ(EdgeBits(step(0.07f)), 0u);  // 0.07 - 0 > 0.07 is false
  EXPECT_EQ(EdgeBits(step(std::nextafter(0.07f, 1.0f))), cmaa2::kEdgeRight);
}

// The right edge (contrast 0.25) loses 0.1 x the strongest perpendicular contrast at its ends:
// a horizontal edge of contrast 2 through its lower end leaves 0.05 (off), of 1.5 leaves 0.1 (on).
TEST(Cmaa2Edges, LocalContrastAdaptationRemovesAnEdgeBesideAStrongerPerpendicularOne) {
  const auto window = [](float below) {
    return [=](int dx, int dy) { return (dx > 0 ? 0.25f : 0.0f) + (dy > 0 ? below : 0.0f); };
  };
  EXPECT_EQ(EdgeBits(window(2.0f)) & cmaa2::kEdgeRight, 0u);
  EXPECT_EQ(EdgeBits(window(1.5f)) & cmaa2::kEdgeRight, cmaa2::kEdgeRight);
  EXPECT_EQ(EdgeBits(window(2.0f), 0.07f, 0.0f) & cmaa2::kEdgeRight, cmaa2::kEdgeRight);  // no adaptation
}

// A candidate has two edges meeting at a corner: every edge set but the empty one, the four
// single edges and the two parallel pairs (left + right, above + below).
TEST(Cmaa2Edges, CandidatesAreTheEdgeSetsWithACorner) {
  for (std::uint32_t bits = 0; bits < 16; ++bits) {
    const bool expected = !(bits == 0 || bits == 1 || bits == 2 || bits == 4 || bits == 8 || bits == 5 || bits == 10);
    EXPECT_EQ(cmaa2::IsCandidate(bits), expected) << bits;
  }
}

// The head reset of a 2x2 block looks at its 12 contrasts (window offsets -1..2): a single pixel
// changed in the 4x4 window around the block triggers it unless it is a corner of the window,
// which touches none of them.
TEST(Cmaa2Edges, ABlockResetsItsHeadWhenOneOfItsTwelveContrastsIsNonZero) {
  for (int py = -1; py <= 2; ++py) {
    for (int px = -1; px <= 2; ++px) {
      const bool corner = (px == -1 || px == 2) && (py == -1 || py == 2);
      EXPECT_EQ(cmaa2::BlockHasContrast([&](int dx, int dy) { return dx == px && dy == py ? 0.5f : 0.25f; }), !corner)
          << px << "," << py;
    }
  }
}

// ---- Pass runs ----

struct Cmaa2Run {
  PassOutput output;
  std::vector<sim::DispatchReport> reports;

  float Layer(std::string_view name, int x, int y) const {
    return testing::LayerValue(testing::LayerNamed(output, name), x, y);
  }

  std::uint64_t Counter(std::string_view dispatch, std::string_view name) const {
    return testing::PassCounterValue(reports, dispatch, name);
  }
  std::uint64_t BytesWritten(std::string_view dispatch, std::string_view resource) const {
    for (const sim::DispatchReport& report : reports) {
      if (report.name != dispatch) continue;
      for (const sim::ResourceTraffic& traffic : report.resources) {
        if (traffic.name == resource) return traffic.bytesWritten;
      }
    }
    throw std::logic_error("no resource " + std::string(resource));
  }
  // The output's 8-bit sRGB code of the red channel.
  int Code(int x, int y) const { return sim::FloatToSrgb8(output.colour.At(x, y).r); }
};

Cmaa2Run RunCmaa2(const sim::Texture2D<glm::vec4>& image, Strategy strategy = Strategy::DeferredQueue,
             std::string_view spec = "cmaa2") {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const sim::Texture2D<glm::vec4> srgb8 = Srgb8ColourTarget("colour-srgb8", image);
  Cmaa2Run run{ResolvePass(spec).Make()->Run(machine, FrameInputs{.colour = &image, .colourSrgb8 = &srgb8}, strategy),
               {}};
  run.reports = machine.Reports();
  return run;
}

// The 8-bit code CMAA2 stores for a linear value (LINEAR_to_SRGB, +0.5 rounding), in double.
int StoredCode(double linear) {
  const double srgb = linear < 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<int>(std::floor(std::clamp(srgb, 0.0, 1.0) * 255.0 + 0.5));
}

void ExpectBothStrategiesEqual(const sim::Texture2D<glm::vec4>& image) {
  const StrategyDifference difference =
      CompareOutputs(RunCmaa2(image, Strategy::StencilCulled).output, RunCmaa2(image, Strategy::DeferredQueue).output);
  EXPECT_TRUE(difference.Identical()) << difference.Describe();
}

// A vertical step between two greys across the whole image: no candidate away from the border.
// Where the brighter side meets the border, the reference's loads outside the texture read 0
// (black), so its corners with the border are candidates: only rows 0 and H-1 may change.
TEST(Cmaa2Golden, AStraightStepHasNoCandidatesAndStaysUntouchedAwayFromTheBorder) {
  const int width = 24, height = 16;
  const sim::Texture2D<glm::vec4> image = GreyImage(width, height, [](int x, int) { return x < 11 ? 40 : 200; });
  const Cmaa2Run run = RunCmaa2(image);
  for (int y = 1; y < height - 1; ++y) {
    for (int x = 1; x < width - 1; ++x) {
      EXPECT_EQ(run.Layer("candidates", x, y), 0.0f) << x << "," << y;
      EXPECT_EQ(run.Code(x, y), x < 11 ? 40 : 200) << x << "," << y;
    }
  }
  EXPECT_EQ(run.Layer("edges", 10, 5), static_cast<float>(cmaa2::kEdgeRight));
  EXPECT_EQ(run.Layer("edges", 11, 5), static_cast<float>(cmaa2::kEdgeLeft));
  EXPECT_EQ(run.Layer("candidates", 0, 0), 1.0f);  // left and top edges against the black outside
  ExpectBothStrategiesEqual(image);
}

// A white rectangle on black, away from the border: its four inner corner pixels are the only
// candidates. The top-left one (edges left and above) blends 0.1 x 0.75 from each of its two
// outside neighbours (the L-continuation terms vanish: its right neighbour also has an edge
// above, its lower one also on the left; 2 edges around, damping saturate(1.3 - 0.2) = 1):
// 0.85 linear, a single 0.8-weight item, so the mean is that item's colour.
TEST(Cmaa2Golden, AnLCornerBlendsOnlyItsCornerPixelFromItsTwoOutsideNeighbours) {
  const int width = 20, height = 16;
  const auto inside = [](int x, int y) { return x >= 5 && x <= 14 && y >= 4 && y <= 11; };
  const sim::Texture2D<glm::vec4> image = GreyImage(width, height, [&](int x, int y) { return inside(x, y) ? 255 : 0; });
  const Cmaa2Run run = RunCmaa2(image);
  const int cornerCode = StoredCode(0.85);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool corner = (x == 5 || x == 14) && (y == 4 || y == 11);
      EXPECT_EQ(run.Layer("candidates", x, y), corner ? 1.0f : 0.0f) << x << "," << y;
      EXPECT_NEAR(run.Code(x, y), corner ? cornerCode : inside(x, y) ? 255 : 0, corner ? 1 : 0) << x << "," << y;
    }
  }
  EXPECT_EQ(run.Counter("cmaa2/process-candidates", "cmaa2/blend_items"), 4u);
  EXPECT_EQ(run.Counter("cmaa2/process-candidates", "cmaa2/z_shapes"), 0u);
  // Only changed pixels are written: 4 pixels of 4 bytes.
  EXPECT_EQ(run.BytesWritten("cmaa2/deferred-colour-apply", "cmaa2/colour"), 16u);
  ExpectBothStrategiesEqual(image);
}

// A white rectangle whose bottom boundary steps down by one row at x = 16: rows 2..7 for x in
// 4..15, rows 2..8 for x in 16..27. The black pixel (15, 8) (edges above and right) holds a
// normal Z of score 4 (quality 0). Its trace runs left along the top edges of (14..4, 8) and right
// along the bottom edges of (17..27, 8): both stop in the same step, lengths 12 and 12. Items
// for i in -5..6 at (15 + i, 8), lerp k = (i + 5.5) / 12 from above for i <= 0 and
// 1 - (i + 5.5) / 12 from below for i > 0 (no odd-length correction, dampening saturate(24 x
// 0.15) = 1), quantised to 10 bits. (15, 8) and (16, 8) also hold their simple-shape items.
TEST(Cmaa2Golden, AZStepOfLength24BlendsALinearRampAlongTheStep) {
  const int width = 32, height = 12;
  const auto inside = [](int x, int y) { return y >= 2 && ((x >= 4 && x <= 15 && y <= 7) || (x >= 16 && x <= 27 && y <= 8)); };
  const sim::Texture2D<glm::vec4> image = GreyImage(width, height, [&](int x, int y) { return inside(x, y) ? 255 : 0; });
  const Cmaa2Run run = RunCmaa2(image);
  EXPECT_EQ(run.Counter("cmaa2/process-candidates", "cmaa2/z_shapes"), 1u);
  const auto quantised = [](double k) { return std::floor(k * 1023.0 + 0.5) / 1023.0; };
  for (int i = -5; i <= 6; ++i) {
    const int x = 15 + i;
    const double k = quantised(i <= 0 ? (i + 5.5) / 12.0 : 1.0 - (i + 5.5) / 12.0);
    double expected = i <= 0 ? k : 1.0 - k;  // black pulled towards white above, white towards black below
    // Simple shapes: (15, 8) takes 0.075 x 1.9 from above and 0.075 from the right (0.2175);
    // (16, 8) mirrors it: 1 - 0.2175. Means with weights 0.8 and 1.8.
    if (x == 15) expected = (0.8 * 0.2175 + 1.8 * expected) / 2.6;
    if (x == 16) expected = (0.8 * (1.0 - 0.2175) + 1.8 * expected) / 2.6;
    EXPECT_NEAR(run.Code(x, 8), StoredCode(expected), 1) << x;
  }
  for (int x = 6; x <= 25; ++x) {
    EXPECT_EQ(run.Code(x, 7), 255) << x;
    EXPECT_EQ(run.Code(x, 9), 0) << x;
    if (x < 10 || x > 21) {
      EXPECT_EQ(run.Code(x, 8), inside(x, 8) ? 255 : 0) << x;
    }
  }
  ExpectBothStrategiesEqual(image);
}

// Odd sizes put a pixel pair's second half outside the image (its nibble computed from black, as
// the reference's 2x2 threads do) and leave partial quads, tiles and groups: random three-level
// images keep the strategies bit-identical, with Zs among them.
TEST(Cmaa2Golden, OddSizedRandomImagesGiveBitIdenticalImagesUnderBothStrategies) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> level(0, 2);
  std::uint64_t zShapes = 0;
  for (const auto& size : {std::pair{37, 23}, {1, 9}, {9, 1}, {64, 3}}) {
    const int width = size.first, height = size.second;
    std::vector<int> codes(static_cast<std::size_t>(width * height));
    for (int& code : codes) code = level(random) * 120;
    const sim::Texture2D<glm::vec4> image =
        GreyImage(width, height, [&](int x, int y) { return codes[static_cast<std::size_t>(y * width + x)]; });
    ExpectBothStrategiesEqual(image);
    const Cmaa2Run run = RunCmaa2(image);
    zShapes += run.Counter("cmaa2/process-candidates", "cmaa2/z_shapes");
    // Nearly every quad has items: the reference's (W*H + 3) / 4 locations would not hold the
    // 19 x 12 quads of 37 x 23 (213 < 228); one location per quad does.
    EXPECT_EQ(run.Counter("cmaa2/process-candidates", "cmaa2/blend_locations_dropped"), 0u);
    EXPECT_EQ(run.Counter("cmaa2/process-candidates", "cmaa2/blend_items_dropped"), 0u);
  }
  EXPECT_GT(zShapes, 0u);
}

// ---- Symmetry ----

sim::Texture2D<glm::vec4> TransformedImage(const sim::Texture2D<glm::vec4>& image, int kind) {
  const int w = image.Width(), h = image.Height();
  const bool transpose = kind == 2;
  sim::Texture2D<glm::vec4> out("transformed", transpose ? h : w, transpose ? w : h, 16);
  for (int y = 0; y < out.Height(); ++y) {
    for (int x = 0; x < out.Width(); ++x) {
      out.At(x, y) = kind == 0 ? image.At(w - 1 - x, y) : kind == 1 ? image.At(x, h - 1 - y) : image.At(y, x);
    }
  }
  return out;
}

// The Z step image of the golden test with its halves `left` and `right` pixels long.
sim::Texture2D<glm::vec4> ZStep(int left, int right) {
  const auto inside = [=](int x, int y) {
    return y >= 2 && ((x >= 16 - left && x <= 15 && y <= 7) || (x >= 16 && x < 16 + right && y <= 8));
  };
  return GreyImage(40, 12, [&](int x, int y) { return inside(x, y) ? 255 : 0; });
}

// Whether CMAA2's output of the image transformed by `kind` (0: mirror x, 1: mirror y, 2:
// transpose), transformed back, is bit-identical to its output of the image.
bool Symmetric(const sim::Texture2D<glm::vec4>& image, int kind) {
  const PassOutput straight = RunCmaa2(image).output;
  const sim::Texture2D<glm::vec4> back = TransformedImage(RunCmaa2(TransformedImage(image, kind)).output.colour, kind);
  for (int y = 0; y < image.Height(); ++y) {
    for (int x = 0; x < image.Width(); ++x) {
      if (back.At(x, y) != straight.colour.At(x, y)) return false;
    }
  }
  return true;
}

// A Z with equal halves comes out the same mirrored in x (the normal Z found at the black pixel
// becomes an inverted Z found at the white one: same lengths, same pixels), in y, or transposed.
TEST(Cmaa2Symmetry, AZWithEqualHalvesMirrorsAndTransposesBitForBit) {
  for (const int kind : {0, 1, 2}) {
    EXPECT_TRUE(Symmetric(ZStep(12, 12), kind)) << kind;
    EXPECT_TRUE(Symmetric(ZStep(7, 7), kind)) << kind;
  }
}

// Swapping the halves' sides (mirror in x, transpose) swaps which half is computed as
// (lerpStep i + lerpFromK) and which as 1 - (...): the same lerp factors in exact arithmetic, not
// always in float. Halves 8 and 10 (lerp step 1/9) give pixel (13, 8) the factor 1.5 / 9, and
// 1.5 / 9 x 1023 = 170.5 is a tie of the 10-bit quantisation: float rounding on either side picks
// 170 or 171, one code apart in the output. Mirroring in y keeps the sides and stays exact.
TEST(Cmaa2Symmetry, SwappingAZsHalvesCanMoveOnePixelByOneCode) {
  const sim::Texture2D<glm::vec4> image = ZStep(8, 10);
  EXPECT_TRUE(Symmetric(image, 1));
  for (const int kind : {0, 2}) {
    EXPECT_FALSE(Symmetric(image, kind)) << kind;
    const PassOutput straight = RunCmaa2(image).output;
    const sim::Texture2D<glm::vec4> back = TransformedImage(RunCmaa2(TransformedImage(image, kind)).output.colour, kind);
    int differing = 0;
    for (int y = 0; y < image.Height(); ++y) {
      for (int x = 0; x < image.Width(); ++x) {
        const int a = sim::FloatToSrgb8(straight.colour.At(x, y).r), b = sim::FloatToSrgb8(back.At(x, y).r);
        EXPECT_LE(std::abs(a - b), 1) << kind << ": " << x << "," << y;
        differing += a != b;
      }
    }
    EXPECT_EQ(differing, 1) << kind;
  }
}

// ---- Presets ----

TEST(Cmaa2Presets, QualityPresetsSetTheReferenceThresholdsAndTscmaaItsEdgeSettings) {
  const auto get = [](std::string_view spec, std::string_view key) { return ResolvePass(spec).settings.Get(key); };
  EXPECT_EQ(get("cmaa2", "threshold"), 0.07);
  EXPECT_EQ(get("cmaa2:preset=low", "threshold"), 0.15);
  EXPECT_EQ(get("cmaa2:preset=medium", "threshold"), 0.10);
  EXPECT_EQ(get("cmaa2:preset=high", "threshold"), 0.07);
  EXPECT_EQ(get("cmaa2:preset=ultra", "threshold"), 0.05);
  EXPECT_EQ(get("cmaa2:preset=tscmaa", "threshold"), 1.0 / 22.0);
  EXPECT_EQ(get("cmaa2:preset=tscmaa", "local_contrast_adaptation"), 0.5);
  EXPECT_EQ(get("cmaa2", "local_contrast_adaptation"), 0.10);
}

// An L corner of luma contrast ~0.12 (codes 60 and 100: sqrt-luma 0.218 and 0.356... measured
// through the pass): found at HIGH (0.07) and MEDIUM (0.10), not at LOW (0.15).
TEST(Cmaa2Presets, TheThresholdDecidesWhetherAWeakCornerIsACandidate) {
  const auto inside = [](int x, int y) { return x >= 4 && x <= 11 && y >= 4 && y <= 11; };
  const sim::Texture2D<glm::vec4> image = GreyImage(16, 16, [&](int x, int y) { return inside(x, y) ? 100 : 60; });
  // sqrt of the decoded linear values, the luma CMAA2 compares (grey: the weights sum to 1).
  const double contrast = static_cast<double>(std::sqrt(sim::Srgb8ToFloat(100)) - std::sqrt(sim::Srgb8ToFloat(60)));
  ASSERT_GT(contrast, 0.10);
  ASSERT_LT(contrast, 0.15);
  EXPECT_EQ(RunCmaa2(image, Strategy::DeferredQueue, "cmaa2:preset=high").Layer("candidates", 4, 4), 1.0f);
  EXPECT_EQ(RunCmaa2(image, Strategy::DeferredQueue, "cmaa2:preset=medium").Layer("candidates", 4, 4), 1.0f);
  EXPECT_EQ(RunCmaa2(image, Strategy::DeferredQueue, "cmaa2:preset=low").Layer("candidates", 4, 4), 0.0f);
}

// ---- Worst case ----

// A black and white checkerboard: every pixel is a candidate (white border pixels see black
// outside; black ones have three edges), every pixel gets one simple-shape item (all Z scores
// are negative: 2 + 2 - 2 - 0.7 x 4 inside) and no Z. The default lists hold them all; the
// reference's default lists (W*H/2 items) drop half the items, counted.
TEST(Cmaa2WorstCase, ACheckerboardFillsTheCompleteListsAndOverflowsTheReferenceDefaultsCounted) {
  const int side = 16, pixels = side * side;
  const sim::Texture2D<glm::vec4> image = GreyImage(side, side, [](int x, int y) { return (x + y) % 2 ? 255 : 0; });
  for (const Strategy strategy : kAllStrategies) {
    const Cmaa2Run complete = RunCmaa2(image, strategy);
    EXPECT_EQ(complete.output.workItems, static_cast<std::uint64_t>(pixels));
    EXPECT_EQ(complete.Counter("cmaa2/process-candidates", "cmaa2/blend_items"), static_cast<std::uint64_t>(pixels));
    EXPECT_EQ(complete.Counter("cmaa2/process-candidates", "cmaa2/blend_items_dropped"), 0u);
    EXPECT_EQ(complete.Counter("cmaa2/process-candidates", "cmaa2/blend_locations_dropped"), 0u);
    EXPECT_EQ(complete.Counter("cmaa2/process-candidates", "cmaa2/z_shapes"), 0u);
    EXPECT_EQ(complete.BytesWritten("cmaa2/deferred-colour-apply", "cmaa2/colour"), 4u * pixels);
    // Inside: four edges, 12 around: 0.1 x saturate(1.3 - 1.2) from each neighbour.
    EXPECT_NEAR(complete.Code(5, 5), StoredCode(0.04), 1);
    EXPECT_NEAR(complete.Code(6, 5), StoredCode(0.96), 1);

    const Cmaa2Run reference = RunCmaa2(image, strategy, "cmaa2:reference_buffers=1");
    EXPECT_EQ(reference.Counter("cmaa2/process-candidates", "cmaa2/blend_items"), static_cast<std::uint64_t>(pixels / 2));
    EXPECT_EQ(reference.Counter("cmaa2/process-candidates", "cmaa2/blend_items_dropped"),
              static_cast<std::uint64_t>(pixels / 2));
  }
  ExpectBothStrategiesEqual(image);
}

// Four-level noise (codes 0, 85, 170, 255) is worse than the checkerboard for the item list: Z
// shapes add their line pixels to most candidates' simple-shape items, more items than pixels (the
// reference's "enough in all cases" W*H would drop some). Two per pixel hold them; the reference's
// default W*H/2 fills up and counts every item it refuses.
TEST(Cmaa2WorstCase, NoiseMakesMoreItemsThanPixelsAndTheDefaultListHoldsThem) {
  const int side = 64, pixels = side * side;
  std::mt19937 random(0);
  std::uniform_int_distribution<int> level(0, 3);
  std::vector<int> codes(static_cast<std::size_t>(pixels));
  for (int& code : codes) code = level(random) * 85;
  const sim::Texture2D<glm::vec4> image =
      GreyImage(side, side, [&](int x, int y) { return codes[static_cast<std::size_t>(y * side + x)]; });
  const Cmaa2Run run = RunCmaa2(image);
  const std::uint64_t items = run.Counter("cmaa2/process-candidates", "cmaa2/blend_items");
  EXPECT_GT(items, static_cast<std::uint64_t>(pixels));
  EXPECT_EQ(run.Counter("cmaa2/process-candidates", "cmaa2/blend_items_dropped"), 0u);
  ExpectBothStrategiesEqual(image);
  const Cmaa2Run reference = RunCmaa2(image, Strategy::DeferredQueue, "cmaa2:reference_buffers=1");
  EXPECT_EQ(reference.Counter("cmaa2/process-candidates", "cmaa2/blend_items"), static_cast<std::uint64_t>(pixels / 2));
  EXPECT_EQ(reference.Counter("cmaa2/process-candidates", "cmaa2/blend_items_dropped"), items - pixels / 2);
}

// Single white pixels on the even-even grid: each is a candidate with one simple-shape item (no
// Z: its neighbours' edges are parallel), one item per quad, so 64 quads need a location. The
// reference's default location list holds (256 + 3) / 6 = 43: 21 quads are dropped, counted, and
// left unwritten; the item list (128) holds all 64 items.
TEST(Cmaa2WorstCase, ALocationOverflowIsCountedAndItsQuadsAreLeftUnwritten) {
  const int side = 16;
  const sim::Texture2D<glm::vec4> image =
      GreyImage(side, side, [](int x, int y) { return x % 2 == 0 && y % 2 == 0 ? 255 : 0; });
  for (const Strategy strategy : kAllStrategies) {
    const Cmaa2Run run = RunCmaa2(image, strategy, "cmaa2:reference_buffers=1");
    EXPECT_EQ(run.Counter("cmaa2/process-candidates", "cmaa2/blend_items"), 64u);
    EXPECT_EQ(run.Counter("cmaa2/process-candidates", "cmaa2/blend_items_dropped"), 0u);
    EXPECT_EQ(run.Counter("cmaa2/process-candidates", "cmaa2/blend_locations_dropped"), 21u);
    EXPECT_EQ(run.BytesWritten("cmaa2/deferred-colour-apply", "cmaa2/colour"), 4u * 43u);
    const Cmaa2Run complete = RunCmaa2(image, strategy);
    EXPECT_EQ(complete.Counter("cmaa2/process-candidates", "cmaa2/blend_locations_dropped"), 0u);
    EXPECT_EQ(complete.BytesWritten("cmaa2/deferred-colour-apply", "cmaa2/colour"), 4u * 64u);
  }
}

}  // namespace
}  // namespace passes
