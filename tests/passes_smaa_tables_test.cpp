// SMAA's lookup tables (passes/smaa/area_tex.h, search_tex.h): the orthogonal areas against
// trapezoids and triangles computed here in closed form, the tables' mirror and flip
// symmetries, every SearchTex entry against its definition, and both tables against the
// published iryoku/smaa Textures/AreaTex.h and SearchTex.h (docs/smaa-tables.md says how those
// were read and compared).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <future>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "fmask/fixtures.h"
#include "passes/smaa/area_tex.h"
#include "passes/smaa/search_tex.h"

namespace passes::smaa {
namespace {

constexpr double kTight = 1e-12;

struct Rg {
  std::uint8_t r, g;
};

Rg AreaTexel(int x, int y) {
  const std::span<const std::uint8_t> bytes = AreaTexBytes();
  const std::size_t at = 2 * (static_cast<std::size_t>(y) * kAreaTexWidth + x);
  return {bytes[at], bytes[at + 1]};
}

// Area over pixel [l, l + 1] under a line falling linearly from height h at x = 0 to 0 at
// x = d / 2, where the pixel lies wholly inside that half: a trapezoid.
double HalfLineTrapezoid(double h, int l, int d) { return std::abs(h) * (1.0 - (2.0 * l + 1.0) / d); }

// The pattern with its two ends swapped (left <-> right), and with up and down swapped.
int Mirror(int p) {
  return (p & kLeftDown ? kRightDown : 0) | (p & kRightDown ? kLeftDown : 0) | (p & kLeftUp ? kRightUp : 0) |
         (p & kRightUp ? kLeftUp : 0);
}
int FlipVertical(int p) {
  return (p & kLeftDown ? kLeftUp : 0) | (p & kLeftUp ? kLeftDown : 0) | (p & kRightDown ? kRightUp : 0) |
         (p & kRightUp ? kRightDown : 0);
}

// --- Orthogonal areas against closed forms (offset 0) ---

TEST(PassesSmaaTables, OrthoLShapeIsTheTrapezoidUnderItsNearHalf) {
  for (int l = 0; l < 40; ++l) {
    for (int r = 0; r < 40; ++r) {
      const int d = l + r + 1;
      const AreaPair down = OrthoArea(kLeftDown, l, r, 0.0), up = OrthoArea(kLeftUp, l, r, 0.0);
      const AreaPair rightDown = OrthoArea(kRightDown, r, l, 0.0);
      if (2 * (l + 1) <= d) {  // the pixel lies in the half next to the crossing edge
        EXPECT_NEAR(down.r, HalfLineTrapezoid(0.5, l, d), kTight) << l << " " << r;
        EXPECT_EQ(down.g, 0.0);
        EXPECT_NEAR(up.g, HalfLineTrapezoid(0.5, l, d), kTight) << l << " " << r;
        EXPECT_EQ(up.r, 0.0);
        // The same L seen from the other end: pixel r counted from the left, distances swapped.
        EXPECT_NEAR(rightDown.r, HalfLineTrapezoid(0.5, l, d), kTight) << l << " " << r;
      }
      if (l > r) {  // the far half is left unfiltered (aa-facts §1.6)
        EXPECT_EQ(down.r + down.g + up.r + up.g, 0.0) << l << " " << r;
      }
    }
  }
}

TEST(PassesSmaaTables, OrthoShortestLIsOneTriangle) {
  // Distances (0, 0): the segment ends at x = 1/2, height 1/2 at x = 0.
  const AreaPair down = OrthoArea(kLeftDown, 0, 0, 0.0);
  EXPECT_DOUBLE_EQ(down.r, 0.125);
  EXPECT_EQ(down.g, 0.0);
  EXPECT_EQ(AreaToUnorm8(down.r), 31);
  EXPECT_EQ(AreaTexel(48, 0).r, 31);  // pattern 1's slot (3, 0), stripe 0
}

TEST(PassesSmaaTables, OrthoZShapeCrossingPixelIsTwoEqualTriangles) {
  const int zUpDown = kLeftUp | kRightDown;
  for (int l = 0; l < 60; ++l) {
    const int d = 2 * l + 1;
    const AreaPair centre = OrthoArea(zUpDown, l, l, 0.0);
    EXPECT_NEAR(centre.r, 1.0 / (8.0 * d), kTight) << l;
    EXPECT_NEAR(centre.g, 1.0 / (8.0 * d), kTight) << l;
    for (int x = 0; x < l; ++x) {  // left of the centre the line is above the edge
      const AreaPair area = OrthoArea(zUpDown, x, d - 1 - x, 0.0);
      EXPECT_NEAR(area.g, 0.5 - (2.0 * x + 1.0) / (2.0 * d), kTight) << l << " " << x;
      EXPECT_EQ(area.r, 0.0);
    }
  }
}

TEST(PassesSmaaTables, OrthoUShapeIsTheSmoothedTrapezoid) {
  for (int l = 0; l < 40; ++l) {
    for (int r = l + 1; r < 60; ++r) {
      const int d = l + r + 1;
      if (2 * (l + 1) > d) continue;
      const double a = HalfLineTrapezoid(0.5, l, d);
      const double rounder = std::sqrt(2.0 * a) / 2.0, p = std::min(d / 32.0, 1.0);
      EXPECT_NEAR(OrthoArea(kLeftDown | kRightDown, l, r, 0.0).r, rounder + (a - rounder) * p, kTight) << l << " " << r;
      EXPECT_NEAR(OrthoArea(kLeftUp | kRightUp, l, r, 0.0).g, rounder + (a - rounder) * p, kTight) << l << " " << r;
    }
  }
}

TEST(PassesSmaaTables, OrthoUnfilteredPatternsAreZeroEverywhere) {
  // No crossing edge, or a crossing edge through one end and nothing or another through the
  // other (aa-facts §1.6).
  for (const int pattern : {0, kLeftDown | kLeftUp, kRightDown | kRightUp, 15}) {
    for (int stripe = 0; stripe < kOrthoOffsetCount; ++stripe) {
      for (int i = 0; i < kOrthoSize; ++i) {
        for (int j = 0; j < kOrthoSize; ++j) {
          const Texel t = OrthoTexel(pattern, stripe, i, j);
          EXPECT_EQ(AreaTexel(t.x, t.y).r + AreaTexel(t.x, t.y).g, 0) << pattern << " " << stripe;
        }
      }
    }
  }
}

// --- Symmetries ---

TEST(PassesSmaaTables, OrthoMirroredPatternWithSwappedDistancesHasTheSameAreas) {
  for (int pattern = 0; pattern < kPatternCount; ++pattern) {
    for (int stripe = 0; stripe < kOrthoOffsetCount; ++stripe) {
      const double offset = OrthoSubsampleOffset(stripe);
      for (int l = 0; l < 50; ++l) {
        for (int r = 0; r < 50; ++r) {
          const AreaPair a = OrthoArea(pattern, l, r, offset), m = OrthoArea(Mirror(pattern), r, l, offset);
          ASSERT_NEAR(a.r, m.r, 1e-9) << pattern << " " << stripe << " " << l << " " << r;
          ASSERT_NEAR(a.g, m.g, 1e-9) << pattern << " " << stripe << " " << l << " " << r;
        }
      }
    }
  }
}

TEST(PassesSmaaTables, OrthoFlippedPatternWithNegatedOffsetSwapsTheChannels) {
  // Stripe pairs with opposite offsets (aa-facts §1.6): 0 with itself, 1/2, 3/4, 5/6. The flip
  // negates every height exactly, so even the truncated bytes must agree.
  constexpr std::array<int, kOrthoOffsetCount> kOpposite{0, 2, 1, 4, 3, 6, 5};
  for (int pattern = 0; pattern < kPatternCount; ++pattern) {
    for (int stripe = 0; stripe < kOrthoOffsetCount; ++stripe) {
      ASSERT_EQ(OrthoSubsampleOffset(kOpposite[stripe]), -OrthoSubsampleOffset(stripe));
      for (int i = 0; i < kOrthoSize; ++i) {
        for (int j = 0; j < kOrthoSize; ++j) {
          const AreaPair a = OrthoArea(pattern, i * i, j * j, OrthoSubsampleOffset(stripe));
          const AreaPair f = OrthoArea(FlipVertical(pattern), i * i, j * j, OrthoSubsampleOffset(kOpposite[stripe]));
          ASSERT_DOUBLE_EQ(a.r, f.g) << pattern << " " << stripe << " " << i << " " << j;
          ASSERT_DOUBLE_EQ(a.g, f.r) << pattern << " " << stripe << " " << i << " " << j;
          const Texel t = OrthoTexel(pattern, stripe, i, j), ft = OrthoTexel(FlipVertical(pattern), kOpposite[stripe], i, j);
          ASSERT_EQ(AreaTexel(t.x, t.y).r, AreaTexel(ft.x, ft.y).g);
          ASSERT_EQ(AreaTexel(t.x, t.y).g, AreaTexel(ft.x, ft.y).r);
        }
      }
    }
  }
}

TEST(PassesSmaaTables, DiagOffsetMovesOnlyEndsWithCrossingEdges) {
  // Pattern 0 has no crossing edge at either end: all five diagonal stripes hold the same slot.
  for (int stripe = 1; stripe < kDiagOffsetCount; ++stripe) {
    for (int i = 0; i < kDiagSize; ++i) {
      for (int j = 0; j < kDiagSize; ++j) {
        const Texel t0 = DiagTexel(0, 0, i, j), t = DiagTexel(0, stripe, i, j);
        ASSERT_EQ(AreaTexel(t0.x, t0.y).r, AreaTexel(t.x, t.y).r);
        ASSERT_EQ(AreaTexel(t0.x, t0.y).g, AreaTexel(t.x, t.y).g);
      }
    }
  }
}

TEST(PassesSmaaTables, DiagSingleLineThroughPixelCornersHalvesThePixel) {
  // Pattern 3 has one candidate line, through (1, 0) and (1 + d, d): along the pixel's diagonal,
  // so about half of the 30 x 30 samples lie on either side; the samples on the diagonal itself
  // fall either way with rounding. The opposite pixel only touches the line at a corner.
  for (int l = 0; l < kDiagSize; ++l) {
    for (int r = 0; r < kDiagSize; ++r) {
      const AreaPair area = DiagArea(3, l, r, {});
      EXPECT_GE(area.r, 435.0 / 900.0) << l << " " << r;
      EXPECT_LE(area.r, 465.0 / 900.0) << l << " " << r;
      EXPECT_LE(area.g, 1.0 / 900.0) << l << " " << r;
    }
  }
}

TEST(PassesSmaaTables, EveryAreaTexelIsWrittenOnceAndTheRestIsZero) {
  std::vector<std::array<int, kAreaTexWidth>> writes(kAreaTexHeight);
  for (int pattern = 0; pattern < kPatternCount; ++pattern) {
    for (int stripe = 0; stripe < kOrthoOffsetCount; ++stripe) {
      for (int i = 0; i < kOrthoSize; ++i) {
        for (int j = 0; j < kOrthoSize; ++j) {
          const Texel t = OrthoTexel(pattern, stripe, i, j);
          ++writes[t.y][t.x];
        }
      }
    }
    for (int stripe = 0; stripe < kDiagOffsetCount; ++stripe) {
      for (int i = 0; i < kDiagSize; ++i) {
        for (int j = 0; j < kDiagSize; ++j) {
          const Texel t = DiagTexel(pattern, stripe, i, j);
          ++writes[t.y][t.x];
        }
      }
    }
  }
  for (int y = 0; y < kAreaTexHeight; ++y) {
    for (int x = 0; x < kAreaTexWidth; ++x) {
      ASSERT_LE(writes[y][x], 1) << x << " " << y;
      // Unwritten: ortho slot 2 (no crossing code maps to it) and diagonal stripes 5, 6.
      const bool unused = x < kDiagHalfX ? (x / kOrthoSize == 2 || y % kStripeRows / kOrthoSize == 2)
                                         : y >= kDiagOffsetCount * kStripeRows;
      ASSERT_EQ(writes[y][x] == 0, unused) << x << " " << y;
      if (unused) {
        ASSERT_EQ(AreaTexel(x, y).r + AreaTexel(x, y).g, 0) << x << " " << y;
      }
    }
  }
}

// --- SearchTex against its definition (aa-facts §1.4, §1.7) ---

// The four edge bits whose pseudo-gather (bilinear fetch at (-0.25, -0.125) px) is value / 32,
// found by trying all sixteen: {up-left, up, left, current}.
std::optional<std::array<bool, 4>> Ungather(int value) {
  for (int mask = 0; mask < 16; ++mask) {
    const auto e = [mask](int bit) { return static_cast<double>(mask >> bit & 1); };
    const double top = e(0) + (e(1) - e(0)) * 0.75, bottom = e(2) + (e(3) - e(2)) * 0.75;
    if ((top + (bottom - top) * 0.875) * 32.0 == value) {
      return std::array<bool, 4>{e(0) != 0.0, e(1) != 0.0, e(2) != 0.0, e(3) != 0.0};
    }
  }
  return std::nullopt;
}

// aa-facts §1.7, in its own words: left: +1 if the current pixel has the edge, +1 more if the
// neighbour has it too and no crossing edge is in the current pixel's column; right: +1 if the
// current pixel has the edge and no crossing edge in its column, +1 more if the neighbour also
// has it and no crossing edge is in the neighbour's column.
int ExpectedDelta(bool right, const std::array<bool, 4>& crossing, const std::array<bool, 4>& line) {
  const bool currentColumnClear = !crossing[1] && !crossing[3], neighbourColumnClear = !crossing[0] && !crossing[2];
  if (!line[3] || (right && !currentColumnClear)) return 0;
  return line[2] && (right ? neighbourColumnClear : currentColumnClear) ? 2 : 1;
}

TEST(PassesSmaaTables, PseudoGatherDecodesEveryEdgeCombination) {
  int decodable = 0;
  for (int value = 0; value <= 32; ++value) {
    const std::optional<std::array<bool, 4>> expected = Ungather(value);
    const std::optional<GatheredEdges> decoded = DecodePseudoGather(value);
    ASSERT_EQ(decoded.has_value(), expected.has_value()) << value;
    if (!decoded) continue;
    ++decodable;
    EXPECT_EQ((std::array<bool, 4>{decoded->upLeft, decoded->up, decoded->left, decoded->current}), *expected);
  }
  EXPECT_EQ(decodable, 16);  // every combination is a distinct multiple of 1/32
}

TEST(PassesSmaaTables, EverySearchTexEntryMatchesItsDefinition) {
  const std::span<const std::uint8_t> bytes = SearchTexBytes();
  ASSERT_EQ(bytes.size(), static_cast<std::size_t>(kSearchTexWidth) * kSearchTexHeight);
  for (int row = 0; row < kSearchTexHeight; ++row) {
    const int g = 32 - row;  // flipped, rows 17..32 of the full table kept
    for (int x = 0; x < kSearchTexWidth; ++x) {
      const bool right = x >= 33;
      const std::optional<std::array<bool, 4>> crossing = Ungather(right ? x - 33 : x), line = Ungather(g);
      const int delta = crossing && line ? ExpectedDelta(right, *crossing, *line) : 0;
      ASSERT_EQ(bytes[static_cast<std::size_t>(row) * kSearchTexWidth + x], 127 * delta) << x << " " << row;
      ASSERT_EQ(SearchTexFullValue(x, g), 127 * delta) << x << " " << row;
    }
  }
}

// --- The published tables (iryoku/smaa Textures/*.h, docs/smaa-tables.md) ---

TEST(PassesSmaaTables, SearchTexEqualsThePublishedTable) {
  // FNV-1a 64 of all 1024 published bytes; spot values (x, row) read from the published file.
  EXPECT_EQ(fmask::Fnv1a64(SearchTexBytes()), 0x21c1fcf0aa631065ull);
  constexpr std::array<std::array<int, 3>, 8> kSpots{{{0, 0, 0xfe},
                                                       {3, 0, 0x7f},
                                                       {21, 0, 0x7f},
                                                       {33, 0, 0xfe},
                                                       {0, 2, 0x00},
                                                       {0, 7, 0x7f},
                                                       {36, 7, 0x00},
                                                       {63, 15, 0x00}}};
  for (const auto& [x, row, value] : kSpots) {
    EXPECT_EQ(SearchTexBytes()[row * kSearchTexWidth + x], value) << x << " " << row;
  }
}

TEST(PassesSmaaTables, AreaTexEqualsThePublishedTable) {
  // FNV-1a 64 of all 179200 published bytes; spot texels (x, y, R, G) read from the published
  // file, covering orthogonal L, U and Z slots, diagonal stripes and the unused region.
  EXPECT_EQ(fmask::Fnv1a64(AreaTexBytes()), 0x247a58bbba65292dull);
  constexpr std::array<std::array<int, 4>, 17> kSpots{{
      {16, 0, 0x00, 0x1f},    // L up, distances (0, 0)
      {48, 0, 0x1f, 0x00},    // L down, distances (0, 0)
      {100, 0, 0x44, 0x7b},   // diagonal pattern 1
      {120, 0, 0x04, 0x7f},   // diagonal pattern 4: a zero-length candidate line
      {140, 0, 0x40, 0x7f},   // diagonal pattern 5: the same
      {16, 96, 0x00, 0x58},   // U up, stripe 1 (smoothed)
      {48, 208, 0x58, 0x00},  // U down, stripe 2 (smoothed)
      {50, 208, 0x4c, 0x00},
      {60, 100, 0x00, 0x2c},  // Z, stripe 1
      {100, 96, 0xd9, 0x00},
      {130, 100, 0x21, 0x22},
      {100, 258, 0xb2, 0x00},  // diagonal stripe 3
      {150, 260, 0x0d, 0x44},
      {120, 370, 0x00, 0xac},  // diagonal stripe 4
      {48, 530, 0x34, 0x00},   // stripe 6
      {100, 420, 0x00, 0x00},  // diagonal half of stripe 5: unused
      {130, 532, 0x00, 0x00},
  }};
  for (const auto& [x, y, r, g] : kSpots) {
    EXPECT_EQ(AreaTexel(x, y).r, r) << x << " " << y;
    EXPECT_EQ(AreaTexel(x, y).g, g) << x << " " << y;
  }
}

TEST(PassesSmaaTables, TablesAreGeneratedOnceForAllThreads) {
  auto first = std::async(std::launch::async, [] { return AreaTexBytes().data(); });
  auto second = std::async(std::launch::async, [] { return AreaTexBytes().data(); });
  EXPECT_EQ(first.get(), second.get());
  EXPECT_EQ(AreaTexBytes().size(), 2u * kAreaTexWidth * kAreaTexHeight);
}

}  // namespace
}  // namespace passes::smaa
