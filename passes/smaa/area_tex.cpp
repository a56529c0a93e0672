// SMAA's AreaTex (see area_tex.h), from the rules of the reference generator
// (iryoku/smaa Scripts/AreaTex.py) as aa-facts §1.6 states them. The bytes match the published
// Textures/AreaTex.h only if every area is computed in double precision with the script's order
// of operations (a rounding difference moves a truncated byte, and a diagonal sample that sits on
// the line flips in or out), so expressions below keep that order, and passes/CMakeLists.txt
// builds this file without fused multiply-adds.

#include "passes/smaa/area_tex.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <vector>

namespace passes::smaa {
namespace {

// aa-facts §1.6 (Scripts/AreaTex.py SUBSAMPLE_OFFSETS_ORTHO, SUBSAMPLE_OFFSETS_DIAG).
constexpr std::array<double, kOrthoOffsetCount> kOrthoOffsets{0.0, -0.25, 0.25, -0.125, 0.125, -0.375, 0.375};
constexpr std::array<Offset2, kDiagOffsetCount> kDiagOffsets{
    {{0.0, 0.0}, {0.25, -0.25}, {-0.25, 0.25}, {0.125, -0.125}, {-0.125, 0.125}}};

// U shapes shorter than this are smoothed towards a rounder profile (aa-facts §1.6,
// SMOOTH_MAX_DISTANCE).
constexpr double kSmoothMaxDistance = 32.0;
// A diagonal area is the fraction of a kDiagSamples² grid over the pixel, edges and corners
// included, on one side of the line (Scripts/AreaTex.py SAMPLES_DIAG).
constexpr int kDiagSamples = 30;
// A segment end this close to the edge line counts as on it: the pixel is one trapezoid, not two
// triangles (Scripts/AreaTex.py).
constexpr double kOnLine = 1e-4;

struct Point {
  double x = 0.0, y = 0.0;
};

AreaPair operator+(AreaPair a, AreaPair b) { return {a.r + b.r, a.g + b.g}; }
AreaPair Half(AreaPair a) { return {a.r / 2.0, a.g / 2.0}; }

// --- Orthogonal lines ---

// What one end of an orthogonal line does: no crossing edge, one leaving down or up, or one
// running through it.
enum class End { None, Down, Up, Through };

End EndOf(bool down, bool up) {
  if (down && up) return End::Through;
  return down ? End::Down : up ? End::Up : End::None;
}

End Opposite(End end) { return end == End::Down ? End::Up : End::Down; }

// Height of the revectorised line at an end (aa-facts §1.6: 0.5 + o above, o - 0.5 below),
// computed as the script does.
double EndHeight(End end, double offset) {
  const double up = 0.5 + offset;
  return end == End::Up ? up : up - 1.0;
}

// The two triangles of a pixel whose segment crosses the edge line inside it: R takes the one
// below, G the one above. A triangle whose corner lies outside the segment's x range is dropped.
AreaPair CrossingArea(Point a, Point b, double y1, double y2) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double crossing = -a.y * dx / dy + a.x;
  double whole = 0.0;
  const double fraction = std::modf(crossing, &whole);
  const double first = crossing > a.x ? y1 * fraction / 2.0 : 0.0;
  const double second = crossing < b.x ? y2 * (1.0 - fraction) / 2.0 : 0.0;
  return y1 < 0.0 ? AreaPair{std::abs(first), std::abs(second)} : AreaPair{std::abs(second), std::abs(first)};
}

// Area between the line through a and b and the edge line over the pixel [x, x + 1], if the
// pixel overlaps the segment's x range (the line is extended over the rest of the pixel).
AreaPair PixelArea(Point a, Point b, int x) {
  const double x1 = x, x2 = x + 1.0;
  if (!((x1 >= a.x && x1 < b.x) || (x2 > a.x && x2 <= b.x))) return {};
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double y1 = a.y + dy * (x1 - a.x) / dx;
  const double y2 = a.y + dy * (x2 - a.x) / dx;
  if (std::signbit(y1) != std::signbit(y2) && std::abs(y1) >= kOnLine && std::abs(y2) >= kOnLine) {
    return CrossingArea(a, b, y1, y2);
  }
  const double mean = (y1 + y2) / 2.0;
  return mean < 0.0 ? AreaPair{std::abs(mean), 0.0} : AreaPair{0.0, std::abs(mean)};
}

// Short U shapes get sqrt(2a)/2 instead of a, blended back to a by length 32 (aa-facts §1.6).
AreaPair Smooth(int length, AreaPair area) {
  const double p = std::clamp(length / kSmoothMaxDistance, 0.0, 1.0);
  auto one = [p](double a) {
    const double rounder = std::sqrt(a * 2.0) * 0.5;
    return rounder + (a - rounder) * p;
  };
  return {one(area.r), one(area.g)};
}

// The revectorised line of an orthogonal edge: from the left end's height at x = 0 through the
// edge line at the middle to the right end's height at x = length.
struct OrthoLine {
  Point start, middle, end;
};

OrthoLine MakeLine(End left, End right, int length, double offset) {
  return {{0.0, EndHeight(left, offset)}, {length / 2.0, 0.0}, {static_cast<double>(length), EndHeight(right, offset)}};
}

// An L shape: only the half nearer to the crossing edge is filtered, so that it meets the
// unfiltered line without crossing edges (aa-facts §1.6).
AreaPair LShape(End left, End right, int leftDistance, int rightDistance, double offset) {
  const OrthoLine line = MakeLine(left, right, leftDistance + rightDistance + 1, offset);
  if (left != End::None && leftDistance <= rightDistance) return PixelArea(line.start, line.middle, leftDistance);
  if (right != End::None && leftDistance >= rightDistance) return PixelArea(line.middle, line.end, leftDistance);
  return {};
}

// A U shape: the two halves, each smoothed (aa-facts §1.6).
AreaPair UShape(End ends, int leftDistance, int rightDistance, double offset) {
  const int length = leftDistance + rightDistance + 1;
  const OrthoLine line = MakeLine(ends, ends, length, offset);
  return Smooth(length, PixelArea(line.start, line.middle, leftDistance)) +
         Smooth(length, PixelArea(line.middle, line.end, leftDistance));
}

// A Z shape: one segment end to end. With an offset it is averaged with its two halves, so that
// it meets the L shapes its own pixels see at a shorter search distance (aa-facts §1.6).
AreaPair ZShape(End left, End right, int leftDistance, int rightDistance, double offset) {
  const OrthoLine line = MakeLine(left, right, leftDistance + rightDistance + 1, offset);
  const AreaPair whole = PixelArea(line.start, line.end, leftDistance);
  if (offset == 0.0) return whole;
  const AreaPair halves =
      PixelArea(line.start, line.middle, leftDistance) + PixelArea(line.middle, line.end, leftDistance);
  return Half(whole + halves);
}

// --- Diagonal lines ---

// The diagonal line's ends are not known exactly (which pattern continues it is not known), so
// most patterns average two candidate lines ("black magic", aa-facts §1.6). A line runs from
// `start` to `end` + (d, d), d = the line's length; Scripts/AreaTex.py areadiag lists them.
struct DiagLine {
  Point start, end;
};
struct DiagCandidates {
  std::array<DiagLine, 2> lines;
  int count = 0;
};

constexpr Point k00{0.0, 0.0}, k10{1.0, 0.0}, k11{1.0, 1.0};
constexpr std::array<DiagCandidates, kPatternCount> kDiagLines{{
    {{{{k11, k11}, {k10, k10}}}, 2},  // 0: no crossing edges
    {{{{k10, k00}, {k10, k10}}}, 2},  // 1
    {{{{k00, k10}, {k10, k10}}}, 2},  // 2
    {{{{k10, k10}, {}}}, 1},          // 3
    {{{{k11, k00}, {k11, k10}}}, 2},  // 4
    {{{{k11, k00}, {k10, k10}}}, 2},  // 5
    {{{{k11, k10}, {}}}, 1},          // 6
    {{{{k11, k10}, {k10, k10}}}, 2},  // 7
    {{{{k00, k11}, {k10, k11}}}, 2},  // 8
    {{{{k10, k11}, {}}}, 1},          // 9
    {{{{k00, k11}, {k10, k10}}}, 2},  // 10
    {{{{k10, k11}, {k10, k10}}}, 2},  // 11
    {{{{k11, k11}, {}}}, 1},          // 12
    {{{{k11, k11}, {k10, k11}}}, 2},  // 13
    {{{{k11, k11}, {k11, k10}}}, 2},  // 14
    {{{{k11, k11}, {k10, k10}}}, 2},  // 15
}};

// Slot codes of a diagonal pattern's two ends (Scripts/AreaTex.py edgesdiag).
int DiagLeftCode(int pattern) { return (pattern & 1) + 2 * (pattern >> 2 & 1); }
int DiagRightCode(int pattern) { return 2 * (pattern >> 1 & 1) + (pattern >> 3 & 1); }

// Fraction of the sample grid over the unit pixel at `corner` strictly on the side of a -> b that
// its normal (b.y - a.y, a.x - b.x) points to.
// A line of zero length (patterns 4 and 5 at distances (0, 0) without offset) has every sample
// inside, as in the reference: the published table holds that.
double SampledCoverage(Point a, Point b, Point corner) {
  if (a.x == b.x && a.y == b.y) return 1.0;
  const double midX = (a.x + b.x) / 2.0, midY = (a.y + b.y) / 2.0;
  const double nx = b.y - a.y, ny = a.x - b.x;
  int inside = 0;
  for (int i = 0; i < kDiagSamples; ++i) {
    const double x = corner.x + i / static_cast<double>(kDiagSamples - 1);
    for (int j = 0; j < kDiagSamples; ++j) {
      const double y = corner.y + j / static_cast<double>(kDiagSamples - 1);
      inside += nx * (x - midX) + ny * (y - midY) > 0.0;
    }
  }
  return inside / static_cast<double>(kDiagSamples * kDiagSamples);
}

// One candidate line: R = the pixel's part outside, G = its opposite pixel's part inside. The
// subsample offset moves only ends that have a crossing edge.
AreaPair DiagLineArea(DiagLine line, int pattern, int left, int length, Offset2 offset) {
  Point a = line.start, b{line.end.x + length, line.end.y + length};
  if (DiagLeftCode(pattern) > 0) a = {a.x + offset.x, a.y + offset.y};
  if (DiagRightCode(pattern) > 0) b = {b.x + offset.x, b.y + offset.y};
  const double own = SampledCoverage(a, b, {1.0 + left, 0.0 + left});
  const double opposite = SampledCoverage(a, b, {1.0 + left, 1.0 + left});
  return {1.0 - own, opposite};
}

// --- The texture ---

int OrthoSlot(End end) {
  constexpr std::array<int, 4> kSlots{0, 3, 1, 4};  // None, Down, Up, Through: aa-facts §1.6
  return kSlots[static_cast<int>(end)];
}

End LeftEnd(int pattern) { return EndOf(pattern & kLeftDown, pattern & kLeftUp); }
End RightEnd(int pattern) { return EndOf(pattern & kRightDown, pattern & kRightUp); }

void PutTexel(std::vector<std::uint8_t>& bytes, Texel texel, AreaPair area) {
  const std::size_t at = 2 * (static_cast<std::size_t>(texel.y) * kAreaTexWidth + texel.x);
  bytes[at] = AreaToUnorm8(area.r);
  bytes[at + 1] = AreaToUnorm8(area.g);
}

std::vector<std::uint8_t> GenerateAreaTex() {
  std::vector<std::uint8_t> bytes(2 * static_cast<std::size_t>(kAreaTexWidth) * kAreaTexHeight, 0);
  for (int pattern = 0; pattern < kPatternCount; ++pattern) {
    for (int stripe = 0; stripe < kOrthoOffsetCount; ++stripe) {
      for (int i = 0; i < kOrthoSize; ++i) {
        for (int j = 0; j < kOrthoSize; ++j) {
          PutTexel(bytes, OrthoTexel(pattern, stripe, i, j), OrthoArea(pattern, i * i, j * j, kOrthoOffsets[stripe]));
        }
      }
    }
    for (int stripe = 0; stripe < kDiagOffsetCount; ++stripe) {
      for (int i = 0; i < kDiagSize; ++i) {
        for (int j = 0; j < kDiagSize; ++j) {
          PutTexel(bytes, DiagTexel(pattern, stripe, i, j), DiagArea(pattern, i, j, kDiagOffsets[stripe]));
        }
      }
    }
  }
  return bytes;
}

}  // namespace

