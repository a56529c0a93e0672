// Sample patterns against the tables of hw-facts §4, typed here independently of
// raster/sample_pattern.cpp, plus the FLIPQUAD tiling, the Halton values, JSON patterns and every
// error path.

#include "raster/sample_pattern.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "raster/raster_error.h"

namespace raster {
namespace {

using Table = std::vector<SampleOffset>;

// reference/hw-facts.md §4.1, offsets in 1/16 px.
const std::map<int, Table> kHwStandard = {
    {1, {{0, 0}}},
    {2, {{4, 4}, {-4, -4}}},
    {4, {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}}},
    {8, {{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}}},
    {16, {{1, 1}, {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5}, {5, 3}, {3, -5}, {-2, 6},
          {0, -7}, {-4, -6}, {-6, 4}, {-8, 0}, {7, -4}, {6, 7}, {-7, -8}}},
};

// reference/hw-facts.md §4.3 (radeonsi EQAA order).
const std::map<int, Table> kHwEqaa = {
    {2, {{-4, -4}, {4, 4}}},
    {4, {{-2, -6}, {2, 6}, {-6, 2}, {6, -2}}},
    {8, {{-3, -5}, {5, 1}, {-1, 3}, {7, -7}, {-7, -1}, {3, 7}, {-5, 5}, {1, -3}}},
    {16, {{-5, -2}, {5, 3}, {-2, 6}, {3, -5}, {-4, -6}, {1, 1}, {-6, 4}, {7, -4}, {-1, -3},
          {6, 7}, {-3, 2}, {0, -7}, {-7, -7}, {2, 5}, {-7, 0}, {4, -1}}},
};

Table PixelOffsets(const SamplePattern& pattern, int pixel) {
  Table offsets;
  for (int s = 0; s < pattern.Count(); ++s) offsets.push_back(pattern.Offset(pixel, s));
  return offsets;
}

std::set<std::pair<int, int>> AsSet(const Table& table) {
  std::set<std::pair<int, int>> set;
  for (const SampleOffset o : table) set.insert({o.x, o.y});
  return set;
}

// The PA_SC_CENTROID_PRIORITY_0/1 pair as one 64-bit value: nibble k = entry k (hw-facts §4.2).
std::uint64_t PackedPriority(const SamplePattern& pattern) {
  std::uint64_t packed = 0;
  for (int k = 0; k < kMaxCoverageSamples; ++k) {
    packed |= std::uint64_t{pattern.CentroidPriority()[k]} << (4 * k);
  }
  return packed;
}

// The RasterError message of `action`, or a test failure when it does not throw one.
std::string PatternErrorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const RasterError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a RasterError";
  return {};
}

void ExpectErrorMentions(const std::function<void()>& action,
                         const std::vector<std::string>& parts) {
  const std::string message = PatternErrorOf(action);
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
}

void ExpectUniform(const SamplePattern& pattern, const Table& expected) {
  ASSERT_EQ(pattern.Count(), std::ssize(expected));
  EXPECT_TRUE(pattern.SameInAllPixels());
  for (int p = 0; p < kQuadPixels; ++p) EXPECT_EQ(PixelOffsets(pattern, p), expected) << p;
}

int UniqueColumns(const Table& table) {
  std::set<int> xs;
  for (const SampleOffset o : table) xs.insert(o.x);
  return static_cast<int>(xs.size());
}

int UniqueRows(const Table& table) {
  std::set<int> ys;
  for (const SampleOffset o : table) ys.insert(o.y);
  return static_cast<int>(ys.size());
}

// ---- Hardware tables --------------------------------------------------------------------------

TEST(SamplePattern, StandardTablesMatchHwFacts) {
  for (const auto& [count, table] : kHwStandard) {
    ExpectUniform(MakeBuiltinPattern("standard", count), table);
  }
}

TEST(SamplePattern, EqaaTablesMatchHwFacts) {
  for (const auto& [count, table] : kHwEqaa) {
    ExpectUniform(MakeBuiltinPattern("eqaa", count), table);
  }
  ExpectUniform(MakeBuiltinPattern("eqaa", 1), {{0, 0}});
}

