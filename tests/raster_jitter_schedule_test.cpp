// Jitter schedules: the per-frame sample positions of every schedule against the sources'
// tables (aa-facts §1.8, §5; seed 001), and the Halton values they cycle.

#include <gtest/gtest.h>

#include "raster/jitter_schedule.h"
#include "raster/raster_error.h"

namespace {

using raster::JitterSchedule;
using raster::SampleOffset;

JitterSchedule Schedule(std::string_view name) {
  return JitterSchedule::Make(name, raster::MakeBuiltinPattern("eqaa", 8));
}

// aa-facts §5.3's 16-entry Halton(2,3) table in [0, 1) from the pixel corner, with the 1-based
// index (entry i + 1), floored to the 1/16 grid and moved to centre-relative offsets.
TEST(JitterSchedule, Halton16FollowsThePublishedTableOnTheSixteenthGrid) {
  const double table[16][2] = {{0.5, 1.0 / 3},     {0.25, 2.0 / 3},    {0.75, 1.0 / 9},    {0.125, 4.0 / 9},
                               {0.625, 7.0 / 9},   {0.375, 2.0 / 9},   {0.875, 5.0 / 9},   {0.0625, 8.0 / 9},
                               {0.5625, 1.0 / 27}, {0.3125, 10.0 / 27}, {0.8125, 19.0 / 27}, {0.1875, 4.0 / 27},
                               {0.6875, 13.0 / 27}, {0.4375, 22.0 / 27}, {0.9375, 7.0 / 27}, {0.03125, 16.0 / 27}};
  const JitterSchedule halton = Schedule("halton16");
  ASSERT_EQ(halton.Length(), 16);
  for (int k = 0; k < 16; ++k) {
    const SampleOffset expected{static_cast<int>(table[k][0] * 16) - 8, static_cast<int>(table[k][1] * 16) - 8};
    EXPECT_EQ(halton.At(k).Offset(0, 0), expected) << "frame " << k;
    EXPECT_EQ(halton.At(k + 16), halton.At(k));
  }
}

TEST(JitterSchedule, Halton8IsThePrefixOfHalton16) {
  const JitterSchedule h8 = Schedule("halton8");
  const JitterSchedule h16 = Schedule("halton16");
  ASSERT_EQ(h8.Length(), 8);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(h8.At(k).Offset(0, 0), h16.At(k).Offset(0, 0));
  EXPECT_EQ(h8.At(8).Offset(0, 0), h16.At(0).Offset(0, 0));
}

// aa-facts §1.8, y up in the table, +y down here.
TEST(JitterSchedule, SmaaT2xAnd4xMatchTheHeaderTable) {
  const JitterSchedule t2x = Schedule("t2x");
  EXPECT_EQ(t2x.Samples(), 1);
  EXPECT_EQ(t2x.At(0).Offset(0, 0), (SampleOffset{4, 4}));    // (+0.25, -0.25) y up
  EXPECT_EQ(t2x.At(1).Offset(0, 0), (SampleOffset{-4, -4}));  // (-0.25, +0.25)
  EXPECT_EQ(t2x.At(2), t2x.At(0));
  const JitterSchedule fourX = Schedule("4x");
  EXPECT_EQ(fourX.Samples(), 2);
  EXPECT_EQ(fourX.At(0).Offset(0, 0), (SampleOffset{6, 2}));    // S0 (+0.375, -0.125)
  EXPECT_EQ(fourX.At(0).Offset(0, 1), (SampleOffset{-2, -6}));  // S1 (-0.125, +0.375)
  EXPECT_EQ(fourX.At(1).Offset(0, 0), (SampleOffset{2, 6}));    // S2 (+0.125, -0.375)
  EXPECT_EQ(fourX.At(1).Offset(0, 1), (SampleOffset{-6, -2}));  // S3 (-0.375, +0.125)
}

// Each frame draws one of FLIPQUAD's two samples; together they are the 2x pattern.
TEST(JitterSchedule, FlipQuadSplitDrawsOneFlipQuadSamplePerFrame) {
  const raster::SamplePattern flipquad = raster::MakeBuiltinPattern("flipquad", 2);
  const JitterSchedule split = Schedule("flipquad-split");
  ASSERT_EQ(split.Length(), 2);
  for (int frame = 0; frame < 2; ++frame) {
    EXPECT_EQ(split.At(frame).Count(), 1);
    for (int p = 0; p < raster::kQuadPixels; ++p) EXPECT_EQ(split.At(frame).Offset(p, 0), flipquad.Offset(p, frame));
  }
  const JitterSchedule quincunx = Schedule("quincunx");
  EXPECT_EQ(quincunx.At(0).Offset(0, 0), (SampleOffset{0, 0}));
  EXPECT_EQ(quincunx.At(1).Offset(0, 0), (SampleOffset{-8, -8}));
}

TEST(JitterSchedule, NoneRepeatsTheRunsPatternAndUnknownNamesAreRefused) {
  const raster::SamplePattern base = raster::MakeBuiltinPattern("eqaa", 8);
  const JitterSchedule none = JitterSchedule::Make("none", base);
  EXPECT_EQ(none.At(0), base);
  EXPECT_EQ(none.At(5), base);
  EXPECT_EQ(raster::JitterScheduleSamples("none"), 0);
  EXPECT_EQ(raster::JitterScheduleSamples("4x"), 2);
  try {
    JitterSchedule::Make("halton9", base);
    FAIL() << "accepted an unknown schedule";
  } catch (const raster::RasterError& error) {
    EXPECT_NE(std::string(error.what()).find("halton9"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("flipquad-split"), std::string::npos);
  }
  EXPECT_THROW(none.At(-1), raster::RasterError);
}

}  // namespace