double OrthoSubsampleOffset(int index) { return kOrthoOffsets.at(static_cast<std::size_t>(index)); }
Offset2 DiagSubsampleOffset(int index) { return kDiagOffsets.at(static_cast<std::size_t>(index)); }

AreaPair OrthoArea(int pattern, int left, int right, double offset) {
  End leftEnd = LeftEnd(pattern), rightEnd = RightEnd(pattern);
  if (leftEnd == End::Through && rightEnd == End::Through) return {};
  if (leftEnd == End::None || rightEnd == End::None) {
    // One crossing edge through an end, and nothing at the other, is no shape: unfiltered.
    if (leftEnd == End::Through || rightEnd == End::Through) return {};
    return LShape(leftEnd, rightEnd, left, right, offset);
  }
  if (leftEnd == End::Through || rightEnd == End::Through) {
    // The line leaves the crossing edge on the side away from the other end's: the whole
    // segment, never averaged with its halves.
    if (leftEnd == End::Through) leftEnd = Opposite(rightEnd);
    if (rightEnd == End::Through) rightEnd = Opposite(leftEnd);
    const OrthoLine line = MakeLine(leftEnd, rightEnd, left + right + 1, offset);
    return PixelArea(line.start, line.end, left);
  }
  if (leftEnd == rightEnd) return UShape(leftEnd, left, right, offset);
  return ZShape(leftEnd, rightEnd, left, right, offset);
}