TEST(SamplePattern, EqaaReordersStandardPositions) {
  for (const int count : {2, 4, 8}) {
    EXPECT_EQ(AsSet(kHwEqaa.at(count)), AsSet(kHwStandard.at(count))) << count;
  }
  // hw-facts §4.3's 16x table is not a permutation of §4.1's: radeonsi moved the two -8
  // coordinates, (-8, 0) and (-7, -8), to -7 (hw-facts §4.2). With that move it is one.
  const auto standard16 = AsSet(kHwStandard.at(16));
  const auto eqaa16 = AsSet(kHwEqaa.at(16));
  std::set<std::pair<int, int>> onlyStandard;
  std::set<std::pair<int, int>> onlyEqaa;
  std::ranges::set_difference(standard16, eqaa16, std::inserter(onlyStandard, onlyStandard.end()));
  std::ranges::set_difference(eqaa16, standard16, std::inserter(onlyEqaa, onlyEqaa.end()));
  EXPECT_EQ(onlyStandard, (std::set<std::pair<int, int>>{{-8, 0}, {-7, -8}}));
  EXPECT_EQ(onlyEqaa, (std::set<std::pair<int, int>>{{-7, 0}, {-7, -7}}));
  std::set<std::pair<int, int>> moved;
  for (const auto& [x, y] : standard16) moved.insert({std::max(x, -7), std::max(y, -7)});
  EXPECT_EQ(moved, eqaa16);
}

// ---- Centroid priority and MAX_SAMPLE_DIST (hw-facts §4.2) -----------------------------------

TEST(SamplePattern, CentroidPriorityMatchesQuotedRegisterValues) {
  // radeonsi 2x and 4x: every sample is equally far from the centre, so index order wins, in
  // the standard and the EQAA order alike.
  EXPECT_EQ(PackedPriority(MakeBuiltinPattern("standard", 2)), 0x1010101010101010u);
  EXPECT_EQ(PackedPriority(MakeBuiltinPattern("eqaa", 2)), 0x1010101010101010u);
  EXPECT_EQ(PackedPriority(MakeBuiltinPattern("standard", 4)), 0x3210321032103210u);
  EXPECT_EQ(PackedPriority(MakeBuiltinPattern("eqaa", 4)), 0x3210321032103210u);
  // RADV's 8x default, "0x76543210 repeated": the standard 8x table is already sorted.
  EXPECT_EQ(PackedPriority(MakeBuiltinPattern("standard", 8)), 0x7654321076543210u);
  EXPECT_EQ(PackedPriority(MakeBuiltinPattern("standard", 1)), 0u);
}

TEST(SamplePattern, CentroidPriorityOfEqaa8DiffersFromRadeonsiOnlyInTies) {
  // Distances of the EQAA 8x samples: 2 and 7 tie at 10, 4 and 6 at 50. The PAL/RADV rule
  // (earlier index first) gives 2,7,1,0,4,6,5,3.
  const SamplePattern eqaa = MakeBuiltinPattern("eqaa", 8);
  EXPECT_EQ(PackedPriority(eqaa), 0x3564017235640172u);
  // radeonsi's hand-written 0x3546012735460127 (hw-facts §4.2) is the standard 8x order (whose
  // ties fall the other way) renamed to EQAA indices, not our rule applied to the EQAA table.
  const SamplePattern standard = MakeBuiltinPattern("standard", 8);
  const Table eqaaTable = PixelOffsets(eqaa, 0);
  std::uint64_t renamed = 0;
  for (int k = 0; k < kMaxCoverageSamples; ++k) {
    const SampleOffset position = standard.Offset(0, standard.CentroidPriority()[k]);
    const auto eqaaIndex = std::ranges::find(eqaaTable, position) - eqaaTable.begin();
    renamed |= static_cast<std::uint64_t>(eqaaIndex) << (4 * k);
  }
  EXPECT_EQ(renamed, 0x3546012735460127u);
}

