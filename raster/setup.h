#pragma once
// Triangle setup: homogeneous clipping (near, far and a guard band), viewport transform,
// snapping to kSubPixelBits, face culling, zero-area rejection and integer edge functions with
// the top-left fill rule (DESIGN.md "Conventions"; style.md habit 7).
//
// Coordinates after setup are integers in 1/256 px ("sub-pixel units"), origin at the top-left
// corner of the viewport, +y down. Sample s of pixel (x, y) sits at
//   X = x * 256 + 128 + offset.x * 16,  Y = y * 256 + 128 + offset.y * 16.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "raster/counters.h"
#include "raster/limits.h"

namespace raster {

enum class CullMode : std::uint8_t { None, Back, Front };

// E(X, Y) = a*X + b*Y + c. A sample is inside the edge when E >= 0; c already includes the
// fill-rule bias (-1 for edges that are neither top nor left), so a sample exactly on a shared
// edge is inside exactly one of the two triangles.
struct EdgeFunction {
  std::int64_t a = 0;
  std::int64_t b = 0;
  std::int64_t c = 0;
  bool topLeft = false;
  constexpr std::int64_t Evaluate(std::int64_t x, std::int64_t y) const { return a * x + b * y + c; }
  // The edge function without the fill-rule bias, for barycentrics.
  constexpr std::int64_t EvaluateUnbiased(std::int64_t x, std::int64_t y) const {
    return Evaluate(x, y) + (topLeft ? 0 : 1);
  }
};

// z(X, Y) = a*X + b*Y + c over sub-pixel coordinates, z in [0, 1] (D3D depth range). Every
// depth aasim stores or tests is this function evaluated in exactly this way, so a Z plane kept
// by a compressed tile and the per-sample depth are bit-identical.
struct ZPlane {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
  float Evaluate(std::int64_t x, std::int64_t y) const {
    return static_cast<float>(a * static_cast<double>(x) + b * static_cast<double>(y) + c);
  }
  friend bool operator==(const ZPlane&, const ZPlane&) = default;
};

struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  bool Empty() const { return x0 >= x1 || y0 >= y1; }
};

struct Viewport {
  int width = 0;
  int height = 0;
};

struct TriangleSetup {
  std::array<EdgeFunction, 3> edges;  // edge i is opposite vertex i
  ZPlane depth;
  float zMin = 0.0f, zMax = 0.0f;  // over the vertices
  PixelRect bounds;                 // pixels any of whose samples may be covered, in viewport
  std::int64_t doubleArea = 0;                               // > 0 (winding normalised)
  std::array<float, 3> invW{};
  // Barycentrics of each set-up vertex in the submitted triangle (identity unless clipped).
  std::array<std::array<float, 3>, 3> sourceBarycentrics{};
  std::uint32_t primitiveId = 0;
  bool frontFacing = true;
};

constexpr std::int64_t SampleX(int pixelX, int offsetX) {
  return pixelX * kSubPixelScale + kSubPixelScale / 2 + offsetX * kSubPixelPerSampleUnit;
}
constexpr std::int64_t SampleY(int pixelY, int offsetY) { return SampleX(pixelY, offsetY); }

// Clips, culls and sets up one triangle given in clip space (D3D conventions: x, y in [-w, w],
// z in [0, w], y up in NDC; counter-clockwise in NDC is front-facing, as in glTF). Appends 0..5
// set-ups to `out` (a clipped triangle becomes a fan) and counts into `counters`.
void SetupTriangle(const std::array<glm::vec4, 3>& clip, std::uint32_t primitiveId,
                   const Viewport& viewport, CullMode cull, std::vector<TriangleSetup>& out,
                   RasterCounters& counters);

// Perspective-correct barycentrics of the submitted triangle at a point in pixel units
// (pixel centres at +0.5). Sums to 1.
std::array<float, 3> PerspectiveBarycentrics(const TriangleSetup& tri, double pixelX,
                                             double pixelY);

}  // namespace raster
