#pragma once
// Filmic SMAA's edge detection (seed 000, Morphological): morphological edge suppression in
// place of SMAA's local contrast adaptation, then one work item per pixel (its higher-contrast
// boundary) and the neighbour agreement that keeps two items of one direction from writing the
// same pixel. The seed gives the ideas, not the formulas; the readings here are documented in
// docs/filmic-smaa.md next to the seed's words.
//
// Everything works on a 6x6 window of gamma-space luma around the pixel P (dx, dy in -3..2), the
// footprint of P's decision and of its four neighbours' (their edges' patterns reach 2 px left
// and up and 1 px right and down of each). The pixel form fills it with texture loads, the
// compute form from its LDS tile; the arithmetic below is the same for both.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace passes::filmic_smaa {

// SMAA's luma (aa-facts §1.3) in the reference's evaluation order (aa-facts §1.9), the same
// expression smaa::EdgeDetection uses.
inline float Luma(const glm::vec3& rgb) { return rgb.x * 0.2126f + (rgb.y * 0.7152f + rgb.z * 0.0722f); }

// The window's extent around P.
inline constexpr int kWindowMin = -3, kWindowMax = 2;
inline constexpr int kWindowSide = kWindowMax - kWindowMin + 1;

struct LumaWindow {
  std::array<float, kWindowSide * kWindowSide> luma{};
  float& At(int dx, int dy) { return luma[static_cast<std::size_t>((dy - kWindowMin) * kWindowSide + dx - kWindowMin)]; }
  float At(int dx, int dy) const {
    return luma[static_cast<std::size_t>((dy - kWindowMin) * kWindowSide + dx - kWindowMin)];
  }
};

// A unit edge named by the pixel whose left or top side it is, relative to the pixel that owns
// the edge under test.
enum class Side : std::uint8_t { Left, Top };
struct UnitEdge {
  Side side;
  std::int8_t dx, dy;
};
// A two-edge line: the edge under test plus `other` (a passing pattern), or two other edges (a
// pattern through the same endpoints that does not pass through it).
struct NonPassing {
  UnitEdge a, b;
};

// The patterns of P's left edge e (between L = (-1, 0) and P; endpoints at the top and bottom
// corners of P's left side). "Passing" lines contain e: e continued up or down, and the L-corners
// at either endpoint turning into P's or L's row boundary. "Non-passing" lines run through the
// same neighbourhood without e: the parallel lines one column either side (2 edges, over the
// rows above-and-here and here-and-below), and the horizontal lines crossing e's endpoints.
// The top edge's patterns are the transpose (Transposed below).
inline constexpr std::array<UnitEdge, 6> kPassing = {{
    {Side::Left, 0, -1},  // continued up
    {Side::Left, 0, 1},   // continued down
    {Side::Top, 0, 0},    // corner at the top endpoint, into P's top side
    {Side::Top, -1, 0},   // corner at the top endpoint, into L's top side
    {Side::Top, 0, 1},    // corner at the bottom endpoint, into P's bottom side
    {Side::Top, -1, 1},   // corner at the bottom endpoint, into L's bottom side
}};
inline constexpr std::array<NonPassing, 6> kNonPassing = {{
    {{Side::Left, -1, -1}, {Side::Left, -1, 0}},  // L's left side continued up
    {{Side::Left, -1, 0}, {Side::Left, -1, 1}},   // L's left side continued down
    {{Side::Left, 1, -1}, {Side::Left, 1, 0}},    // P's right side continued up
    {{Side::Left, 1, 0}, {Side::Left, 1, 1}},     // P's right side continued down
    {{Side::Top, -1, 0}, {Side::Top, 0, 0}},      // the horizontal line through the top endpoint
    {{Side::Top, -1, 1}, {Side::Top, 0, 1}},      // the horizontal line through the bottom endpoint
}};

constexpr UnitEdge Transposed(UnitEdge edge) {
  return {edge.side == Side::Left ? Side::Top : Side::Left, edge.dy, edge.dx};
}

// Seed 000, Morphological: "suppress edge if a pattern that does not pass through current edge
// wins"; aa-facts §2: kept only if the passing score beats max(2 * threshold, non-passing score).
// The factor 2 is that summary's; the seed names no constants.
inline constexpr float kPassingScoreThresholdFactor = 2.0f;

// Luma differences across unit edges of the window, relative to the pixel at (ox, oy).
class EdgeScores {
 public:
  EdgeScores(const LumaWindow& window, float threshold) : w_(window), threshold_(threshold) {}