TEST(SamplePattern, CentroidPriorityOfEqaa16FollowsTheMovedPositions) {
  // radeonsi's centroid_priority_16x = 0xc97e64b231d0fa85 (SI-MSAA; not quoted in hw-facts) was
  // computed for the DX positions: sample 14 at (-8, 0) is farther out than samples 4 and 6.
  // Our table has (-7, 0) there (distance 49, ties sample 11), hence a different value.
  EXPECT_EQ(PackedPriority(MakeBuiltinPattern("eqaa", 16)), 0xc9764eb231d0fa85u);
  Table dxPositions = kHwEqaa.at(16);
  dxPositions[12] = {-7, -8};
  dxPositions[14] = {-8, 0};
  EXPECT_EQ(PackedPriority(SamplePattern::CreateUniform("eqaa-dx", dxPositions)),
            0xc97e64b231d0fa85u);
}

TEST(SamplePattern, CentroidPriorityUsesTheTopLeftPixelAndKeepsTiesStable) {
  const Table near = {{1, 0}, {7, 7}, {0, -1}, {-1, 0}};
  const Table far = {{7, 7}, {6, 6}, {5, 5}, {1, 1}};
  const SamplePattern pattern = SamplePattern::Create("mixed", 4, {near, far, far, far});
  const std::array<std::uint8_t, kMaxCoverageSamples> expected = {0, 2, 3, 1, 0, 2, 3, 1,
                                                                  0, 2, 3, 1, 0, 2, 3, 1};
  EXPECT_EQ(pattern.CentroidPriority(), expected);
  EXPECT_FALSE(pattern.SameInAllPixels());
}

TEST(SamplePattern, MaxSampleDistance) {
  // hw-facts §4.2 defaults: 0 / 4 / 6 / 7 for 1/2/4/8x; 16x is 8 with the DX -8 positions and
  // 7 with radeonsi's moved ones.
  const std::map<int, int> standard = {{1, 0}, {2, 4}, {4, 6}, {8, 7}, {16, 8}};
  for (const auto& [count, distance] : standard) {
    EXPECT_EQ(MakeBuiltinPattern("standard", count).MaxSampleDistance(), distance) << count;
  }
  EXPECT_EQ(MakeBuiltinPattern("eqaa", 16).MaxSampleDistance(), 7);
  // Every quad pixel counts, not just the top-left one.
  const Table small = {{1, -1}, {0, 2}};
  const SamplePattern pattern =
      SamplePattern::Create("one-far", 2, {small, small, small, {{1, -1}, {0, -8}}});
  EXPECT_EQ(pattern.MaxSampleDistance(), 8);
}

// ---- The other built-ins ----------------------------------------------------------------------

TEST(SamplePattern, CentreHasEverySampleAtTheCentre) {
  for (const int count : {1, 2, 4, 8, 16}) {
    ExpectUniform(MakeBuiltinPattern("centre", count), Table(static_cast<std::size_t>(count)));
  }
}

TEST(SamplePattern, RotatedGridCoversUniqueRowsAndColumns) {
  const SamplePattern rg2 = MakeBuiltinPattern("rotated-grid", 2);
  ExpectUniform(rg2, {{-4, 4}, {4, -4}});
  EXPECT_NE(PixelOffsets(rg2, 0), kHwStandard.at(2));
  const SamplePattern rg4 = MakeBuiltinPattern("rotated-grid", 4);
  ExpectUniform(rg4, {{-2, -6}, {6, -2}, {2, 6}, {-6, 2}});
  // Seed 001: 2xRG has 2 unique rows and columns, 4xRG has 4.
  EXPECT_EQ(UniqueRows(PixelOffsets(rg2, 0)), 2);
  EXPECT_EQ(UniqueColumns(PixelOffsets(rg2, 0)), 2);
  EXPECT_EQ(UniqueRows(PixelOffsets(rg4, 0)), 4);
  EXPECT_EQ(UniqueColumns(PixelOffsets(rg4, 0)), 4);
}

TEST(SamplePattern, QuincunxIsCentreAndTopLeftCorner) {
  ExpectUniform(MakeBuiltinPattern("quincunx", 2), {{0, 0}, {-8, -8}});
}

