// The CRAA LUT generator and its fixture format (passes/craa/craa_lut.h, docs/craa.md "CRAA
// LUT"): determinism, the weight limits, symmetry, the fit against all-own, the seed's worked
// entry, and the strict reader.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "passes/craa/craa_lut.h"
#include "raster/sample_pattern.h"

namespace {

using passes::craa::CraaLut;
using passes::craa::CraaLutError;
using passes::craa::LutEntry;
using passes::craa::LutEntrySource;
using passes::craa::LutGeneratorSettings;

// An eighth of the default configurations (120000): enough for the frequent entries, fast.
LutGeneratorSettings Small() { return passes::craa::WithConfigurations({}, 120000); }
LutGeneratorSettings Tiny() { return passes::craa::WithConfigurations({}, 12000); }

raster::SamplePattern Standard(int samples) { return raster::MakeBuiltinPattern("standard", samples); }

// Every sample mirrored (x -> -x when `horizontal`, else y -> -y), sample indices kept.
raster::SamplePattern Mirrored(const raster::SamplePattern& pattern, bool horizontal) {
  std::vector<raster::SampleOffset> offsets;
  for (int s = 0; s < pattern.Count(); ++s) {
    const raster::SampleOffset o = pattern.Offset(0, s);
    offsets.push_back(horizontal ? raster::SampleOffset{-o.x, o.y} : raster::SampleOffset{o.x, -o.y});
  }
  return raster::SamplePattern::CreateUniform("mirrored", offsets);
}

void ExpectEntry(const LutEntry& entry, int up, int bottom, int left, int right, const std::string& what) {
  EXPECT_EQ(entry.up, up) << what;
  EXPECT_EQ(entry.bottom, bottom) << what;
  EXPECT_EQ(entry.left, left) << what;
  EXPECT_EQ(entry.right, right) << what;
}

TEST(CraaLut, PackingPutsUpInTheLowNibbleAndRoundTripsEveryValue) {
  EXPECT_EQ(passes::craa::PackLutEntry({2, 3, 0, 0}), 0x0032);
  EXPECT_EQ(passes::craa::PackLutEntry({1, 2, 3, 15}), 0xF321);
  for (std::uint32_t packed = 0; packed <= 0xFFFF; ++packed) {
    ASSERT_EQ(passes::craa::PackLutEntry(passes::craa::UnpackLutEntry(static_cast<std::uint16_t>(packed))), packed);
  }
}

TEST(CraaLut, DefaultSettingsAreTheDefaultTotalInTheDefaultProportions) {
  const LutGeneratorSettings defaults;
  const LutGeneratorSettings split = passes::craa::WithConfigurations({}, 960000);
  EXPECT_EQ(split.edges, defaults.edges);
  EXPECT_EQ(split.corners, defaults.corners);
  EXPECT_EQ(split.junctions, defaults.junctions);
  EXPECT_EQ(split.slivers, defaults.slivers);
  EXPECT_EQ(split.sliverEdges, defaults.sliverEdges);
  EXPECT_EQ(split.triangles, defaults.triangles);
}

TEST(CraaLut, SameTableTwiceAndWithOneOrTwoThreads) {
  for (const int samples : {4, 8}) {
    LutGeneratorSettings one = Tiny(), two = Tiny();
    one.threads = 1;
    two.threads = 2;
    const auto a = passes::craa::GenerateCraaLutWithSummary(Standard(samples), one);
    const auto b = passes::craa::GenerateCraaLutWithSummary(Standard(samples), two);
    EXPECT_EQ(a.lut, b.lut) << samples;
    EXPECT_EQ(a.summary.meanError, b.summary.meanError) << samples;
    EXPECT_EQ(passes::craa::GenerateCraaLut(Standard(samples), two), b.lut) << samples;
  }
}

TEST(CraaLut, AnotherSeedGivesAnotherSampleOfConfigurations) {
  LutGeneratorSettings other = Tiny();
  other.seed = 2;
  EXPECT_NE(passes::craa::GenerateCraaLut(Standard(8), Tiny()), passes::craa::GenerateCraaLut(Standard(8), other));
}

// Exhaustive over every entry of the 2S, 4S, 8S and 16S tables: weights <= 15, sum <= the
// UNKNOWN samples (so FMASK 0 is all own), and the GPU size is 2 bytes an entry.
TEST(CraaLut, WeightsNeverExceedTheLimits) {
  for (const int samples : {2, 4, 8, 16}) {
    const CraaLut lut = passes::craa::GenerateCraaLut(Standard(samples), Tiny());
    ASSERT_EQ(lut.Tables(), 1);
    EXPECT_EQ(lut.Bytes(), (std::size_t{2} << samples));
    ExpectEntry(lut.Entry(0, 0), 0, 0, 0, 0, "FMASK 0");
    EXPECT_EQ(lut.Source(0, 0), LutEntrySource::kFixed);
    for (std::uint32_t f = 0; f < (1u << samples); ++f) {
      const LutEntry& e = lut.Entry(0, f);
      ASSERT_LE(std::max({e.up, e.bottom, e.left, e.right}), passes::craa::kMaxLutWeight) << samples << " " << f;
      ASSERT_LE(e.Sum(), std::popcount(f)) << samples << " " << f;
      ASSERT_EQ(lut.Entry(3, f), e) << "one table serves every quad pixel";
    }
  }
  EXPECT_EQ(passes::craa::GenerateCraaLut(Standard(8), Tiny()).Bytes(), 512u) << "seed 001: 512 bytes for 8S";
}

TEST(CraaLut, FitBeatsAllOwnOnItsConfigurations) {
  for (const int samples : {2, 4, 8}) {
    const auto generated = passes::craa::GenerateCraaLutWithSummary(Standard(samples), Tiny());
    EXPECT_LT(generated.summary.meanError, 0.5 * generated.summary.meanErrorAllOwn) << samples;
    EXPECT_GT(generated.summary.fitted, 0);
  }
}

// Mirroring the pattern mirrors the configurations' samples: the distribution is closed under
// the 8 symmetries of the square and the sums are exact integers, so the table mirrors exactly,
// except where two neighbours are interchangeable for an FMASK (a sliver stored in the centre
// leaves the same surface above and below): there the split between them is an exact tie that
// both tables break the same way, so the mirrored entry must then have the same error.
TEST(CraaLut, MirroredPatternSwapsLeftRightOrUpBottom) {
  const raster::SamplePattern pattern = Standard(8);
  const auto lut = passes::craa::GenerateCraaLutWithSummary(pattern, Tiny());
  int asymmetric = 0, ties = 0;
  for (const bool horizontal : {true, false}) {
    const auto mirrored = passes::craa::GenerateCraaLutWithSummary(Mirrored(pattern, horizontal), Tiny());
    for (std::uint32_t f = 0; f < 256; ++f) {
      const LutEntry& e = lut.lut.Entry(0, f);
      const LutEntry swapped = horizontal ? LutEntry{e.up, e.bottom, e.right, e.left}
                                          : LutEntry{e.bottom, e.up, e.left, e.right};
      ASSERT_EQ(mirrored.entryError[f], lut.entryError[f]) << horizontal << " " << f;
      if (mirrored.lut.Entry(0, f) != swapped) ++ties;
      asymmetric += (horizontal ? e.left != e.right : e.up != e.bottom) ? 1 : 0;
    }
  }
  EXPECT_LE(ties, 4) << "exact ties are rare";
  EXPECT_GT(asymmetric, 40) << "the test needs entries that tell the sides apart";
}

// eqaa 8x is standard 8x re-indexed (hw-facts §4.3): the same table with the FMASK bits permuted.
TEST(CraaLut, ReindexedPatternPermutesTheIndex) {
  const raster::SamplePattern standard = Standard(8), eqaa = raster::MakeBuiltinPattern("eqaa", 8);
  std::vector<int> toStandard(8);
  for (int s = 0; s < 8; ++s) {
    for (int t = 0; t < 8; ++t) {
      if (eqaa.Offset(0, s) == standard.Offset(0, t)) toStandard[s] = t;
    }
  }
  const CraaLut a = passes::craa::GenerateCraaLut(standard, Tiny());
  const CraaLut b = passes::craa::GenerateCraaLut(eqaa, Tiny());
  for (std::uint32_t f = 0; f < 256; ++f) {
    std::uint32_t g = 0;
    for (int s = 0; s < 8; ++s) g |= ((f >> s) & 1u) << toStandard[s];
    ASSERT_EQ(b.Entry(0, f), a.Entry(0, g)) << f;
  }
}

// A fully UNKNOWN 8S pixel never comes out of the configurations (the stored surface covers a
// sample): the nearest-edge rule gives each sample to the neighbour across its nearest edge,
// |y| == |x| to the vertical one. Standard 8x: U (1,-3) (-3,-5) (7,-7); B (-1,3) (-5,5) (3,7);
// L (-7,-1); R (5,1).
TEST(CraaLut, UnreachedFmaskUsesTheNearestEdgeRule) {
  const auto generated = passes::craa::GenerateCraaLutWithSummary(Standard(8), Tiny());
  EXPECT_EQ(generated.lut.Source(0, 0xFF), LutEntrySource::kFallback);
  ExpectEntry(generated.lut.Entry(0, 0xFF), 3, 3, 1, 1, "FMASK 0xFF");
  EXPECT_GE(generated.summary.fallbacks, 1);
  EXPECT_EQ(generated.summary.fitted + generated.summary.fallbacks, 255);
}

TEST(CraaLut, PatternThatDiffersPerQuadPixelGetsFourTables) {
  const CraaLut lut = passes::craa::GenerateCraaLut(raster::MakeBuiltinPattern("flipquad", 2), Tiny());
  ASSERT_EQ(lut.Tables(), 4);
  EXPECT_EQ(lut.Bytes(), 4u * 4u * 2u);
  EXPECT_EQ(lut.Offsets(1)[0], (raster::SampleOffset{-8, 3}));
  const CraaLut back = passes::craa::ParseCraaLut(passes::craa::FormatCraaLut(lut), "flipquad.json");
  EXPECT_EQ(back, lut);
}

// Seed 001 "8xCRAA LUT: Example": CLUT[01101111] (sample 0 first: FMASK 0xF6, samples 0 and 3
// known) = U 2, B 3. The generator gives U 0 B 6 for eqaa (the known samples are the two
// topmost, so the UNKNOWN ones lie below an edge near the top) and U 1 B 4 R 1 for standard;
// docs/craa.md "The seed's worked entry" explains the difference.
TEST(CraaLut, SeedWorkedEntry) {
  const CraaLut eqaa = passes::craa::GenerateCraaLut(raster::MakeBuiltinPattern("eqaa", 8), Small());
  ExpectEntry(eqaa.Entry(0, 0xF6), 0, 6, 0, 0, "eqaa 0xF6");
  const CraaLut standard = passes::craa::GenerateCraaLut(Standard(8), Small());
  ExpectEntry(standard.Entry(0, 0xF6), 1, 4, 0, 1, "standard 0xF6");
}

// The same at the default settings, as `aasim craa-lut` writes the table.
TEST(FullSize, CraaLutSeedWorkedEntryAtDefaultSettings) {
  const CraaLut eqaa = passes::craa::GenerateCraaLut(raster::MakeBuiltinPattern("eqaa", 8));
  ExpectEntry(eqaa.Entry(0, 0xF6), 0, 6, 0, 0, "eqaa 0xF6");
  ExpectEntry(eqaa.Entry(0, 0x6F), 2, 4, 0, 0, "eqaa 0x6F (the index read most significant bit first)");
}

TEST(CraaLut, SettingsOutOfRangeAreRefused) {
  LutGeneratorSettings s = Tiny();
  s.edges = -1;
  EXPECT_THROW(passes::craa::GenerateCraaLut(Standard(2), s), std::invalid_argument);
  s = Tiny();
  s.maxSliverWidth = 0.0;
  EXPECT_THROW(passes::craa::GenerateCraaLut(Standard(2), s), std::invalid_argument);
  s = passes::craa::WithConfigurations({}, passes::craa::kMaxLutConfigurations + 10);
  EXPECT_THROW(passes::craa::GenerateCraaLut(Standard(2), s), std::invalid_argument);
}

// ---- Fixture format ----

TEST(CraaLutFile, RoundTripsWithFallbacks) {
  for (const int samples : {1, 2, 8, 16}) {
    const CraaLut lut = passes::craa::GenerateCraaLut(Standard(samples), Tiny());
    const std::string text = passes::craa::FormatCraaLut(lut);
    const CraaLut back = passes::craa::ParseCraaLut(text, "lut.json");
    EXPECT_EQ(back, lut) << samples;
    EXPECT_EQ(passes::craa::FormatCraaLut(back), text) << samples;
  }
}

// A hand-made 2S table: FMASK 1 = sample 0 UNKNOWN.
std::string Valid2S() {
  return R"({"schema": "aasim.craa.lut", "version": 1, "pattern": "p", "samples": 2, "tables": [
    {"offsets": [[-4, -4], [4, 4]], "fallback": [3],
     "entries": [[0, 0, 0, 0], [1, 0, 0, 0], [0, 0, 0, 1], [0, 1, 1, 0]]}]})";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

