// SMAA 1x on synthetic images whose edges and weights follow from the algorithm's definition
// (aa-facts §1.3-§1.6), independently of the kernels: edge rules, zero weights where SMAA has
// nothing to blend, transposition symmetry, preset search lengths, and error against an
// analytically supersampled disc.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "passes/registry.h"
#include "passes_test_util.h"
#include "sim/colour.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"

namespace passes {
namespace {

using testing::Codes;
using testing::GreyImage;


struct SmaaRun {
  PassOutput output;
  std::vector<sim::DispatchReport> reports;

  const PassLayer& Layer(std::string_view name) const { return testing::LayerNamed(output, name); }
  float At(std::string_view layer, int x, int y, int channel) const {
    return testing::LayerValue(Layer(layer), x, y, channel);
  }
  std::uint64_t Counter(std::string_view dispatch, std::string_view name) const {
    return testing::PassCounterValue(reports, dispatch, name);
  }
};

SmaaRun RunSmaa(std::string_view spec, const sim::Texture2D<glm::vec4>& image,
            Strategy strategy = Strategy::DeferredQueue, const sim::Texture2D<float>* depth = nullptr) {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const PassConfig config = ResolvePass(spec);
  const sim::Texture2D<glm::vec4> srgb8 = Srgb8ColourTarget("colour-srgb8", image);
  SmaaRun run{config.Make()->Run(machine, FrameInputs{.colour = &image, .colourSrgb8 = &srgb8, .depth = depth}, strategy),
              {}};
  run.reports = machine.Reports();
  return run;
}

// Codes of the output's red channel, as the 8-bit sRGB target holds them.
int OutputCode(const SmaaRun& run, int x, int y) { return sim::FloatToSrgb8(run.output.colour.At(x, y).r); }

constexpr int kSmaaDark = 40, kSmaaBright = 200;

// ---- Edge detection (aa-facts §1.3) ----

TEST(SmaaEdges, AVerticalStepMarksTheLeftEdgeOfTheColumnRightOfIt) {
  const auto image = GreyImage(16, 8, [](int x, int) { return x < 6 ? kSmaaDark : kSmaaBright; });
  const SmaaRun run = RunSmaa("smaa", image);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 16; ++x) {
      EXPECT_EQ(run.At("edges", x, y, 0), x == 6 ? 1.0f : 0.0f) << x << "," << y;
      EXPECT_EQ(run.At("edges", x, y, 1), 0.0f) << x << "," << y;
    }
  }
  EXPECT_EQ(run.output.workItems, 8u);
}

// The threshold test is step(threshold, delta): a delta equal to the threshold is an edge.
TEST(SmaaEdges, ADeltaEqualToTheThresholdIsAnEdge) {
  const auto image = GreyImage(8, 4, [](int x, int) { return x < 4 ? 100 : 151; });
  // The luma delta the reference computes: dot(rgb, (0.2126, 0.7152, 0.0722)) on k / 255 codes.
  const auto luma = [](int code) {
    const float v = sim::Unorm8ToFloat(static_cast<std::uint8_t>(code));
    return v * 0.2126f + (v * 0.7152f + v * 0.0722f);
  };
  const float delta = std::fabs(luma(151) - luma(100));
  char exact[64];  // %.9g prints a float exactly enough to read back the same float
  std::snprintf(exact, sizeof exact, "smaa:threshold=%.9g", static_cast<double>(delta));
  EXPECT_EQ(RunSmaa(exact, image).output.workItems, 4u);
  std::snprintf(exact, sizeof exact, "smaa:threshold=%.9g", static_cast<double>(std::nextafter(delta, 1.0f)));
  EXPECT_EQ(RunSmaa(exact, image).output.workItems, 0u);
}

// Local contrast adaptation: an edge survives only if no neighbouring delta exceeds twice its
// own; equality keeps it.
TEST(SmaaEdges, LocalContrastAdaptationDropsAWeakEdgeBesideAStrongOne) {
  // Columns: ... 100 | 150 (the edge, delta 50) | the right neighbour: 255 (delta 105) drops it.
  for (const auto& [right, kept] : {std::pair{255, false}, std::pair{200, true}, std::pair{150, true}}) {
    const auto image = GreyImage(8, 1, [right = right](int x, int) { return x < 3 ? 100 : x == 3 ? 150 : right; });
    const SmaaRun run = RunSmaa("smaa:threshold=0.05", image);
    EXPECT_EQ(run.At("edges", 3, 0, 0), kept ? 1.0f : 0.0f) << "right neighbour " << right;
  }
}