// FLIPQUAD in a unit pixel: (0, 1/3), (2/3, 0), (1, 2/3), (1/3, 1), mirrored (x -> 1 - x) in
// every other pixel of a checkerboard, each coordinate snapped to the nearest 1/16. Mirroring
// swaps the left and right edges, so each point is named by the edge it lands on.
struct FlipQuadPoints {
  SampleOffset left, top, right, bottom;  // absolute, in 1/16 px from the block's origin
};

FlipQuadPoints IdealFlipQuad(int px, int py) {
  const bool mirrored = (px + py) % 2 == 1;
  const auto snap = [](int pixel, double unit) {
    return pixel * 16 + static_cast<int>(std::lround(16.0 * unit));
  };
  FlipQuadPoints points;
  for (const auto& [ux, uy] : {std::pair{0.0, 1.0 / 3.0}, std::pair{2.0 / 3.0, 0.0},
                               std::pair{1.0, 2.0 / 3.0}, std::pair{1.0 / 3.0, 1.0}}) {
    const double x = mirrored ? 1.0 - ux : ux;
    const SampleOffset point{snap(px, x), snap(py, uy)};
    SampleOffset& edge = x == 0.0    ? points.left
                         : uy == 0.0 ? points.top
                         : x == 1.0  ? points.right
                                     : points.bottom;
    edge = point;
  }
  return points;
}

SampleOffset Absolute(const SamplePattern& pattern, int px, int py, int sample) {
  const SampleOffset o = pattern.Offset(QuadPixelIndex(px, py), sample);
  return {px * 16 + 8 + o.x, py * 16 + 8 + o.y};
}

TEST(SamplePattern, FlipQuadTilesThePlane) {
  const SamplePattern pattern = MakeBuiltinPattern("flipquad", 2);
  EXPECT_FALSE(pattern.SameInAllPixels());
  for (int py = 0; py < 4; ++py) {
    for (int px = 0; px < 4; ++px) {
      const FlipQuadPoints ideal = IdealFlipQuad(px, py);
      // A pixel renders its left-edge (sample 0) and top-edge (sample 1) points ...
      EXPECT_EQ(Absolute(pattern, px, py, 0), ideal.left) << px << "," << py;
      EXPECT_EQ(Absolute(pattern, px, py, 1), ideal.top) << px << "," << py;
      // ... and borrows the other two from its right and bottom neighbours.
      EXPECT_EQ(ideal.right, Absolute(pattern, px + 1, py, 0)) << px << "," << py;
      EXPECT_EQ(ideal.bottom, Absolute(pattern, px, py + 1, 1)) << px << "," << py;
      // Seed 001: the four points a pixel uses have 4 unique rows and 4 unique columns.
      const Table used = {ideal.left, ideal.top, ideal.right, ideal.bottom};
      EXPECT_EQ(UniqueRows(used), 4);
      EXPECT_EQ(UniqueColumns(used), 4);
    }
  }
}

// ---- Halton jitter (aa-facts §5) --------------------------------------------------------------

TEST(SamplePattern, HaltonFirstValues) {
  // Halton(2,3) at indices 1..8: (1/2, 1/3), (1/4, 2/3), (3/4, 1/9), (1/8, 4/9), (5/8, 7/9),
  // (3/8, 2/9), (7/8, 5/9), (1/16, 8/9); offset = floor(16 h) - 8.
  const Table expected = {{0, -3}, {-4, 2}, {4, -7}, {-6, -1}, {2, 4}, {-2, -5}, {6, 0}, {-7, 6}};
  const std::vector<SamplePattern> sequence = HaltonJitterSequence(8);
  ASSERT_EQ(sequence.size(), expected.size());
  for (int k = 0; k < 8; ++k) {
    const std::string name = "halton:" + std::to_string(k);
    ExpectUniform(sequence[k], {expected[k]});
    EXPECT_EQ(sequence[k].Name(), name);
    EXPECT_EQ(MakeBuiltinPattern(name, 1), sequence[k]);
  }
  EXPECT_TRUE(HaltonJitterSequence(0).empty());
}

