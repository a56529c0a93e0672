#pragma once
// SMAA's AreaTex, generated here instead of shipped as a table (docs/smaa-tables.md). For each
// shape of the edge's two ends, pair of distances to those ends and subsample offset, a texel
// holds the areas the revectorised edge cuts from the pixel on either side of the edge: what
// the blending-weight pass looks up (aa-facts §1.4, §1.6).
//
// Layout (aa-facts §1.6), 160 x 560 RG8 texels, in 7 stripes of 80 rows, one per subsample
// offset index:
//   x   0..79   orthogonal lines: 5 x 5 slots of 16 x 16 texels, slot = crossing code of each end
//               (0 none, 1 up, 3 down, 4 both; 2 unused), texel (i, j) = distances (i², j²);
//   x  80..159  diagonal lines: 4 x 4 slots of 20 x 20 texels, slot = the shader's 2-bit end code,
//               texel (i, j) = distances (i, j); only stripes 0..4, the rest of the half is zero.
// Each texel is R then G: R is the area where the revectorised line runs below the edge line,
// G where it runs above (for a horizontal edge, the weights aa-facts §1.5 calls "P towards the
// pixel above" and "the pixel above towards P").

#include <cstdint>
#include <span>

namespace passes::smaa {

inline constexpr int kAreaTexWidth = 160, kAreaTexHeight = 560;  // aa-facts §1.2/§1.6

inline constexpr int kPatternCount = 16;       // crossing-edge shapes of a line's two ends
inline constexpr int kOrthoSize = 16;          // AREATEX_MAX_DISTANCE, aa-facts §1.2
inline constexpr int kDiagSize = 20;           // AREATEX_MAX_DISTANCE_DIAG, aa-facts §1.2
inline constexpr int kStripeRows = 80;         // 5 ortho slots x 16 = 4 diagonal slots x 20
inline constexpr int kDiagHalfX = 80;          // diagonal patterns start here
inline constexpr int kOrthoOffsetCount = 7;    // aa-facts §1.6 subsample offset table
inline constexpr int kDiagOffsetCount = 5;     // aa-facts §1.6 subsample offset table

// Orthogonal pattern bits (Scripts/AreaTex.py numbering): at which end a crossing edge leaves
// the line on which side. "Down" is the current pixel's row (below a top edge), "up" the row
// above; both bits of one end = a crossing edge through it ("+").
inline constexpr int kLeftDown = 1, kRightDown = 2, kLeftUp = 4, kRightUp = 8;

// Diagonal patterns keep Scripts/AreaTex.py's numbering too: pattern p has the slot codes
// (p & 1) + 2 * (p >> 2 & 1) at the left end and 2 * (p >> 1 & 1) + (p >> 3 & 1) at the right.

struct AreaPair {
  double r = 0.0;  // below the edge line
  double g = 0.0;  // above it
};

struct Offset2 {
  double x = 0.0, y = 0.0;
};

struct Texel {
  int x = 0, y = 0;
};

// The subsample offset of stripe `index` (aa-facts §1.6).
double OrthoSubsampleOffset(int index);
Offset2 DiagSubsampleOffset(int index);

// Area for an orthogonal line of `pattern` with `left` and `right` pixels to its ends (linear
// distances), the revectorised ends raised by `offset` px.
AreaPair OrthoArea(int pattern, int left, int right, double offset);
// The same for a diagonal line (distances in pixels along the diagonal), estimated by point
// sampling as the reference does.
AreaPair DiagArea(int pattern, int left, int right, Offset2 offset);

// Where a value lives: `i` and `j` index the texels of the pattern's slot (ortho: distances i²
// and j²; diagonal: i and j).
Texel OrthoTexel(int pattern, int offsetIndex, int i, int j);
Texel DiagTexel(int pattern, int offsetIndex, int i, int j);

// How the reference stores an area: 255 * area, truncated (aa-facts §1.6).
std::uint8_t AreaToUnorm8(double area);

// RG8 texels, row-major from the top row (D3D memory order, aa-facts §1.9), R then G per texel.
// Generated on first use (thread-safe static), then cached.
std::span<const std::uint8_t> AreaTexBytes();

}  // namespace passes::smaa