// The luma path measures the left-left delta from the left neighbour, the colour path from the
// centre (aa-facts §1.3).
TEST(SmaaEdges, FarDeltasAreMeasuredFromTheNeighbourInLumaAndFromTheCentreInColour) {
  // Codes 45 45 100 [130] 130: the edge's own delta is 30, so a far delta above 60 drops it. Luma
  // measures |100 - 45| = 55 and keeps it; colour measures |130 - 45| = 85 and drops it.
  const auto image = GreyImage(5, 1, [](int x, int) { return x >= 3 ? 130 : x == 2 ? 100 : 45; });
  EXPECT_EQ(RunSmaa("smaa:threshold=0.05", image).At("edges", 3, 0, 0), 1.0f);
  EXPECT_EQ(RunSmaa("smaa-colour:threshold=0.05", image).At("edges", 3, 0, 0), 0.0f);
}

TEST(SmaaEdges, DepthEdgesUseATenthOfTheThreshold) {
  const auto image = GreyImage(8, 4, [](int, int) { return 128; });
  sim::Texture2D<float> depth("depth", 8, 4, 4, 0.5f);
  for (int y = 0; y < 4; ++y) {
    for (int x = 4; x < 8; ++x) depth.At(x, y) = 0.5f + 0.0101f;
  }
  EXPECT_EQ(RunSmaa("smaa-depth:threshold=0.1", image, Strategy::DeferredQueue, &depth).output.workItems, 4u);
  EXPECT_EQ(RunSmaa("smaa-depth:threshold=0.102", image, Strategy::DeferredQueue, &depth).output.workItems, 0u);
}

// Predication: 2 x threshold away from depth edges, 2 x threshold x 0.6 on them (aa-facts §1.3).
TEST(SmaaEdges, PredicationLowersTheThresholdOnlyWhereTheDepthHasAnEdge) {
  // A luma step of about 0.16: above SMAA's 0.1 but below the predicated 0.2 away from depth
  // edges, above 0.12 on them.
  const auto image = GreyImage(16, 4, [](int x, int) { return x < 8 ? 100 : 141; });
  sim::Texture2D<float> flat("depth", 16, 4, 4, 0.5f);
  EXPECT_EQ(RunSmaa("smaa", image).output.workItems, 4u);
  EXPECT_EQ(RunSmaa("smaa-predicated", image, Strategy::DeferredQueue, &flat).output.workItems, 0u);
  sim::Texture2D<float> stepped = flat;
  for (int y = 0; y < 4; ++y) {
    for (int x = 8; x < 16; ++x) stepped.At(x, y) = 0.9f;
  }
  EXPECT_EQ(RunSmaa("smaa-predicated", image, Strategy::DeferredQueue, &stepped).output.workItems, 4u);
}

// ---- Blending weights: where SMAA has nothing to blend ----

TEST(SmaaWeights, StraightEdgesWithoutEndsGetNoWeight) {
  const auto image = GreyImage(64, 32, [](int, int y) { return y < 16 ? kSmaaDark : kSmaaBright; });
  const SmaaRun run = RunSmaa("smaa", image);
  EXPECT_EQ(run.output.workItems, 64u);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 64; ++x) {
      for (int c = 0; c < 4; ++c) ASSERT_EQ(run.At("weights", x, y, c), 0.0f) << x << "," << y << " channel " << c;
      ASSERT_EQ(OutputCode(run, x, y), image.At(x, y).r > 0.5f ? kSmaaBright : kSmaaDark);
    }
  }
}

// Every edge of a checkerboard is one pixel long and crossed at both ends in both rows: a "+"
// pattern at each end, whose area is zero (aa-facts §1.6).
TEST(SmaaWeights, ACheckerboardIsLeftAlone) {
  const auto image = GreyImage(16, 16, [](int x, int y) { return (x + y) % 2 ? kSmaaDark : kSmaaBright; });
  const SmaaRun run = RunSmaa("smaa:preset=medium", image);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) ASSERT_EQ(OutputCode(run, x, y), (x + y) % 2 ? kSmaaDark : kSmaaBright) << x << "," << y;
  }
}