TEST(SamplePattern, HaltonMatchesAFloatingPointReference) {
  const auto radicalInverse = [](std::int64_t index, int base) {
    double h = 0.0;
    for (double scale = 1.0 / base; index > 0; index /= base, scale /= base) {
      h += (index % base) * scale;
    }
    return static_cast<int>(std::floor(h * 16.0)) - 8;
  };
  const std::vector<SamplePattern> sequence = HaltonJitterSequence(256);
  for (int k = 0; k < 256; ++k) {
    EXPECT_EQ(sequence[k].Offset(0, 0),
              (SampleOffset{radicalInverse(k + 1, 2), radicalInverse(k + 1, 3)}))
        << k;
  }
  // The largest K: Halton index 2^31 must not overflow.
  const std::int64_t lastIndex = std::int64_t{1} << 31;
  EXPECT_EQ(MakeBuiltinPattern("halton:2147483647", 1).Offset(0, 0),
            (SampleOffset{radicalInverse(lastIndex, 2), radicalInverse(lastIndex, 3)}));
}

// ---- Names and errors -------------------------------------------------------------------------

TEST(SamplePattern, BuiltinNames) {
  EXPECT_EQ(BuiltinPatternNames(),
            (std::vector<std::string>{"standard", "eqaa", "centre", "rotated-grid", "quincunx",
                                      "flipquad", "halton:K"}));
}

TEST(SamplePattern, UnknownBuiltinOrCountListsTheCatalogue) {
  const std::vector<std::string> catalogue = {
      "standard (1, 2, 4, 8, 16)", "eqaa (1, 2, 4, 8, 16)", "centre (1, 2, 4, 8, 16)",
      "rotated-grid (2, 4)",       "quincunx (2)",          "flipquad (2)",
      "halton:K (1; K >= 0)"};
  const auto withCatalogue = [&](std::string first) {
    std::vector<std::string> parts = catalogue;
    parts.push_back(std::move(first));
    return parts;
  };
  ExpectErrorMentions([] { MakeBuiltinPattern("sparse", 4); }, withCatalogue("'sparse'"));
  ExpectErrorMentions([] { MakeBuiltinPattern("standard", 3); }, withCatalogue("no 3-sample"));
  ExpectErrorMentions([] { MakeBuiltinPattern("centre", 32); }, withCatalogue("no 32-sample"));
  ExpectErrorMentions([] { MakeBuiltinPattern("rotated-grid", 8); }, withCatalogue("no 8-sample"));
  ExpectErrorMentions([] { MakeBuiltinPattern("quincunx", 4); }, withCatalogue("'quincunx'"));
  ExpectErrorMentions([] { MakeBuiltinPattern("flipquad", 1); }, withCatalogue("'flipquad'"));
  ExpectErrorMentions([] { MakeBuiltinPattern("halton:3", 2); }, withCatalogue("'halton:3'"));
  for (const char* bad : {"halton", "halton:", "halton:-1", "halton:x", "halton:1.5", "halton: 1",
                          "halton:99999999999"}) {
    ExpectErrorMentions([&] { MakeBuiltinPattern(bad, 1); },
                        withCatalogue(std::string("'") + bad + "'"));
  }
  ExpectErrorMentions([] { HaltonJitterSequence(-1); }, {"-1"});
}

TEST(SamplePattern, CreateRejectsIllegalCounts) {
  const Table three = {{0, 0}, {1, 1}, {2, 2}};
  EXPECT_EQ(PatternErrorOf([&] { SamplePattern::Create("tri", 3, {three, three, three, three}); }),
            "pattern 'tri': 3 samples; legal counts are 1, 2, 4, 8, 16");
  EXPECT_EQ(PatternErrorOf([&] { SamplePattern::CreateUniform("tri", three); }),
            "pattern 'tri': 3 samples; legal counts are 1, 2, 4, 8, 16");
  EXPECT_EQ(PatternErrorOf([] { SamplePattern::CreateUniform("none", {}); }),
            "pattern 'none': 0 samples; legal counts are 1, 2, 4, 8, 16");
}

TEST(SamplePattern, CreateNamesThePixelWithTheWrongOffsetCount) {
  const Table two = {{0, 0}, {1, 1}};
  EXPECT_EQ(PatternErrorOf([&] { SamplePattern::Create("short", 2, {two, two, {{0, 0}}, two}); }),
            "pattern 'short': quad pixel 2 has 1 offsets, expected 2");
}