AreaPair DiagArea(int pattern, int left, int right, Offset2 offset) {
  const DiagCandidates& candidates = kDiagLines.at(static_cast<std::size_t>(pattern));
  const int length = left + right + 1;
  const AreaPair first = DiagLineArea(candidates.lines[0], pattern, left, length, offset);
  if (candidates.count == 1) return first;
  return Half(first + DiagLineArea(candidates.lines[1], pattern, left, length, offset));
}

Texel OrthoTexel(int pattern, int offsetIndex, int i, int j) {
  return {kOrthoSize * OrthoSlot(LeftEnd(pattern)) + i,
          kStripeRows * offsetIndex + kOrthoSize * OrthoSlot(RightEnd(pattern)) + j};
}

Texel DiagTexel(int pattern, int offsetIndex, int i, int j) {
  return {kDiagHalfX + kDiagSize * DiagLeftCode(pattern) + i,
          kStripeRows * offsetIndex + kDiagSize * DiagRightCode(pattern) + j};
}

std::uint8_t AreaToUnorm8(double area) {
  assert(area >= 0.0 && area <= 1.0);
  return static_cast<std::uint8_t>(static_cast<int>(255.0 * area));
}

std::span<const std::uint8_t> AreaTexBytes() {
  static const std::vector<std::uint8_t> bytes = GenerateAreaTex();
  return bytes;
}

}  // namespace passes::smaa
