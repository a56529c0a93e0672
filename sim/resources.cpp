// Resource line tracking, stencil buffers and tile heat maps (see resources.h, views.h,
// heat_map.h).

#include "sim/resources.h"

#include <bit>
#include <limits>

#include "sim/heat_map.h"
#include "sim/parallel.h"
#include "sim/views.h"

namespace sim {

Resource::Resource(std::string name, std::size_t modelledBytes)
    : name_(std::move(name)), modelledBytes_(modelledBytes) {
  const std::size_t lines = (modelledBytes + kCacheLineBytes - 1) / kCacheLineBytes;
  readLines_.assign((lines + 63) / 64, 0);
  writtenLines_.assign((lines + 63) / 64, 0);
}

void Resource::BeginDispatch() {
  std::fill(readLines_.begin(), readLines_.end(), 0);
  std::fill(writtenLines_.begin(), writtenLines_.end(), 0);
}

std::uint64_t Resource::CountBits(const std::vector<std::uint64_t>& lines) {
  std::uint64_t count = 0;
  for (const std::uint64_t word : lines) count += static_cast<std::uint64_t>(std::popcount(word));
  return count;
}

namespace {
raster::DepthSurfaceConfig StencilConfig(int width, int height) {
  raster::DepthSurfaceConfig config;
  config.width = width;
  config.height = height;
  return config;
}
}  // namespace

StencilBuffer::StencilBuffer(std::string name, int width, int height)
    : Resource(std::move(name), static_cast<std::size_t>(width) * static_cast<std::size_t>(height)),
      surface_(StencilConfig(width, height), raster::MakeBuiltinPattern("centre", 1)) {}

void StencilBuffer::Clear(std::uint8_t value) { surface_.Clear(1.0f, value); }

TileHeatMap::TileHeatMap(int width, int height)
    : width_(width), height_(height), tilesX_((width + kTileSize - 1) / kTileSize),
      tilesY_((height + kTileSize - 1) / kTileSize) {
  const std::size_t tiles = static_cast<std::size_t>(tilesX_) * static_cast<std::size_t>(tilesY_);
  active_.assign(tiles, 0);
  helper_.assign(tiles, 0);
  dead_.assign(tiles, 0);
}

float TileHeatMap::Utilization(int tx, int ty) const {
  const std::uint32_t launched = Launched(tx, ty);
  if (launched == 0) return -1.0f;
  return static_cast<float>(Active(tx, ty)) / static_cast<float>(launched);
}

void StoreSrgb8(const Texture2D<glm::vec4>& linear, Texture2D<glm::vec4>& target) {
  AASIM_CHECK(target.TexelFormat() == Format::RGBA8Srgb);
  AASIM_CHECK(linear.Width() == target.Width() && linear.Height() == target.Height());
  const std::span<const glm::vec4> in = linear.Texels();
  std::uint8_t* const codes = target.Codes().data();
  const auto row = static_cast<std::size_t>(linear.Width());
  ParallelFor(static_cast<std::size_t>(linear.Height()), [&](std::size_t y) {
    for (std::size_t i = y * row; i < (y + 1) * row; ++i) EncodeCodes(Format::RGBA8Srgb, in[i], codes + 4 * i, 4);
  });
}

}  // namespace sim