// ---- Blending weights against the analytic areas of the revectorised line (aa-facts §1.6) ----

// The area between a straight segment h(t) (height above the edge, in pixels) and the edge over
// [l, l + 1]: the part above goes to G (the pixel above blends towards this one), the part
// below to R (this pixel blends towards the one above), as aa-facts §1.5 reads the channels.
struct AreaPair {
  double r = 0.0, g = 0.0;
};
AreaPair SegmentArea(const std::function<double(double)>& h, double l) {
  AreaPair area;
  const int steps = 4096;
  for (int i = 0; i < steps; ++i) {
    const double v = h(l + (i + 0.5) / steps) / steps;
    (v > 0 ? area.g : area.r) += std::fabs(v);
  }
  return area;
}

// The Z area SMAA reads for a pixel l pixels from a run's left end and r from its right end:
// AreaTex holds the revectorised line's areas at squared distances (texel (i, j) for distances
// i^2 and j^2, a line of i^2 + j^2 + 1 pixels from +0.5 to -0.5) and the shader samples it
// bilinearly at (sqrt(l), sqrt(r)) (aa-facts §1.4, §1.6).
AreaPair ZArea(int l, int r) {
  const auto exact = [](int i, int j) {
    const double length = i * i + j * j + 1;
    return SegmentArea([length](double t) { return 0.5 - t / length; }, i * i);
  };
  const double u = std::sqrt(l), v = std::sqrt(r);
  const int i = static_cast<int>(u), j = static_cast<int>(v);
  const double fu = u - i, fv = v - j;
  AreaPair area;
  for (const auto& [di, dj, weight] : {std::tuple{0, 0, (1 - fu) * (1 - fv)}, std::tuple{1, 0, fu * (1 - fv)},
                                       std::tuple{0, 1, (1 - fu) * fv}, std::tuple{1, 1, fu * fv}}) {
    if (weight == 0.0) continue;
    const AreaPair corner = exact(i + di, j + dj);
    area.r += weight * corner.r;
    area.g += weight * corner.g;
  }
  return area;
}

// A staircase of slope 1/n: bright below row y0 + floor(x / n). Each run of n top edges has a
// crossing edge in the row above at its left end and in its own row at its right end (a Z).
// Orthogonal weights only: diagonals and corner rounding off (they are tested elsewhere).
// Tolerance 3/255: AreaTex truncates to 1/255, the shader's fixed-point bilinear weighs in
// 1/256 steps, and the weights round to 1/255.
TEST(SmaaWeights, StairStepsMatchTheAnalyticAreas) {
  for (int n = 1; n <= 16; ++n) {
    const int width = 4 * n + 8, height = 12, y0 = 4;
    const auto image = GreyImage(width, height, [&](int x, int y) { return y >= y0 + x / n ? kSmaaBright : kSmaaDark; });
    const SmaaRun run = RunSmaa("smaa:max_search_steps_diag=0,corner_rounding=100", image);
    for (int k = 1; k <= 2; ++k) {  // runs away from the image borders
      for (int l = 0; l < n; ++l) {
        const AreaPair expected = ZArea(l, n - 1 - l);
        const int x = k * n + l, y = y0 + k;
        EXPECT_NEAR(run.At("weights", x, y, 0), expected.r, 3.0 / 255) << "slope 1/" << n << " pixel " << l;
        EXPECT_NEAR(run.At("weights", x, y, 1), expected.g, 3.0 / 255) << "slope 1/" << n << " pixel " << l;
      }
    }
  }
}

// A one-pixel line across the whole image is two straight edges without ends: nothing to blend.
TEST(SmaaWeights, OnePixelLinesAcrossTheImageAreLeftAlone) {
  const auto horizontal = GreyImage(64, 16, [](int, int y) { return y == 7 ? kSmaaBright : kSmaaDark; });
  const auto vertical = GreyImage(16, 64, [](int x, int) { return x == 7 ? kSmaaBright : kSmaaDark; });
  for (const auto* image : {&horizontal, &vertical}) {
    const SmaaRun run = RunSmaa("smaa", *image);
    EXPECT_GT(run.output.workItems, 0u);
    for (int y = 0; y < image->Height(); ++y) {
      for (int x = 0; x < image->Width(); ++x) {
        for (int c = 0; c < 4; ++c) ASSERT_EQ(run.At("weights", x, y, c), 0.0f) << x << "," << y;
      }
    }
  }
}

