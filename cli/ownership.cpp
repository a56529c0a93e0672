// Sample ownership from the quad stream and its previews (see ownership.h).

#include "cli/ownership.h"

#include <algorithm>
#include <array>
#include <bit>
#include <stdexcept>
#include <string>

#include <oneapi/tbb/parallel_for.h>

#include "cli/image_io.h"
#include "raster/limits.h"

namespace cli {
namespace {

// Bin-local sample owners: bins own their pixels, so each bin is replayed on its own with a
// small buffer instead of one W*H*S array, and bins run in parallel without sharing pixels.
class BinOwners {
 public:
  BinOwners(int originX, int originY, int samples)
      : originX_(originX),
        originY_(originY),
        samples_(samples),
        owners_(static_cast<std::size_t>(raster::kBinSize * raster::kBinSize * samples),
                kNoPrimitive) {}

  void Replay(const raster::QuadFragment& quad) {
    if (quad.x < originX_ || quad.x >= originX_ + raster::kBinSize || quad.y < originY_ ||
        quad.y >= originY_ + raster::kBinSize) {
      throw std::logic_error("raster: quad at (" + std::to_string(quad.x) + ", " +
                             std::to_string(quad.y) + ") lies outside its bin");
    }
    for (int pixel = 0; pixel < raster::kQuadPixels; ++pixel) {
      const int localX = quad.x - originX_ + (pixel & 1);
      const int localY = quad.y - originY_ + (pixel >> 1);
      std::uint32_t* owners = Pixel(localX, localY);
      for (raster::SampleMask mask = quad.passed.Pixel(pixel); mask != 0; mask &= mask - 1) {
        owners[std::countr_zero(mask)] = quad.primitiveId;
      }
    }
  }

  std::uint32_t* Pixel(int localX, int localY) {
    return owners_.data() + (localY * raster::kBinSize + localX) * samples_;
  }

 private:
  int originX_, originY_, samples_;
  std::vector<std::uint32_t> owners_;
};

void SummarisePixel(const std::uint32_t* owners, int samples, std::size_t pixel,
                    PixelOwnership& out) {
  std::array<std::uint32_t, raster::kMaxCoverageSamples> sorted{};
  const auto end = std::copy_if(owners, owners + samples, sorted.begin(),
                                [](std::uint32_t id) { return id != kNoPrimitive; });
  std::sort(sorted.begin(), end);
  std::uint32_t majority = kNoPrimitive;
  int majorityRun = 0, distinct = 0;
  for (auto run = sorted.begin(); run != end;) {
    const auto runEnd = std::upper_bound(run, end, *run);
    ++distinct;
    if (runEnd - run > majorityRun) {  // strict: ties keep the lower id
      majorityRun = static_cast<int>(runEnd - run);
      majority = *run;
    }
    run = runEnd;
  }
  out.coverage[pixel] = static_cast<float>(end - sorted.begin()) / static_cast<float>(samples);
  out.majorityPrimitive[pixel] = majority;
  out.ownerCount[pixel] = static_cast<std::uint8_t>(distinct);
}

void SummariseBin(const raster::RasterResult& result, std::size_t bin, PixelOwnership& out) {
  const int originX = static_cast<int>(bin % result.binsX) * raster::kBinSize;
  const int originY = static_cast<int>(bin / result.binsX) * raster::kBinSize;
  BinOwners owners(originX, originY, out.samples);
  for (const raster::QuadFragment& quad : result.quadsByBin[bin]) owners.Replay(quad);
  const int endX = std::min(originX + raster::kBinSize, out.width);
  const int endY = std::min(originY + raster::kBinSize, out.height);
  for (int y = originY; y < endY; ++y) {
    for (int x = originX; x < endX; ++x) {
      const std::size_t pixel = static_cast<std::size_t>(y) * out.width + x;
      SummarisePixel(owners.Pixel(x - originX, y - originY), out.samples, pixel, out);
    }
  }
}

}  // namespace

// Wellons' "lowbias32" integer mixer. +1: the mixer maps 0 to 0, which would paint primitive 0
// like the background.
std::uint32_t PrimitiveHash(std::uint32_t primitiveId) {
  std::uint32_t v = primitiveId + 1u;
  v ^= v >> 16;
  v *= 0x7feb352du;
  v ^= v >> 15;
  v *= 0x846ca68bu;
  v ^= v >> 16;
  return v;
}

std::size_t PixelOwnership::PixelsCovered() const {
  return static_cast<std::size_t>(
      std::count_if(coverage.begin(), coverage.end(), [](float c) { return c > 0.0f; }));
}

std::size_t PixelOwnership::PixelsPartial() const {
  return static_cast<std::size_t>(std::count_if(coverage.begin(), coverage.end(),
                                                [](float c) { return c > 0.0f && c < 1.0f; }));
}

PixelOwnership ComputeOwnership(const raster::RasterResult& result, int width, int height,
                                int samples) {
  if (result.quadsByBin.size() != static_cast<std::size_t>(result.binsX) * result.binsY ||
      result.binsX * raster::kBinSize < width || result.binsY * raster::kBinSize < height) {
    throw std::logic_error("raster: the bin grid does not cover the viewport");
  }
  PixelOwnership out;
  out.width = width;
  out.height = height;
  out.samples = samples;
  const std::size_t pixelCount = static_cast<std::size_t>(width) * height;
  out.coverage.resize(pixelCount);
  out.majorityPrimitive.resize(pixelCount);
  out.ownerCount.resize(pixelCount);
  tbb::parallel_for(std::size_t{0}, result.quadsByBin.size(),
                    [&](std::size_t bin) { SummariseBin(result, bin, out); });
  return out;
}

std::vector<std::uint8_t> CoverageImage(const PixelOwnership& ownership) {
  std::vector<std::uint8_t> image(ownership.coverage.size());
  std::transform(ownership.coverage.begin(), ownership.coverage.end(), image.begin(),
                 [](float coverage) { return EncodeSrgb8(coverage); });
  return image;
}

std::vector<std::uint8_t> PrimitiveImage(const PixelOwnership& ownership) {
  constexpr float kGrey = 0.25f;
  std::vector<std::uint8_t> image(ownership.coverage.size() * 3, 0);
  for (std::size_t pixel = 0; pixel < ownership.coverage.size(); ++pixel) {
    const int owners = ownership.ownerCount[pixel];
    if (owners == 0) continue;
    const std::uint32_t hash = PrimitiveHash(ownership.majorityPrimitive[pixel]);
    const float towardsGrey = static_cast<float>(owners - 1) / static_cast<float>(owners);
    for (int channel = 0; channel < 3; ++channel) {
      // Channels from 0.15 up keep every primitive visibly brighter than the background.
      const float colour =
          0.15f + 0.85f * static_cast<float>((hash >> (8 * channel)) & 0xFFu) / 255.0f;
      image[pixel * 3 + channel] = EncodeSrgb8(colour + (kGrey - colour) * towardsGrey);
    }
  }
  return image;
}

}  // namespace cli
