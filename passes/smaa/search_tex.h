#pragma once
// SMAA's SearchTex, generated here instead of shipped as a table (docs/smaa-tables.md): how many
// pixels the last step of a line search must add, read from one bilinear "pseudo-gather" of the
// edges texture (aa-facts §1.4, §1.7).
//
// The full table is 66 x 33: x = 32 * e.r (+ 33 for searches to the right), y = 32 * e.g, with
// e the fetched value, each a multiple of 1/32 that decodes into four edge bits. Values are
// 127 * delta, delta in {0, 1, 2}. The published texture keeps columns 0..63 and rows 17..32,
// flipped vertically (row r = full row 32 - r), which the shader's scale and bias undo.

#include <cstdint>
#include <optional>
#include <span>

namespace passes::smaa {

inline constexpr int kSearchTexWidth = 64, kSearchTexHeight = 16;  // aa-facts §1.7
inline constexpr int kSearchTexFullWidth = 66, kSearchTexFullHeight = 33;  // SEARCHTEX_SIZE, aa-facts §1.2
inline constexpr int kSearchTexCropTop = 17;  // first full row kept (Scripts/SearchTex.py crop)
inline constexpr int kSearchTexRightX = 33;   // searches to the right start here in the full table
inline constexpr int kSearchDeltaScale = 127;  // byte per pixel of delta (Scripts/SearchTex.py)

// The four texels one pseudo-gather blends (aa-facts §1.4), relative to the current pixel
// (x, y): (x - 1, y - 1), (x, y - 1), (x - 1, y), (x, y), with weights 1, 3, 7, 21 / 32.
struct GatheredEdges {
  bool upLeft = false, up = false, left = false, current = false;
};

enum class SearchDirection { Left, Right };

// The edge bits whose blend is `thirtySeconds` / 32, or nothing when no combination gives it.
std::optional<GatheredEdges> DecodePseudoGather(int thirtySeconds);

// Extra pixels (0..2) for the last step of a horizontal search, given the gathered vertical
// edges (e.r, the crossing edges) and horizontal edges (e.g, the line itself), each as
// thirty-seconds; 0 when either does not decode.
int SearchDelta(SearchDirection direction, int crossing32, int line32);

// One byte of the full 66 x 33 table.
std::uint8_t SearchTexFullValue(int x, int y);

// R8 texels, row-major from the top row.
std::span<const std::uint8_t> SearchTexBytes();

}  // namespace passes::smaa