TEST(SamplePattern, CreateNamesTheOffGridSample) {
  const Table ok = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  const Table bad = {{0, 0}, {1, 1}, {2, 2}, {8, -2}};
  EXPECT_EQ(PatternErrorOf([&] { SamplePattern::Create("NAME", 4, {ok, bad, ok, ok}); }),
            "pattern 'NAME': quad pixel 1 sample 3 offset (8, -2) is off the sample grid: x and y "
            "must be integers in -8..7 (1/16 px)");
  const Table centre = {{0, 0}};
  const Table low = {{0, -9}};
  ExpectErrorMentions([&] { SamplePattern::Create("low", 1, {ok, ok, ok, low}); },
                      {"quad pixel 0", "4 offsets, expected 1"});
  ExpectErrorMentions([&] { SamplePattern::Create("low", 1, {centre, centre, centre, low}); },
                      {"'low'", "quad pixel 3 sample 0 offset (0, -9)"});
}

// ---- JSON patterns ----------------------------------------------------------------------------

TEST(SamplePattern, JsonUniformOffsets) {
  const SamplePattern pattern = ParsePatternJson(
      R"({"name": "my-pattern", "samples": 4, "offsets": [[-2,-6],[6,-2],[-6,2],[2,6]]})", 4,
      "f.json");
  EXPECT_EQ(pattern.Name(), "my-pattern");
  ExpectUniform(pattern, kHwStandard.at(4));
  EXPECT_EQ(pattern, SamplePattern::CreateUniform("my-pattern", kHwStandard.at(4)));
}

TEST(SamplePattern, JsonPerPixelOffsets) {
  const SamplePattern pattern = ParsePatternJson(
      R"({"name": "fq", "samples": 2,
          "pixels": [[[-8,-3],[3,-8]], [[-8,3],[-3,-8]], [[-8,3],[-3,-8]], [[-8,-3],[3,-8]]]})",
      2, "fq.json");
  const SamplePattern flipQuad = MakeBuiltinPattern("flipquad", 2);
  for (int p = 0; p < kQuadPixels; ++p) {
    EXPECT_EQ(PixelOffsets(pattern, p), PixelOffsets(flipQuad, p)) << p;
  }
  EXPECT_EQ(pattern.CentroidPriority(), flipQuad.CentroidPriority());
}

TEST(SamplePattern, JsonPixelUnitsConvertOnTheGrid) {
  // hw-facts §4.1's float form of standard 4x; (p - 0.5) * 16 per axis.
  const SamplePattern pattern = ParsePatternJson(
      R"({"name": "std4", "samples": 4, "units": "pixels",
          "offsets": [[0.375,0.125],[0.875,0.375],[0.125,0.625],[0.625,0.875]]})",
      4, "p.json");
  ExpectUniform(pattern, kHwStandard.at(4));
  const SamplePattern edges = ParsePatternJson(
      R"({"name": "e", "samples": 2, "units": "pixels", "offsets": [[0, 0.9375], [0.5, 0]]})", 2,
      "e.json");
  ExpectUniform(edges, {{-8, 7}, {0, -8}});
  EXPECT_EQ(ParsePatternJson(R"({"name": "s", "samples": 1, "units": "sixteenths",
                                 "offsets": [[3, -4]]})",
                             1, "s.json")
                .Offset(0, 0),
            (SampleOffset{3, -4}));
}

TEST(SamplePattern, JsonRoundTripsEveryBuiltin) {
  std::vector<SamplePattern> patterns;
  for (const int count : {1, 2, 4, 8, 16}) {
    for (const char* name : {"standard", "eqaa", "centre"}) {
      patterns.push_back(MakeBuiltinPattern(name, count));
    }
  }
  patterns.push_back(MakeBuiltinPattern("rotated-grid", 2));
  patterns.push_back(MakeBuiltinPattern("rotated-grid", 4));
  patterns.push_back(MakeBuiltinPattern("quincunx", 2));
  patterns.push_back(MakeBuiltinPattern("flipquad", 2));
  patterns.push_back(MakeBuiltinPattern("halton:5", 1));
  for (const SamplePattern& pattern : patterns) {
    const std::string json = FormatPatternJson(pattern);
    const char* form = pattern.SameInAllPixels() ? "\"offsets\"" : "\"pixels\"";
    EXPECT_NE(json.find(form), std::string::npos) << json;
    EXPECT_EQ(ParsePatternJson(json, pattern.Count(), "round-trip"), pattern) << json;
  }
}