// A U: a one-row bump of m pixels on a long horizontal edge. Its top run is crossed in its own row
// at both ends (code 3 and 3, aa-facts §1.4), so the revectorised line dips below the run at both
// ends: only R (the pixel blends towards the one above), mirror-symmetric about the bump's middle,
// largest at the ends.
TEST(SmaaWeights, AUShapeBlendsSymmetricallyMostAtItsEnds) {
  for (const int m : {3, 4, 7, 10}) {
    const int a = 20, y0 = 8;
    const auto image = GreyImage(64, 16, [&](int x, int y) {
      return y >= y0 || (y == y0 - 1 && x >= a && x < a + m) ? kSmaaBright : kSmaaDark;
    });
    const SmaaRun run = RunSmaa("smaa:max_search_steps_diag=0,corner_rounding=100", image);
    for (int l = 0; l < m; ++l) {
      const int x = a + l, mirrored = a + m - 1 - l;
      EXPECT_EQ(run.At("weights", x, y0 - 1, 1), 0.0f) << "m " << m << " pixel " << l;
      EXPECT_EQ(run.At("weights", x, y0 - 1, 0), run.At("weights", mirrored, y0 - 1, 0)) << "m " << m << " pixel " << l;
      if (l > 0 && l <= (m - 1) / 2) {
        EXPECT_LE(run.At("weights", x, y0 - 1, 0), run.At("weights", x - 1, y0 - 1, 0)) << "m " << m << " pixel " << l;
      }
    }
    EXPECT_GT(run.At("weights", a, y0 - 1, 0), 0.0f) << "m " << m;
  }
}

// ---- Symmetry ----

// Transposing the image transposes the edges (R <-> G) and the weights (RG <-> BA) and the output.
// Diagonal searches start only from top edges in the reference, so they are off here.
TEST(SmaaSymmetry, TransposingTheImageTransposesEdgesWeightsAndOutput) {
  const int n = 48;
  const Codes shapes = [](int x, int y) {
    const bool disc = (x - 20) * (x - 20) + (y - 26) * (y - 26) < 140;
    const bool bar = x > 30 && x < 44 && y > 5 && y < 9 + x / 8;
    return disc ? kSmaaBright : bar ? 150 : kSmaaDark;
  };
  const auto image = GreyImage(n, n, shapes);
  const auto transposed = GreyImage(n, n, [&](int x, int y) { return shapes(y, x); });
  for (const char* spec : {"smaa:max_search_steps_diag=0", "smaa:preset=medium", "smaa-colour:preset=low"}) {
    const SmaaRun a = RunSmaa(spec, image), b = RunSmaa(spec, transposed);
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        ASSERT_EQ(a.At("edges", x, y, 0), b.At("edges", y, x, 1)) << spec << " " << x << "," << y;
        ASSERT_EQ(a.At("edges", x, y, 1), b.At("edges", y, x, 0)) << spec << " " << x << "," << y;
        for (int c = 0; c < 4; ++c) {
          ASSERT_EQ(a.At("weights", x, y, c), b.At("weights", y, x, (c + 2) % 4)) << spec << " " << x << "," << y;
        }
        ASSERT_EQ(OutputCode(a, x, y), OutputCode(b, y, x)) << spec << " " << x << "," << y;
      }
    }
  }
}

// ---- The report ----

// The report lists a dispatch's bindings in the order its kernel declares them (sim/dispatch.h),
// under every compiler: the blend reads the colour, then the weights. Declared as arguments of
// one parenthesised call, GCC registered them the other way round and clang this way.
TEST(SmaaReport, TheBlendListsItsBindingsInDeclarationOrder) {
  const auto image = GreyImage(16, 8, [](int x, int) { return x < 8 ? kSmaaDark : kSmaaBright; });
  const SmaaRun run = RunSmaa("smaa", image);
  const auto blend = std::find_if(run.reports.begin(), run.reports.end(),
                                  [](const sim::DispatchReport& r) { return r.name == "smaa/neighbourhood-blending"; });
  ASSERT_NE(blend, run.reports.end());
  std::vector<std::string> names;
  for (const sim::ResourceTraffic& resource : blend->resources) names.push_back(resource.name);
  EXPECT_EQ(names, (std::vector<std::string>{"colour-srgb8", "smaa/weights", "smaa/output"}));
}

