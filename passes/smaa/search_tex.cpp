// SMAA's SearchTex (see search_tex.h), from the rules of the reference generator
// (iryoku/smaa Scripts/SearchTex.py) as aa-facts §1.7 states them.

#include "passes/smaa/search_tex.h"

#include <array>
#include <vector>

namespace passes::smaa {
namespace {

// Bilinear weights of the pseudo-gather in thirty-seconds, in GatheredEdges order (aa-facts §1.4):
// (1 - 0.75) * (1 - 0.875), 0.75 * (1 - 0.875), (1 - 0.75) * 0.875, 0.75 * 0.875.
constexpr std::array<int, 4> kGatherWeights{1, 3, 7, 21};

GatheredEdges EdgesOfMask(int mask) { return {(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0, (mask & 8) != 0}; }

// Searching left ends on the pixel pair (x - 1, x): the current pixel's edge adds one pixel,
// and the left neighbour's another unless a crossing edge at the current pixel's left boundary
// (either row) stops the line there.
int DeltaLeft(GatheredEdges crossing, GatheredEdges line) {
  if (!line.current) return 0;
  return line.left && !crossing.up && !crossing.current ? 2 : 1;
}

// Searching right, a crossing edge at the left boundary of either pixel of the pair (either row)
// ends the line before that pixel.
int DeltaRight(GatheredEdges crossing, GatheredEdges line) {
  if (!line.current || crossing.up || crossing.current) return 0;
  return line.left && !crossing.upLeft && !crossing.left ? 2 : 1;
}

std::vector<std::uint8_t> GenerateSearchTex() {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(kSearchTexWidth) * kSearchTexHeight);
  for (int row = 0; row < kSearchTexHeight; ++row) {
    for (int x = 0; x < kSearchTexWidth; ++x) {
      const int fullRow = kSearchTexFullHeight - 1 - row;  // flipped; rows below kSearchTexCropTop dropped
      bytes[static_cast<std::size_t>(row) * kSearchTexWidth + x] = SearchTexFullValue(x, fullRow);
    }
  }
  return bytes;
}

}  // namespace

std::optional<GatheredEdges> DecodePseudoGather(int thirtySeconds) {
  for (int mask = 0; mask < 16; ++mask) {
    int sum = 0;
    for (int bit = 0; bit < 4; ++bit) sum += (mask >> bit & 1) * kGatherWeights[bit];
    if (sum == thirtySeconds) return EdgesOfMask(mask);
  }
  return std::nullopt;
}

int SearchDelta(SearchDirection direction, int crossing32, int line32) {
  const std::optional<GatheredEdges> crossing = DecodePseudoGather(crossing32), line = DecodePseudoGather(line32);
  if (!crossing || !line) return 0;
  return direction == SearchDirection::Left ? DeltaLeft(*crossing, *line) : DeltaRight(*crossing, *line);
}

std::uint8_t SearchTexFullValue(int x, int y) {
  const bool right = x >= kSearchTexRightX;
  const int delta = SearchDelta(right ? SearchDirection::Right : SearchDirection::Left,
                                right ? x - kSearchTexRightX : x, y);
  return static_cast<std::uint8_t>(kSearchDeltaScale * delta);
}

std::span<const std::uint8_t> SearchTexBytes() {
  static const std::vector<std::uint8_t> bytes = GenerateSearchTex();
  return bytes;
}

}  // namespace passes::smaa