TEST(SamplePattern, JsonErrorsNameTheFileAndSample) {
  const auto parse = [](std::string text, int samples) {
    return [text = std::move(text), samples] { ParsePatternJson(text, samples, "f.json"); };
  };
  EXPECT_EQ(PatternErrorOf(parse(R"({"name":"x","samples":4,"pixels":[[[0,0],[0,0],[0,0]],
              [[0,0],[0,0],[0,0],[0,0]],[[0,0],[0,0],[0,0],[0,0]],[[0,0],[0,0],[0,0],[0,0]]]})",
                          4)),
            "pattern file 'f.json' has 3 offsets for quad pixel 0, expected 4");
  EXPECT_EQ(PatternErrorOf(parse(R"({"name":"x","samples":8,"offsets":[[0,0]]})", 4)),
            "pattern file 'f.json' defines 8 samples but --samples is 4");
  ExpectErrorMentions(parse(R"({"name":"x","samples":2,"offsets":[[0,0]]})", 2),
                      {"'f.json'", "1 offsets, expected 2"});
  ExpectErrorMentions(
      parse(R"({"name":"x","samples":2,"offsets":[[0,0],[1.5,0]]})", 2),
      {"'f.json'", "sample 1 offset (1.5, 0) is off the sample grid", "integers in -8..7"});
  ExpectErrorMentions(parse(R"({"name":"x","samples":2,"offsets":[[0,0],[0,8]]})", 2),
                      {"'f.json'", "sample 1 offset (0, 8) is off the sample grid"});
  ExpectErrorMentions(
      parse(R"({"name":"x","samples":1,"pixels":[[[0,0]],[[0,0]],[[0,0]],[[0,"a"]]]})", 1),
      {"'f.json'", "quad pixel 3 sample 0 must be an [x, y] pair"});
  ExpectErrorMentions(
      parse(R"({"name":"x","samples":2,"units":"pixels","offsets":[[0.5,0.5],[0.3,0.5]]})", 2),
      {"'f.json'", "sample 1 position (0.3, 0.5) is off the sample grid", "multiples of 1/16"});
  ExpectErrorMentions(
      parse(R"({"name":"x","samples":1,"units":"pixels","offsets":[[1.0,0.5]]})", 1),
      {"'f.json'", "sample 0 position"});
  ExpectErrorMentions(parse(R"({"name":"x","samples":4,"offsets":[[0,0)", 4),
                      {"'f.json'", "not valid JSON"});
  ExpectErrorMentions(parse("[1, 2]", 4), {"'f.json'", "one JSON object"});
  ExpectErrorMentions(parse(R"({"samples":1,"offsets":[[0,0]]})", 1), {"'f.json'", "\"name\""});
  ExpectErrorMentions(parse(R"({"name":"x","offsets":[[0,0]]})", 1), {"'f.json'", "\"samples\""});
  ExpectErrorMentions(parse(R"({"name":"x","samples":1})", 1),
                      {"'f.json'", "neither \"offsets\" nor \"pixels\""});
  ExpectErrorMentions(parse(R"({"name":"x","samples":1,"offsets":[[0,0]],
                                "pixels":[[[0,0]],[[0,0]],[[0,0]],[[0,0]]]})",
                            1),
                      {"'f.json'", "both \"offsets\" and \"pixels\""});
  ExpectErrorMentions(parse(R"({"name":"x","samples":1,"offset":[[0,0]]})", 1),
                      {"'f.json'", "unknown key \"offset\""});
  ExpectErrorMentions(parse(R"({"name":"x","samples":1,"units":"mm","offsets":[[0,0]]})", 1),
                      {"'f.json'", "needs \"units\" to be", "\"mm\""});
  ExpectErrorMentions(parse(R"({"name":"x","samples":"4","offsets":[[0,0]]})", 4),
                      {"'f.json'", "needs \"samples\" to be an integer"});
  ExpectErrorMentions(parse(R"({"name":"","samples":1,"offsets":[[0,0]]})", 1),
                      {"'f.json'", "needs \"name\" to be a non-empty string"});
  ExpectErrorMentions(parse(R"({"name":"x","samples":1,"pixels":[[[0,0]],[[0,0]],[[0,0]]]})", 1),
                      {"'f.json'", "\"pixels\" to be 4 lists, one per quad pixel"});
  ExpectErrorMentions(parse(R"({"name":"x","samples":1,"offsets":{"a":1}})", 1),
                      {"'f.json'", "list of [x, y] pairs"});
  ExpectErrorMentions(parse(R"({"name":"tri","samples":3,"offsets":[[0,0],[1,1],[2,2]]})", 3),
                      {"'f.json'", "3 samples; legal counts are 1, 2, 4, 8, 16"});
}

