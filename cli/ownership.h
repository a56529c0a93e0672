#pragma once
// Which primitive each coverage sample shows after depth testing, reconstructed from the quad
// stream, and the two PNG previews made from it. Depth writes are on in `aasim raster`, so the
// last quad whose `passed` mask holds a sample is the visible writer of that sample.

#include <cstdint>
#include <vector>

#include "raster/rasterizer.h"

namespace cli {

inline constexpr std::uint32_t kNoPrimitive = 0xFFFFFFFFu;

struct PixelOwnership {
  int width = 0;
  int height = 0;
  int samples = 0;
  // Per pixel, row-major.
  std::vector<float> coverage;                   // samples with an owner / samples
  std::vector<std::uint32_t> majorityPrimitive;  // owns the most samples (lower id on ties)
  std::vector<std::uint8_t> ownerCount;          // distinct owning primitives

  std::size_t PixelsCovered() const;  // coverage > 0
  std::size_t PixelsPartial() const;  // 0 < coverage < 1, the anti-aliasing edge pixels
};

// Replays each bin's quads in rasterization order. Throws std::logic_error when a quad lies
// outside its bin, which would break raster's ownership invariant.
PixelOwnership ComputeOwnership(const raster::RasterResult& result, int width, int height,
                                int samples);

// A well-mixed hash of a primitive id, so neighbouring ids get unrelated preview colours.
std::uint32_t PrimitiveHash(std::uint32_t primitiveId);

// 8-bit grey, sRGB-encoded coverage fraction: white = covered, black = background.
std::vector<std::uint8_t> CoverageImage(const PixelOwnership& ownership);
// 8-bit RGB: a colour hashed from the majority primitive, pulled towards grey by the number of
// distinct owners ((n - 1) / n of the way), black background.
std::vector<std::uint8_t> PrimitiveImage(const PixelOwnership& ownership);

}  // namespace cli
