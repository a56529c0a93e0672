#pragma once
// The scan converter: set up every triangle, bin set-ups into kBinSize tiles in submission
// order, rasterize bins in parallel (each bin owns its pixels, so the result is deterministic
// whatever the thread count), walk 8x8 tiles and 2x2 quads hierarchically, run depth/stencil,
// and emit the quad stream that sim/ packs into waves and fmask/ stores.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "raster/counters.h"
#include "raster/coverage_mask.h"
#include "raster/depth_stencil.h"
#include "raster/limits.h"
#include "raster/setup.h"

namespace raster {

struct DrawState {
  CullMode cull = CullMode::Back;
  DepthState depth;
  StencilState stencil;
};

struct DrawInput {
  std::span<const glm::vec4> clipPositions;  // D3D clip space, see SetupTriangle
  std::span<const std::uint32_t> indices;    // triangle list
  std::uint32_t firstPrimitiveId = 0;        // primitive id of the first triangle
};

// Centroid location per pixel (hw-facts §4.2): the pixel centre when every sample is covered,
// otherwise the first covered sample in the centroid priority order.
inline constexpr std::uint8_t kCentroidAtCentre = 0xFE;
inline constexpr std::uint8_t kCentroidNone = 0xFF;  // pixel not covered

// One 2x2 quad of one triangle: the unit the hardware ships from scan converter to shader.
struct QuadFragment {
  std::uint16_t x = 0, y = 0;  // top-left pixel, both even
  std::uint32_t primitiveId = 0;
  std::uint32_t setupIndex = 0;  // into RasterResult::triangles, for interpolation
  QuadCoverage covered;          // before depth/stencil
  QuadCoverage passed;           // after depth/stencil
  QuadCoverage depthExact;       // see PixelDepthResult::depthExact
  std::array<std::uint8_t, kQuadPixels> centroid{};  // sample index, kCentroidAtCentre/None
  bool frontFacing = true;
};

struct RasterResult {
  std::vector<TriangleSetup> triangles;
  int binsX = 0, binsY = 0;
  std::vector<std::vector<QuadFragment>> quadsByBin;  // bin-major, in rasterization order
  RasterCounters counters;

  std::size_t QuadCount() const;
};

struct RasterOptions {
  bool collectQuads = true;
  // Past this many collected quads Run throws QuadStreamError (kMaxQuadStreamBytes).
  std::size_t maxQuads = kMaxQuadStreamBytes / sizeof(QuadFragment);
};

// Owns the set-ups, bins and quad buffers and reuses them from draw to draw, so a frame loop
// does not pay for fresh memory every frame.
class Rasterizer {
 public:
  // Validates the input (index range, finite positions; RasterError names the first bad one),
  // rasterizes into `surface` and returns quads and counters (valid until the next Run).
  const RasterResult& Run(const DrawInput& input, const DrawState& state,
                          DepthStencilSurface& surface, const RasterOptions& options = {});
  // Moves the last result out; the next Run starts with empty buffers.
  RasterResult Release() { return std::move(result_); }

 private:
  void SetupAll(const DrawInput& input, const Viewport& viewport, CullMode cull);
  void BinTriangles();

  RasterResult result_;
  std::vector<std::vector<TriangleSetup>> chunkSetups_;
  std::vector<RasterCounters> chunkCounters_;
  std::vector<std::vector<std::uint32_t>> bins_;
  std::vector<RasterCounters> binCounters_;
};

// One-shot convenience: a fresh Rasterizer for a single draw.
RasterResult Rasterize(const DrawInput& input, const DrawState& state,
                       DepthStencilSurface& surface, const RasterOptions& options = {});

// Interpolation positions of a quad pixel, in pixel units (centre at +0.5).
std::array<double, 2> SamplePosition(int x, int y, const SamplePattern& pattern, int sample);
std::array<double, 2> CentroidPosition(const QuadFragment& quad, int quadPixel,
                                       const SamplePattern& pattern);

}  // namespace raster
