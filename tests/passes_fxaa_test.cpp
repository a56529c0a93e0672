// FXAA 3.11 PC quality on synthetic grey images whose results follow by hand from
// FxaaPixelShader's formulas (Fxaa3_11.h), independently of the kernels. On a grey image the
// pre-pass luma is the grey code itself, so every luma below is code / 255. Bilinear fetches of
// the 8-bit texture are the machine's fixed point (aa-facts §1.9): a sample between two texels
// with weight w in 1/256 reads a + ((w (b - a) + 128) >> 8) on the codes.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "passes/compare.h"
#include "passes/fxaa/fxaa.h"
#include "passes/fxaa/fxaa_kernels.h"
#include "passes/registry.h"
#include "passes_test_util.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"

namespace passes {
namespace {

using testing::Codes;
using testing::GreyImage;

struct FxaaRun {
  PassOutput output;
  std::vector<sim::DispatchReport> reports;

  // The 8-bit gamma code the pass stored (its output decodes them; decode-then-encode is lossless).
  int Code(int x, int y, int channel = 0) const {
    return sim::FloatToSrgb8(output.colour.At(x, y)[channel]);
  }
  float Span(int x, int y, int channel) const {
    for (const PassLayer& layer : output.layers) {
      if (layer.name != "span") continue;
      return layer.values.at((static_cast<std::size_t>(y) * static_cast<std::size_t>(layer.width) +
                              static_cast<std::size_t>(x)) * 4 + static_cast<std::size_t>(channel));
    }
    throw std::logic_error("no span layer");
  }
};

FxaaRun RunFxaa(const sim::Texture2D<glm::vec4>& image, const PassSettings& settings,
                Strategy strategy = Strategy::StencilCulled) {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const sim::Texture2D<glm::vec4> srgb8 = Srgb8ColourTarget("colour-srgb8", image);
  FxaaRun run{fxaa::Make(settings)->Run(machine, FrameInputs{.colour = &image, .colourSrgb8 = &srgb8}, strategy), {}};
  run.reports = machine.Reports();
  return run;
}

FxaaRun RunFxaa(const sim::Texture2D<glm::vec4>& image, std::string_view spec = "fxaa",
                Strategy strategy = Strategy::StencilCulled) {
  return RunFxaa(image, ResolvePass(spec).settings, strategy);
}

const fxaa::StepTable& StepTableFor(int preset) {
  const fxaa::StepTable* table = fxaa::FindStepTable(preset);
  if (table == nullptr) throw std::logic_error("no FXAA preset " + std::to_string(preset));
  return *table;
}

// ---- The presets ----

// FXAA_QUALITY__PS and P0.. of every FXAA_QUALITY__PRESET, restated from Fxaa3_11.h "FXAA QUALITY -
// PRESETS".
TEST(FxaaPresets, StepTablesAreTheHeaders) {
  const std::vector<std::pair<int, std::vector<float>>> header{
      {10, {1.5f, 3.0f, 12.0f}},
      {11, {1.0f, 1.5f, 3.0f, 12.0f}},
      {12, {1.0f, 1.5f, 2.0f, 4.0f, 12.0f}},
      {13, {1.0f, 1.5f, 2.0f, 2.0f, 4.0f, 12.0f}},
      {14, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
      {15, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
      {20, {1.5f, 2.0f, 8.0f}},
      {21, {1.0f, 1.5f, 2.0f, 8.0f}},
      {22, {1.0f, 1.5f, 2.0f, 2.0f, 8.0f}},
      {23, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 8.0f}},
      {24, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 3.0f, 8.0f}},
      {25, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {26, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {27, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {28, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {29, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {39, {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
  };
  ASSERT_EQ(fxaa::kStepTables.size(), header.size());
  for (const auto& [preset, steps] : header) {
    const fxaa::StepTable* table = fxaa::FindStepTable(preset);
    ASSERT_NE(table, nullptr) << preset;
    const std::span<const float> ours = table->Steps();
    EXPECT_EQ(std::vector<float>(ours.begin(), ours.end()), steps) << "preset " << preset;
  }
  EXPECT_EQ(fxaa::FindStepTable(16), nullptr);
}

TEST(FxaaPresets, EveryPresetIsRegisteredByNumberAndTheDefaultIsTwelve) {
  for (const fxaa::StepTable& table : fxaa::kStepTables) {
    const std::string number = std::to_string(table.preset);
    EXPECT_EQ(ResolvePass("fxaa:preset=" + number).settings.Get("quality_preset"), table.preset);
  }
  const PassSettings defaults = ResolvePass("fxaa").settings;
  EXPECT_EQ(defaults.Get("quality_preset"), 12);
  EXPECT_EQ(defaults.Get("subpix"), 0.75);
  EXPECT_EQ(defaults.Get("edge_threshold"), 0.166);
  EXPECT_EQ(defaults.Get("edge_threshold_min"), 0.0833);
  // A number between the header's presets is refused when the settings are read, before any run.
  try {
    ResolvePass("fxaa:quality_preset=16");
    ADD_FAILURE() << "quality_preset=16 accepted";
  } catch (const SettingsError& error) {
    EXPECT_NE(std::string(error.what()).find("quality_preset=16 is not one of {10, 11, 12, 13, 14, 15, 20,"),
              std::string::npos)
        << error.what();
  }
}

// ---- End-of-edge search on one-pixel lines of known length ----

// A one-pixel white line on black: each line pixel is a horizontal span (edgeHorz = 8 or 6 against
// edgeVert <= 2) whose pair is N (|gradientN| = |gradientS| = 1, ties go to N), so the search runs
// on the boundary half a pixel above the line with lumaNN / 2 = 0.5 and gradientScaled = 0.25. A
// sample there whose footprint is all line reads 128 (+0.002), one wholly past the end reads 0
// (-0.5: an end), and one straddling the end reads lerp_y(128, 0, lerp_x(128, 255, 0) = 128) = 64
// (-0.249, not an end). So the side's reach is the first fetched cumulative step c (all but the
// table's last) with floor(c) >= the distance to the first pixel past the end, else the table's
// full reach.
float ExpectedReach(const fxaa::StepTable& table, int distanceToEnd) {
  float reach = 0.0f;
  for (int k = 0; k < table.count; ++k) {
    reach += table.steps[static_cast<std::size_t>(k)];
    if (k < table.count - 1 && std::floor(reach) >= static_cast<float>(distanceToEnd)) return reach;
  }
  return reach;
}

// Line pixels from centre - (toN - 1) to centre + (toP - 1), along x (or y when `vertical`); at
// least two, or the horizontal tie of an isolated pixel decides the span.
sim::Texture2D<glm::vec4> LineImage(bool vertical, int centre, int toN, int toP) {
  constexpr int kLong = 96, kShort = 16, kRow = 8;
  const Codes line = [=](int along, int across) {
    return across == kRow && along > centre - toN && along < centre + toP ? 255 : 0;
  };
  return vertical ? GreyImage(kShort, kLong, [&](int x, int y) { return line(y, x); })
                  : GreyImage(kLong, kShort, [&](int x, int y) { return line(x, y); });
}

TEST(FxaaSearch, FindsBothEndsOfLinesAtTheDistancesTheStepTablesGive) {
  constexpr int kCentre = 48, kRow = 8;
  const std::vector<std::pair<int, int>> ends{{2, 1}, {1, 2}, {2, 3}, {3, 5}, {4, 8}, {6, 11}, {9, 14},
                                              {13, 17}, {19, 21}, {26, 30}, {40, 40}};
  for (const int preset : {10, 12, 20, 25, 29, 39}) {
    const fxaa::StepTable& table = StepTableFor(preset);
    const PassSettings settings = ResolvePass("fxaa:preset=" + std::to_string(preset)).settings;
    for (const bool vertical : {false, true}) {
      for (const auto& [toN, toP] : ends) {
        const FxaaRun run = RunFxaa(LineImage(vertical, kCentre, toN, toP), settings);
        const int x = vertical ? kRow : kCentre, y = vertical ? kCentre : kRow;
        const std::string where = "preset " + std::to_string(preset) + (vertical ? " vertical" : " horizontal") +
                                  " line, ends " + std::to_string(toN) + " and " + std::to_string(toP) + " px away";
        EXPECT_EQ(run.Span(x, y, 0), vertical ? 2.0f : 1.0f) << where;
        EXPECT_NEAR(run.Span(x, y, 1), ExpectedReach(table, toN), 1e-3) << where;
        EXPECT_NEAR(run.Span(x, y, 2), ExpectedReach(table, toP), 1e-3) << where;
      }
    }
  }
}

// The reach beyond which a line's end is never found: the sum of the table.
TEST(FxaaSearch, ALineLongerThanThePresetsReachEndsAtTheFullReach) {
  const fxaa::StepTable& table = StepTableFor(12);
  EXPECT_EQ(ExpectedReach(table, 40), 1.0f + 1.5f + 2.0f + 4.0f + 12.0f);
  const FxaaRun run = RunFxaa(LineImage(false, 48, 40, 40));
  EXPECT_NEAR(run.Span(48, 8, 1), 20.5f, 1e-3);
  EXPECT_NEAR(run.Span(48, 8, 2), 20.5f, 1e-3);
}

// ---- Golden images ----

// A vertical step, black (x < 8) | white, 16x16, preset 12. Only the two columns at the step pass
// the early exit (range 1 >= max(0.0833, 0.166)); every other pixel keeps its code. Both are
// vertical spans (edgeVert = 1 + 2 + 1 against edgeHorz = 0) whose searches never end (the step
// runs through the image and clamp addressing continues it; every sample reads 128/255 against
// lumaNN / 2 = 0.5), so pixelOffset = 0.5 - 20.5 / 41 = 0 and only the sub-pixel term blends:
// subpixA = 2 (N+S+W+E) + diagonals = 4 (x = 7) or 8 (x = 8), subpixC = |subpixA / 12 - lumaM| /
// range = 1/3, subpixH = 0.75 ((3 - 2/3) (1/9))^2 = 0.0504 px towards the other side. Column 7
// samples at x = 7.5504 px: s = round(7.5504 * 256) - 128 = 1805, weight 13: code
// 0 + ((13 * 255 + 128) >> 8) = 13. Column 8 at 8.4496 px: s = 2035, texel 7, weight 243: code
// (243 * 255 + 128) >> 8 = 242.
TEST(FxaaGolden, AStepEdgeBlendsItsTwoColumnsByTheSubPixelAmount) {
  const sim::Texture2D<glm::vec4> image = GreyImage(16, 16, [](int x, int) { return x < 8 ? 0 : 255; });
  for (const Strategy strategy : kAllStrategies) {
    const FxaaRun run = RunFxaa(image, "fxaa", strategy);
    EXPECT_EQ(run.output.workItems, 32u);
    for (int y = 0; y < 16; ++y) {
      for (int x = 0; x < 16; ++x) {
        const int expected = x == 7 ? 13 : x == 8 ? 242 : x < 8 ? 0 : 255;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(run.Code(x, y, c), expected) << x << ", " << y;
      }
    }
  }
}

// The step in all four orientations: FXAA is symmetric here (no tie decides anything, and the
// fixed-point lerp is mirror-symmetric: lerp(w, a, b) == lerp(256 - w, b, a)).
TEST(FxaaGolden, TheStepEdgeIsMirrorAndTransposeSymmetric) {
  const auto check = [](const Codes& code, const std::function<int(int, int)>& across, const std::string& what) {
    const FxaaRun run = RunFxaa(GreyImage(16, 16, code));
    for (int y = 0; y < 16; ++y) {
      for (int x = 0; x < 16; ++x) {
        const int a = across(x, y);  // 0..15 across the step, the step between 7 and 8
        const int dark = code(x, y) == 0;
        const int expected = a == 7 || a == 8 ? (dark ? 13 : 242) : code(x, y);
        ASSERT_EQ(run.Code(x, y), expected) << what << " at " << x << ", " << y;
      }
    }
  };
  check([](int x, int) { return x < 8 ? 0 : 255; }, [](int x, int) { return x; }, "black | white");
  check([](int x, int) { return x < 8 ? 255 : 0; }, [](int x, int) { return x; }, "white | black");
  check([](int, int y) { return y < 8 ? 0 : 255; }, [](int, int y) { return y; }, "black over white");
  check([](int, int y) { return y < 8 ? 255 : 0; }, [](int, int y) { return y; }, "white over black");
}

// An isolated white pixel at (8, 8) on black: subpixA = 0, subpixC = |0 - 1| / 1 = 1, subpixH =
// 0.75. Its span is horizontal (edgeHorz = edgeVert = 4, ties go horizontal), the pair N (ties go
// N), both searches end at the first sample (1 px, reads 0). lumaMM = 0.5 > 0 and the ends read
// -0.5, so goodSpan holds but pixelOffset = 0.5 - 1/2 = 0; the sub-pixel term moves the fetch 0.75
// px up: s = round(7.75 * 256) - 128 = 1856, weight 64 between row 7 (0) and row 8 (255): code 64.
// N and S neighbours: horizontal spans towards the pixel, subpixC = (2/12) / 1, subpixH =
// 0.75 ((3 - 1/3) / 36)^2 = 0.0041 px: weight 1 (N) or 255 (S): code 1. W and E neighbours tie
// edgeHorz = edgeVert = 2, take the horizontal span although their edge is vertical, and blend
// with the black above them: code 0. The result is not transpose-symmetric although the input is:
// the tie rule (edgeHorz >= edgeVert) decides.
TEST(FxaaGolden, AnIsolatedPixelKeepsAQuarterOfItsContrastAndTiesBreakHorizontally) {
  const sim::Texture2D<glm::vec4> image = GreyImage(16, 16, [](int x, int y) { return x == 8 && y == 8 ? 255 : 0; });
  const FxaaRun run = RunFxaa(image);
  EXPECT_EQ(run.Code(8, 8), 64);
  EXPECT_EQ(run.Span(8, 8, 0), 1.0f);
  EXPECT_NEAR(run.Span(8, 8, 3), -0.75f, 1e-6);  // towards N
  EXPECT_EQ(run.Code(8, 7), 1);
  EXPECT_EQ(run.Code(8, 9), 1);
  EXPECT_EQ(run.Code(7, 8), 0);
  EXPECT_EQ(run.Code(9, 8), 0);
  EXPECT_EQ(run.Span(7, 8, 0), 1.0f);  // a horizontal span on a vertical edge: the tie
  EXPECT_EQ(run.output.workItems, 5u);  // the diagonal neighbours see no contrast in their cross
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      if (std::abs(x - 8) + std::abs(y - 8) > 1) {
        ASSERT_EQ(run.Code(x, y), 0) << x << ", " << y;
      }
    }
  }
}

// A white one-pixel line through the image between rows of equal luma but different colour: grey
// 76 above and red (255, 0, 0) below (luma round(255 x 0.299) = 76 both). The line's pair is a tie
// and goes N: it blends with the row above by subpixH = 0.4115 px (subpixC = 2/3), s = round(8.0885
// x 256) - 128 = 1943, weight 151 from row 7 towards row 8: 76 + ((151 x 179 + 128) >> 8) = 182
// per channel. Flipped vertically (red above, grey below) it blends with the red above: (255,
// 150, 150), not the mirror of (182, 182, 182): FXAA is not mirror-symmetric where pairN ties.
TEST(FxaaGolden, ATieBetweenEqualLumaNeighboursBlendsTowardsTheNorth) {
  const auto image = [](bool redAbove) {
    sim::Texture2D<glm::vec4> texture("input", 16, 16, 16);
    for (int y = 0; y < 16; ++y) {
      for (int x = 0; x < 16; ++x) {
        const bool above = y < 8;
        const glm::vec3 codes = y == 8 ? glm::vec3(255.0f)
                                : (above == redAbove) ? glm::vec3(255.0f, 0.0f, 0.0f)
                                                      : glm::vec3(76.0f);
        texture.At(x, y) = glm::vec4(sim::Srgb8ToFloat(static_cast<std::uint8_t>(codes.r)),
                                     sim::Srgb8ToFloat(static_cast<std::uint8_t>(codes.g)),
                                     sim::Srgb8ToFloat(static_cast<std::uint8_t>(codes.b)), 1.0f);
      }
    }
    return texture;
  };
  const FxaaRun greyAbove = RunFxaa(image(false));
  const FxaaRun redAbove = RunFxaa(image(true));
  for (const int x : {0, 8, 15}) {
    EXPECT_EQ(greyAbove.Code(x, 8, 0), 182);
    EXPECT_EQ(greyAbove.Code(x, 8, 1), 182);
    EXPECT_EQ(greyAbove.Code(x, 8, 2), 182);
    EXPECT_EQ(redAbove.Code(x, 8, 0), 255);
    EXPECT_EQ(redAbove.Code(x, 8, 1), 150);
    EXPECT_EQ(redAbove.Code(x, 8, 2), 150);
  }
}

// ---- Thresholds ----

// range < max(edge_threshold_min, rangeMax x edge_threshold) exits: a range exactly at the clamped
// threshold joins the work set, the next float above it does not. A step 0 | 16: range = rangeMax
// = 16/255 (as the shader computes it, 16 x (1/255)); rangeMax x 0.063 is far below, so the
// minimum decides.
TEST(FxaaThresholds, ARangeExactlyAtTheMinimumJoinsTheWorkSet) {
  const sim::Texture2D<glm::vec4> image = GreyImage(16, 8, [](int x, int) { return x < 8 ? 0 : 16; });
  const float range = sim::Unorm8ToFloat(16) - sim::Unorm8ToFloat(0);
  PassSettings settings = ResolvePass("fxaa:edge_threshold=0.063").settings;
  settings.Set("edge_threshold_min", static_cast<double>(range));
  EXPECT_EQ(RunFxaa(image, settings).output.workItems, 16u);
  settings.Set("edge_threshold_min", static_cast<double>(std::nextafter(range, 1.0f)));
  EXPECT_EQ(RunFxaa(image, settings).output.workItems, 0u);
}

// The relative threshold: a step 200 | 255 has range 55/255 and rangeMax 1 (255 x (1/255) rounds
// to 1 or just below; the threshold is searched so that rangeMax x t == range in float32).
TEST(FxaaThresholds, ARangeExactlyAtTheScaledMaximumJoinsTheWorkSet) {
  const sim::Texture2D<glm::vec4> image = GreyImage(16, 8, [](int x, int) { return x < 8 ? 200 : 255; });
  const float rangeMax = sim::Unorm8ToFloat(255), range = rangeMax - sim::Unorm8ToFloat(200);
  float atRange = range / rangeMax;
  while (rangeMax * atRange > range) atRange = std::nextafter(atRange, 0.0f);
  while (rangeMax * atRange < range) atRange = std::nextafter(atRange, 1.0f);
  ASSERT_EQ(rangeMax * atRange, range);
  float above = atRange;
  while (rangeMax * above <= range) above = std::nextafter(above, 1.0f);
  PassSettings settings = ResolvePass("fxaa").settings;
  settings.Set("edge_threshold", static_cast<double>(atRange));
  EXPECT_EQ(RunFxaa(image, settings).output.workItems, 16u);
  settings.Set("edge_threshold", static_cast<double>(above));
  EXPECT_EQ(RunFxaa(image, settings).output.workItems, 0u);
}

// ---- Worst case ----

// A one-pixel checkerboard: every pixel's cross has range 1, so every pixel is in the work set and
// a full-size queue holds them all. Interior pixels: horizontal spans (edgeHorz = edgeVert = 8),
// pair N, every search sample reads 128 (never an end), subpixC = 2/3, subpixH = 0.4115 px up:
// s = round((y + 0.0885) x 256) - 128, weight 151 from row y - 1: white -> (151 x 255 + 128) >> 8 =
// 150, black -> 255 - 150 = 105.
TEST(FxaaWorstCase, ACheckerboardPutsEveryPixelInTheWorkSetAndLosesNone) {
  constexpr int kSide = 24;
  const sim::Texture2D<glm::vec4> image = GreyImage(kSide, kSide, [](int x, int y) { return (x + y) % 2 ? 0 : 255; });
  std::optional<FxaaRun> first;
  for (const Strategy strategy : kAllStrategies) {
    const FxaaRun run = RunFxaa(image, "fxaa", strategy);
    EXPECT_EQ(run.output.workItems, static_cast<std::uint64_t>(kSide * kSide)) << StrategyName(strategy);
    for (int y = 0; y < kSide; ++y) {
      for (int x = 0; x < kSide; ++x) {
        ASSERT_NE(run.Span(x, y, 0), 0.0f) << x << ", " << y;
        if (x == 0 || y == 0 || x == kSide - 1 || y == kSide - 1) continue;
        ASSERT_EQ(run.Code(x, y), (x + y) % 2 ? 105 : 150) << x << ", " << y;
      }
    }
    for (const sim::DispatchReport& report : run.reports) {
      for (const sim::ResourceTraffic& traffic : report.resources) EXPECT_EQ(traffic.storesDroppedOob, 0u) << report.name;
    }
    if (first) {
      EXPECT_TRUE(CompareOutputs(first->output, run.output).Identical());
    } else {
      first = run;
    }
  }
}

// ---- Against the original shader ----

// A staircase of 5-pixel steps, grey 40 below / 200 above the edge (30x12): the codes FXAA changed,
// as the FXAA_PC path of Fxaa3_11.h computed them on Mesa llvmpipe (GL 4.5 core, FXAA_GLSL_130,
// FXAA_GATHER4_ALPHA 0, the header's luma pre-pass example into an RGBA8 texture; docs/fxaa.md
// "Against the original"). Every other pixel keeps its code. Presets 12 (dithered steps: the
// half-pixel samples read 8-bit lerps) and 39 (unit steps first) end the searches at different
// samples, so the blends along each step differ.
struct ChangedCode {
  int x, y, code;
};
TEST(FxaaReference, AStaircaseGivesTheOriginalShadersCodesOnLlvmpipe) {
  const Codes stairs = [](int x, int y) { return y >= 3 + x / 5 ? 200 : 40; };
  const sim::Texture2D<glm::vec4> image = GreyImage(30, 12, stairs);
  const std::vector<std::pair<int, std::vector<ChangedCode>>> reference{
      {12, {
      {0, 2, 48}, {1, 2, 48}, {2, 2, 48}, {3, 2, 48}, {4, 2, 43}, {0, 3, 149}, {1, 3, 149}, {2, 3, 138},
      {3, 3, 138}, {4, 3, 128}, {5, 3, 91}, {6, 3, 63}, {7, 3, 48}, {8, 3, 48}, {9, 3, 43}, {5, 4, 197},
      {6, 4, 192}, {7, 4, 177}, {8, 4, 177}, {9, 4, 137}, {10, 4, 91}, {11, 4, 63}, {12, 4, 48}, {13, 4, 48},
      {14, 4, 43}, {10, 5, 197}, {11, 5, 192}, {12, 5, 177}, {13, 5, 177}, {14, 5, 137}, {15, 5, 91},
      {16, 5, 63}, {17, 5, 48}, {18, 5, 48}, {19, 5, 43}, {15, 6, 197}, {16, 6, 192}, {17, 6, 177},
      {18, 6, 177}, {19, 6, 137}, {20, 6, 91}, {21, 6, 63}, {22, 6, 48}, {23, 6, 48}, {24, 6, 43},
      {20, 7, 197}, {21, 7, 192}, {22, 7, 177}, {23, 7, 177}, {24, 7, 137}, {25, 7, 113}, {26, 7, 103},
      {27, 7, 91}, {28, 7, 91}, {29, 7, 73}, {25, 8, 197}, {26, 8, 192}, {27, 8, 192}, {28, 8, 192},
      {29, 8, 192}}},
      {39, {
      {0, 2, 48}, {1, 2, 48}, {2, 2, 48}, {3, 2, 48}, {4, 2, 43}, {0, 3, 146}, {1, 3, 141}, {2, 3, 136},
      {3, 3, 131}, {4, 3, 126}, {5, 3, 93}, {6, 3, 67}, {7, 3, 48}, {8, 3, 48}, {9, 3, 43}, {5, 4, 197},
      {6, 4, 192}, {7, 4, 192}, {8, 4, 173}, {9, 4, 147}, {10, 4, 93}, {11, 4, 67}, {12, 4, 48}, {13, 4, 48},
      {14, 4, 43}, {10, 5, 197}, {11, 5, 192}, {12, 5, 192}, {13, 5, 173}, {14, 5, 147}, {15, 5, 93},
      {16, 5, 67}, {17, 5, 48}, {18, 5, 48}, {19, 5, 43}, {15, 6, 197}, {16, 6, 192}, {17, 6, 192},
      {18, 6, 173}, {19, 6, 147}, {20, 6, 93}, {21, 6, 67}, {22, 6, 48}, {23, 6, 48}, {24, 6, 43},
      {20, 7, 197}, {21, 7, 192}, {22, 7, 192}, {23, 7, 173}, {24, 7, 147}, {25, 7, 114}, {26, 7, 109},
      {27, 7, 104}, {28, 7, 99}, {29, 7, 94}, {25, 8, 197}, {26, 8, 192}, {27, 8, 192}, {28, 8, 192},
      {29, 8, 192}}},
  };
  for (const auto& [preset, changed] : reference) {
    const FxaaRun run = RunFxaa(image, "fxaa:preset=" + std::to_string(preset));
    std::vector<int> expected(30 * 12);
    for (int y = 0; y < 12; ++y) {
      for (int x = 0; x < 30; ++x) expected[static_cast<std::size_t>(y * 30 + x)] = stairs(x, y);
    }
    for (const ChangedCode& c : changed) expected[static_cast<std::size_t>(c.y * 30 + c.x)] = c.code;
    for (int y = 0; y < 12; ++y) {
      for (int x = 0; x < 30; ++x) {
        for (int channel = 0; channel < 3; ++channel) {
          ASSERT_EQ(run.Code(x, y, channel), expected[static_cast<std::size_t>(y * 30 + x)])
              << "preset " << preset << " at " << x << ", " << y;
        }
      }
    }
  }
}

}  // namespace
}  // namespace passes