// A frame given without its 8-bit sRGB target is refused, not silently stored by the pass.
TEST(SmaaInputs, TheEightBitFrameMustBeGiven) {
  const auto image = GreyImage(16, 8, [](int x, int) { return x < 8 ? kSmaaDark : kSmaaBright; });
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  EXPECT_THROW(ResolvePass("smaa").Make()->Run(machine, FrameInputs{.colour = &image}, Strategy::DeferredQueue),
               std::logic_error);
  const sim::Texture2D<glm::vec4> small = Srgb8ColourTarget("small", GreyImage(8, 8, [](int, int) { return kSmaaDark; }));
  EXPECT_THROW(ResolvePass("smaa").Make()->Run(machine, FrameInputs{.colour = &image, .colourSrgb8 = &small},
                                               Strategy::DeferredQueue),
               std::logic_error);
}

// ---- Presets ----

// A long edge with one step: every preset searches further than the one before it (steps of
// 2 px, aa-facts §1.2), and the search stops at the ends it can reach.
TEST(SmaaPresets, EachPresetSearchesFurther) {
  const auto image = GreyImage(256, 16, [](int x, int y) { return y < (x < 128 ? 8 : 9) ? kSmaaDark : kSmaaBright; });
  std::uint64_t previous = 0;
  for (const char* preset : {"low", "medium", "high", "ultra"}) {
    const SmaaRun run = RunSmaa(std::string("smaa:preset=") + preset, image);
    const std::uint64_t steps = run.Counter("smaa/blending-weights", "search_steps");
    EXPECT_GT(steps, previous) << preset;
    previous = steps;
  }
}

// ---- Quality ----

// Exact coverage of a pixel by a shape, by 64x64 supersampling.
double Coverage(int x, int y, const std::function<bool(double, double)>& inside) {
  int hits = 0;
  for (int j = 0; j < 64; ++j) {
    for (int i = 0; i < 64; ++i) hits += inside(x + (i + 0.5) / 64, y + (j + 0.5) / 64);
  }
  return hits / 4096.0;
}

// The L1 error against the true coverage of a white shape on black, before and after SMAA.
std::pair<double, double> ErrorBeforeAndAfter(int width, int height, const std::function<bool(double, double)>& inside) {
  const auto image = GreyImage(width, height, [&](int x, int y) { return inside(x + 0.5, y + 0.5) ? 255 : 0; });
  const SmaaRun run = RunSmaa("smaa", image);
  double before = 0.0, after = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double truth = Coverage(x, y, inside);
      before += std::fabs(static_cast<double>(image.At(x, y).r) - truth);
      after += std::fabs(static_cast<double>(run.output.colour.At(x, y).r) - truth);
    }
  }
  return {before, after};
}

// Straight edges of shallow slope are what SMAA's revectorisation reconstructs: its line through
// the middles of the steps stays within half a pixel (horizontally) of the true line, so the
// blended pixels approach the true coverage, and the closer the shallower the slope (the half
// pixel is a smaller height).
TEST(SmaaQuality, ShallowStraightEdgesComeCloseToTheirTrueCoverage) {
  double previous = 1.0;
  for (const double slope : {1.0 / 3, 1.0 / 5, 1.0 / 8, 1.0 / 13}) {
    const auto [before, after] =
        ErrorBeforeAndAfter(96, 48, [slope](double x, double y) { return y > 8.37 + slope * x; });
    const double ratio = after / before;
    EXPECT_LT(ratio, previous) << "slope " << slope << ": aliased " << before << ", SMAA " << after;
    previous = ratio;
  }
  EXPECT_LT(previous, 0.3);
}

// A disc mixes every pattern (L, Z and the U at its poles, which SMAA rounds off as if concave):
// SMAA still lowers the error, by less.
TEST(SmaaQuality, SmaaLowersTheErrorOfAnAliasedDisc) {
  const auto [before, after] = ErrorBeforeAndAfter(64, 64, [](double x, double y) {
    return (x - 31.3) * (x - 31.3) + (y - 32.6) * (y - 32.6) < 21.7 * 21.7;
  });
  EXPECT_LT(after, before) << "aliased " << before << ", SMAA " << after;
}

}  // namespace
}  // namespace passes