// 5e-324 px used to snap silently onto the grid: the shift by -8 px rounded the off-grid value away.
TEST(SamplePattern, TinyOffGridPositionsAreRefused) {
  const std::string text =
      R"({"name":"x","samples":2,"units":"pixels","offsets":[[0.5,0.5],[5e-324,0.5]]})";
  ExpectErrorMentions([&] { ParsePatternJson(text, 2, "f.json"); },
                      {"'f.json'", "sample 1 position", "off the sample grid"});
}

TEST(SamplePattern, DeepNestingIsRefusedWithAShortMessage) {
  const std::string deep = std::string(70000, '[') + std::string(70000, ']');
  ExpectErrorMentions([&] { ParsePatternJson(deep, 4, "f.json"); },
                      {"'f.json'", "nests deeper than 64 levels"});
  const std::string deepOffsets = R"({"name":"x","samples":1,"offsets":)" + std::string(60, '[') +
                                  std::string(60, ']') + "}";
  const std::string message = PatternErrorOf([&] { ParsePatternJson(deepOffsets, 1, "f.json"); });
  EXPECT_NE(message.find("'f.json'"), std::string::npos) << message;
  EXPECT_LT(message.size(), 200u) << message;
}

// ---- Files and ResolvePattern -----------------------------------------------------------------

// A file in the test temp directory, randomly named so concurrent runs of the suite do not meet.
class TempFile {
 public:
  explicit TempFile(const std::string& text)
      : path_(std::filesystem::path(::testing::TempDir()) /
              ("aasim_pattern_" + std::to_string(std::random_device{}()) + ".json")) {
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::filesystem::remove(path_); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::filesystem::path& Path() const { return path_; }

 private:
  std::filesystem::path path_;
};

TEST(SamplePattern, LoadAndResolveFiles) {
  const TempFile file(R"({"name": "rg", "samples": 2, "offsets": [[-4, 4], [4, -4]]})");
  const SamplePattern loaded = LoadPatternJson(file.Path(), 2);
  EXPECT_EQ(loaded, SamplePattern::CreateUniform("rg", Table{{-4, 4}, {4, -4}}));
  EXPECT_EQ(ResolvePattern(file.Path().string(), 2), loaded);
  ExpectErrorMentions([&] { LoadPatternJson(file.Path(), 4); },
                      {file.Path().string(), "defines 2 samples but --samples is 4"});

  EXPECT_EQ(ResolvePattern("standard", 8), MakeBuiltinPattern("standard", 8));
  EXPECT_EQ(ResolvePattern("halton:2", 1), MakeBuiltinPattern("halton:2", 1));
  ExpectErrorMentions([] { ResolvePattern("missing.json", 4); },
                      {"pattern file 'missing.json'", "cannot be opened"});
  ExpectErrorMentions([] { ResolvePattern("no/such/dir", 4); }, {"pattern file 'no/such/dir'"});
  ExpectErrorMentions([] { ResolvePattern("missing", 4); }, {"unknown sample pattern 'missing'"});
  ExpectErrorMentions([] { LoadPatternJson("/dev/zero", 4); },
                      {"pattern file '/dev/zero'", "not a regular file"});
}

}  // namespace
}  // namespace raster