  // |luma difference| across the unit edge (the neighbour first, as SMAA's |L - Lleft| is
  // symmetric in float).
  float Delta(int ox, int oy, UnitEdge edge) const {
    const int x = ox + edge.dx, y = oy + edge.dy;
    return edge.side == Side::Left ? std::fabs(w_.At(x, y) - w_.At(x - 1, y))
                                   : std::fabs(w_.At(x, y) - w_.At(x, y - 1));
  }

  // The contrast of the left (side Left) or top edge of pixel (ox, oy) if it survives the
  // threshold (SMAA's step: equality counts) and the suppression, else 0.
  float Kept(int ox, int oy, Side side) const {
    const auto oriented = [side](UnitEdge edge) { return side == Side::Left ? edge : Transposed(edge); };
    const float delta = Delta(ox, oy, oriented({Side::Left, 0, 0}));
    if (!(delta >= threshold_)) return 0.0f;
    float passing = 0.0f;
    for (const UnitEdge other : kPassing) passing = std::max(passing, delta + Delta(ox, oy, oriented(other)));
    float nonPassing = 0.0f;
    for (const NonPassing line : kNonPassing) {
      nonPassing = std::max(nonPassing, Delta(ox, oy, oriented(line.a)) + Delta(ox, oy, oriented(line.b)));
    }
    return passing >= std::max(kPassingScoreThresholdFactor * threshold_, nonPassing) ? delta : 0.0f;
  }

 private:
  const LumaWindow& w_;
  float threshold_;
};

// What one pixel decides: its kept edges (SMAA's RG edges, read by every pixel's searches) and
// the work item it runs, if any.
enum class Item : std::uint8_t { None = 0, Vertical = 1, Horizontal = 2 };

struct PixelEdges {
  glm::vec2 edges{0.0f};  // (left, top), 0 or 1
  Item item = Item::None;
  bool lostAgreement = false;  // chose a boundary, lost it to a neighbour
};

// The boundary a pixel would search (seed 000: "each pixel searches top or left boundaries only
// (the one with higher contrast)"; ties go to the left edge) and its contrast.
struct Choice {
  Item item;
  float contrast;
};
inline Choice ChoiceOf(const EdgeScores& scores, int ox, int oy) {
  const float left = scores.Kept(ox, oy, Side::Left), top = scores.Kept(ox, oy, Side::Top);
  if (left > 0.0f && left >= top) return {Item::Vertical, left};
  if (top > 0.0f) return {Item::Horizontal, top};
  return {Item::None, 0.0f};
}

// Neighbour agreement (seed 000: "checking neighbor decision — I've more contrast, I win!"): a
// vertical item writes its pixel and the one on its left, so two vertical items side by side
// would both write one pixel. P keeps its item only if it beats both neighbours along the
// blending axis that chose the same direction: strictly more contrast than the one after it,
// at least as much as the one before it. Of two adjacent choosers exactly one test fails, so no
// two items of one direction are adjacent along their axis and no pixel is written twice in a
// dispatch (tests/passes_filmic_smaa_test.cpp checks it on random images).
inline bool WinsAgainstNeighbours(const EdgeScores& scores, const Choice& mine, glm::ivec2 before, glm::ivec2 after) {
  const Choice b = ChoiceOf(scores, before.x, before.y), a = ChoiceOf(scores, after.x, after.y);
  if (b.item == mine.item && b.contrast >= mine.contrast) return false;
  if (a.item == mine.item && a.contrast > mine.contrast) return false;
  return true;
}

// P's candidate edges from the centre, left and top lumas alone: SMAA's early exit (its discard),
// taken before the rest of the window is read.
inline bool MayHaveEdge(float centre, float left, float top, float threshold) {
  return std::fabs(centre - left) >= threshold || std::fabs(centre - top) >= threshold;
}

inline PixelEdges Decide(const LumaWindow& window, float threshold) {
  const EdgeScores scores(window, threshold);
  PixelEdges result;
  result.edges = {scores.Kept(0, 0, Side::Left) > 0.0f ? 1.0f : 0.0f,
                  scores.Kept(0, 0, Side::Top) > 0.0f ? 1.0f : 0.0f};
  const Choice mine = ChoiceOf(scores, 0, 0);
  if (mine.item == Item::Vertical && WinsAgainstNeighbours(scores, mine, {-1, 0}, {1, 0})) result.item = mine.item;
  if (mine.item == Item::Horizontal && WinsAgainstNeighbours(scores, mine, {0, -1}, {0, 1})) result.item = mine.item;
  result.lostAgreement = mine.item != Item::None && result.item == Item::None;
  return result;
}

}  // namespace passes::filmic_smaa