std::string ParseError(const std::string& text) {
  try {
    passes::craa::ParseCraaLut(text, "bad.json");
  } catch (const CraaLutError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(CraaLutFile, ReadsAHandMadeTable) {
  const CraaLut lut = passes::craa::ParseCraaLut(Valid2S(), "ok.json");
  EXPECT_EQ(lut.Samples(), 2);
  EXPECT_EQ(lut.PatternName(), "p");
  ExpectEntry(lut.Entry(2, 1), 1, 0, 0, 0, "FMASK 1");
  EXPECT_EQ(lut.Packed(0, 3), 0x0110);
  EXPECT_EQ(lut.Source(0, 3), LutEntrySource::kFallback);
  EXPECT_EQ(lut.Source(0, 1), LutEntrySource::kFitted);
}

TEST(CraaLutFile, RefusesMalformedInputWithOneLineNamingWhere) {
  const std::string valid = Valid2S();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{", "CRAA LUT file 'bad.json' is not valid JSON"},
      {"[]", "CRAA LUT file 'bad.json' must hold one JSON object, found an array of 0 values"},
      {Replace(valid, "aasim.craa.lut", "other"), "has schema \"other\", expected \"aasim.craa.lut\""},
      {Replace(valid, "\"version\": 1", "\"version\": 2"), "has version 2, expected 1"},
      {Replace(valid, "\"samples\": 2", "\"samples\": 3"), "needs \"samples\" to be 1, 2, 4, 8 or 16, found 3"},
      {Replace(valid, "\"pattern\": \"p\",", ""), "has no \"pattern\" key"},
      {Replace(valid, "\"pattern\"", "\"colour\": 1, \"pattern\""), "has unknown key \"colour\""},
      {Replace(valid, "[1, 0, 0, 0]", "[16, 0, 0, 0]"),
       "'bad.json': table 0 entry 1 up must be an integer in 0..15, found 16"},
      {Replace(valid, "[1, 0, 0, 0]", "[1, 0, 0, 1]"),
       "'bad.json': table 0 entry 1 weights sum to 2 but the FMASK has 1 UNKNOWN samples"},
      {Replace(valid, "[0, 0, 0, 0], [1", "[0, 0, 1, 0], [1"),
       "table 0 entry 0 weights sum to 1 but the FMASK has 0 UNKNOWN samples"},
      {Replace(valid, "[0, 0, 0, 1]", "[0, 0, 0]"), "table 0 entry 2 must be an [up, bottom, left, right] list"},
      {Replace(valid, ", [0, 1, 1, 0]]", "]"), "table 0 needs \"entries\" to be a list of 4 entries, found an array of 3"},
      {Replace(valid, "[4, 4]]", "[4, 8]]"), "table 0 sample 1 y must be an integer in -8..7, found 8"},
      {Replace(valid, "[[-4, -4], [4, 4]]", "[[-4, -4]]"), "needs \"offsets\" to be a list of 2 [x, y] pairs"},
      {Replace(valid, "\"fallback\": [3]", "\"fallback\": [3, 2]"), "table 0 fallback 1 must be above the one before it (3)"},
      {Replace(valid, "\"fallback\": [3]", "\"fallback\": [0]"), "table 0 fallback 0 an FMASK value must be an integer in 1..3"},
      {Replace(valid, "\"tables\": [", "\"tables\": [1, "), "needs \"tables\" to be a list of 1 or 4 tables"},
      {std::string(100, '[') + std::string(100, ']'), "nests deeper than 64 levels"},
  };
  for (const auto& [text, message] : cases) {
    const std::string error = ParseError(text);
    EXPECT_NE(error.find(message), std::string::npos) << "expected: " << message << "\n got: " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

}  // namespace
