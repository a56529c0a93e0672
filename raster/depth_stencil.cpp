// Depth/stencil block: Z-plane tiles, anchored per-sample depth, hi-Z bounds and hi-stencil
// pretests (model described in depth_stencil.h).

#include "raster/depth_stencil.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

#include "raster/raster_error.h"

namespace raster {
namespace {

bool IsPowerOfTwoUpTo(int value, int limit) {
  return value >= 1 && value <= limit && std::has_single_bit(static_cast<unsigned>(value));
}

void ValidateConfig(const DepthSurfaceConfig& c, const SamplePattern& pattern) {
  auto fail = [](const std::string& what) { throw RasterError("depth surface: " + what); };
  if (c.width < 1 || c.width > kMaxDimension || c.height < 1 || c.height > kMaxDimension) {
    fail("size " + std::to_string(c.width) + "x" + std::to_string(c.height) +
         " is outside 1.." + std::to_string(kMaxDimension) + " per axis");
  }
  if (!IsPowerOfTwoUpTo(c.coverageSamples, kMaxCoverageSamples)) {
    fail(std::to_string(c.coverageSamples) + " coverage samples; legal: 1, 2, 4, 8, 16");
  }
  if (!IsPowerOfTwoUpTo(c.depthSamples, kMaxDepthSamples)) {
    fail(std::to_string(c.depthSamples) + " depth samples; legal: 1, 2, 4, 8");
  }
  if (c.depthSamples > c.coverageSamples) {
    fail(std::to_string(c.depthSamples) + " depth samples exceed " +
         std::to_string(c.coverageSamples) + " coverage samples (need S >= Z)");
  }
  if (pattern.Count() != c.coverageSamples) {
    fail("pattern '" + pattern.Name() + "' has " + std::to_string(pattern.Count()) +
         " samples but the surface has " + std::to_string(c.coverageSamples));
  }
  if (c.maxZPlanes < 0 || c.maxZPlanes > kMaxZPlanesPerTile) {
    fail("max Z planes " + std::to_string(c.maxZPlanes) + " is outside 0.." +
         std::to_string(kMaxZPlanesPerTile));
  }
  if (!(c.clearDepth >= 0.0f && c.clearDepth <= 1.0f)) fail("clear depth must be in [0, 1]");
}

int DistanceSquared(SampleOffset a, SampleOffset b) {
  return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
}

std::uint8_t ApplyStencilOp(StencilOp op, std::uint8_t value, std::uint8_t ref) {
  switch (op) {
    case StencilOp::Keep: return value;
    case StencilOp::Zero: return 0;
    case StencilOp::Replace: return ref;
    case StencilOp::IncrementClamp: return value == 0xFF ? value : static_cast<std::uint8_t>(value + 1);
    case StencilOp::DecrementClamp: return value == 0 ? value : static_cast<std::uint8_t>(value - 1);
    case StencilOp::Invert: return static_cast<std::uint8_t>(~value);
    case StencilOp::IncrementWrap: return static_cast<std::uint8_t>(value + 1);
    case StencilOp::DecrementWrap: return static_cast<std::uint8_t>(value - 1);
  }
  return value;
}

bool StencilPasses(CompareFunc func, std::uint8_t ref, std::uint8_t mask, std::uint8_t value) {
  return Compare<int>(func, ref & mask, value & mask);
}

void AddStencilValue(std::array<std::uint64_t, 4>& values, std::uint8_t value) {
  values[value >> 6] |= std::uint64_t{1} << (value & 63u);
}

}  // namespace

template <typename Fn>
void DepthStencilSurface::ForEachTilePixel(int tx, int ty, Fn&& fn) const {
  for (int y = ty * kTileSize; y < std::min((ty + 1) * kTileSize, config_.height); ++y) {
    for (int x = tx * kTileSize; x < std::min((tx + 1) * kTileSize, config_.width); ++x) fn(x, y);
  }
}

DepthStencilSurface::DepthStencilSurface(const DepthSurfaceConfig& config, SamplePattern pattern)
    : config_(config), pattern_(std::move(pattern)) {
  ValidateConfig(config_, pattern_);
  tilesX_ = (config_.width + kTileSize - 1) / kTileSize;
  tilesY_ = (config_.height + kTileSize - 1) / kTileSize;
  const std::size_t pixels = static_cast<std::size_t>(config_.width) * config_.height;
  tiles_.resize(static_cast<std::size_t>(tilesX_) * tilesY_);
  planeIndex_.resize(pixels * config_.coverageSamples);
  anchorDepth_.resize(pixels * config_.depthSamples);
  stencil_.resize(pixels);
  FindNearestAnchors();
  BuildPretestTables();
  Clear(config_.clearDepth, config_.clearStencil);
}

void DepthStencilSurface::FindNearestAnchors() {
  for (int p = 0; p < kQuadPixels; ++p) {
    for (int s = 0; s < config_.coverageSamples; ++s) {
      int best = 0;
      for (int a = 0; a < config_.depthSamples; ++a) {
        const SampleOffset here = pattern_.Offset(p, s);
        if (DistanceSquared(here, pattern_.Offset(p, a)) < DistanceSquared(here, pattern_.Offset(p, best))) best = a;
      }
      nearestAnchor_[p][s] = static_cast<std::uint8_t>(s < config_.depthSamples ? s : best);
    }
  }
}

void DepthStencilSurface::SetPattern(SamplePattern pattern) {
  ValidateConfig(config_, pattern);
  pattern_ = std::move(pattern);
  FindNearestAnchors();
  Clear(config_.clearDepth, config_.clearStencil);
}

void DepthStencilSurface::Clear(float depth, std::uint8_t stencil) {
  config_.clearDepth = depth;
  config_.clearStencil = stencil;
  for (ZTile& tile : tiles_) {
    tile.state = ZTileState::Cleared;
    tile.planeCount = 0;
    tile.zMin = tile.zMax = depth;
  }
  // Plane indices and anchored depth are not touched: a Cleared tile reads as the clear depth
  // without them, and they are (re)initialised when the tile first leaves that state.
  std::fill(stencil_.begin(), stencil_.end(), stencil);
  StencilValues cleared{};
  AddStencilValue(cleared, stencil);
  for (ZTile& tile : tiles_) SetHiStencilBits(tile, cleared);
}

void DepthStencilSurface::BuildPretestTables() {
  for (std::size_t k = 0; k < kHiStencilPretests; ++k) {
    const HiStencilPretest& pretest = config_.hiStencil[k];
    StencilValues& passes = pretestPasses_[k];
    passes = {};
    for (int value = 0; value < 256; ++value) {
      const auto code = static_cast<std::uint8_t>(value);
      if (StencilPasses(pretest.func, pretest.ref, pretest.mask, code)) AddStencilValue(passes, code);
    }
  }
}

void DepthStencilSurface::SetHiStencilPretests(
    const std::array<HiStencilPretest, kHiStencilPretests>& pretests) {
  config_.hiStencil = pretests;
  BuildPretestTables();
  for (int ty = 0; ty < tilesY_; ++ty) {
    for (int tx = 0; tx < tilesX_; ++tx) RefreshHiStencil(tx, ty);
  }
}

float DepthStencilSurface::StoredDepth(const ZTile& tile, int pixel, int quadPixel, int x, int y,
                                       int sample) const {
  if (tile.state == ZTileState::Cleared) return config_.clearDepth;
  if (tile.state == ZTileState::Decompressed) {
    return anchorDepth_[pixel * config_.depthSamples + nearestAnchor_[quadPixel][sample]];
  }
  const std::uint8_t plane = planeIndex_[pixel * config_.coverageSamples + sample];
  const SampleOffset offset = pattern_.Offset(quadPixel, sample);
  return tile.planes[plane].Evaluate(SampleX(x, offset.x), SampleY(y, offset.y));
}

float DepthStencilSurface::TestDepth(int x, int y, int sample) const {
  return StoredDepth(tiles_[TileIndex(x / kTileSize, y / kTileSize)], PixelIndex(x, y),
                     QuadPixelIndex(x, y), x, y, sample);
}

float DepthStencilSurface::AnchorDepth(int x, int y, int anchor) const {
  return TestDepth(x, y, anchor);
}

void DepthStencilSurface::SetStencil(int x, int y, std::uint8_t value) {
  stencil_[PixelIndex(x, y)] = value;
  tiles_[TileIndex(x / kTileSize, y / kTileSize)].hiStencilStale = true;
}

bool DepthStencilSurface::HiZRejects(int tx, int ty, const DepthState& depth, float triMin,
                                     float triMax) const {
  if (!depth.testEnable || !depth.hiZEnable) return false;
  const ZTile& tile = tiles_[TileIndex(tx, ty)];
  switch (depth.func) {
    case CompareFunc::Never: return true;
    case CompareFunc::Less: return triMin >= tile.zMax;
    case CompareFunc::LessEqual: return triMin > tile.zMax;
    case CompareFunc::Greater: return triMax <= tile.zMin;
    case CompareFunc::GreaterEqual: return triMax < tile.zMin;
    case CompareFunc::Equal: return triMin > tile.zMax || triMax < tile.zMin;
    case CompareFunc::NotEqual:
    case CompareFunc::Always: return false;
  }
  return false;
}

// A tile may be skipped only when a pretest matching the draw's stencil test says no pixel can
// pass, and failing has no side effect (otherwise the skipped pixels would miss a stencil write).
bool DepthStencilSurface::HiStencilRejects(int tx, int ty, const StencilState& stencil) {
  if (!stencil.enable || stencil.failOp != StencilOp::Keep) return false;
  const ZTile& tile = tiles_[TileIndex(tx, ty)];
  if (tile.hiStencilStale) RefreshHiStencil(tx, ty);
  for (int k = 0; k < kHiStencilPretests; ++k) {
    const HiStencilPretest& pretest = config_.hiStencil[k];
    if (pretest.enable && pretest.func == stencil.func && pretest.ref == stencil.ref &&
        pretest.mask == stencil.readMask && !tile.stencilMayPass[k]) {
      return true;
    }
  }
  return false;
}

DepthStencilSurface::StencilValues DepthStencilSurface::TileStencilValues(int tx, int ty) const {
  static_assert(kTileSize == 8, "a tile row is compared as one 8-byte word");
  StencilValues present{};
  const int x0 = tx * kTileSize, y0 = ty * kTileSize;
  // Most tiles hold one value (a cleared surface; a pass's stencil mask away from its edges), so
  // a whole tile's rows are first compared 8 bytes at a time with its first pixel's.
  if (x0 + kTileSize <= config_.width) {
    const std::uint8_t first = stencil_[static_cast<std::size_t>(PixelIndex(x0, y0))];
    const std::uint64_t everyByte = first * std::uint64_t{0x0101010101010101};
    bool uniform = true;
    for (int y = y0; y < std::min(y0 + kTileSize, config_.height) && uniform; ++y) {
      std::uint64_t row = 0;
      std::memcpy(&row, &stencil_[static_cast<std::size_t>(PixelIndex(x0, y))], sizeof(row));
      uniform = row == everyByte;
    }
    if (uniform) {
      AddStencilValue(present, first);
      return present;
    }
  }
  ForEachTilePixel(tx, ty, [&](int x, int y) {
    AddStencilValue(present, stencil_[static_cast<std::size_t>(PixelIndex(x, y))]);
  });
  return present;
}

// Some pixel may pass a pretest when a value the tile holds passes it, and may fail when a value
// it holds fails it.
void DepthStencilSurface::SetHiStencilBits(ZTile& tile, const StencilValues& present) const {
  for (std::size_t k = 0; k < kHiStencilPretests; ++k) {
    bool mayPass = false, mayFail = false;
    for (std::size_t word = 0; word < present.size(); ++word) {
      mayPass |= (present[word] & pretestPasses_[k][word]) != 0;
      mayFail |= (present[word] & ~pretestPasses_[k][word]) != 0;
    }
    tile.stencilMayPass[k] = mayPass;
    tile.stencilMayFail[k] = mayFail;
  }
  tile.hiStencilStale = false;
}

void DepthStencilSurface::RefreshHiStencil(int tx, int ty) {
  SetHiStencilBits(tiles_[TileIndex(tx, ty)], TileStencilValues(tx, ty));
}

PixelDepthResult DepthStencilSurface::TestPixel(int x, int y, SampleMask covered,
                                                const TriangleSetup& tri, const DepthState& depth,
                                                const StencilState& stencil,
                                                RasterCounters& counters) {
  PixelDepthResult result;
  const int pixel = PixelIndex(x, y);
  std::uint8_t& stencilValue = stencil_[pixel];
  if (stencil.enable && !StencilPasses(stencil.func, stencil.ref, stencil.readMask, stencilValue)) {
    result.stencilWritten = WriteStencil(stencilValue, stencil.failOp, stencil);
    return result;
  }
  result.stencilPassed = covered;
  counters.samplesStencilPassed += static_cast<std::uint64_t>(std::popcount(covered));

  const int quadPixel = QuadPixelIndex(x, y);
  const int tileIndex = TileIndex(x / kTileSize, y / kTileSize);
  std::array<float, kMaxCoverageSamples> incoming{};
  SampleMask passed = 0;
  for (SampleMask rest = covered; rest != 0; rest &= static_cast<SampleMask>(rest - 1)) {
    const int s = std::countr_zero(rest);
    const SampleOffset offset = pattern_.Offset(quadPixel, s);
    incoming[s] = tri.depth.Evaluate(SampleX(x, offset.x), SampleY(y, offset.y));
    const bool pass = !depth.testEnable ||
                      Compare(depth.func, incoming[s], StoredDepth(tiles_[tileIndex], pixel, quadPixel, x, y, s));
    passed |= static_cast<SampleMask>(pass << s);
  }
  result.depthPassed = passed;
  const bool guessed = depth.testEnable && tiles_[tileIndex].state == ZTileState::Decompressed;
  result.depthExact = guessed ? static_cast<SampleMask>(covered & AllSamples(config_.depthSamples)) : covered;
  counters.samplesDepthPassed += static_cast<std::uint64_t>(std::popcount(passed));
  if (stencil.enable) {
    result.stencilWritten =
        WriteStencil(stencilValue, passed ? stencil.passOp : stencil.depthFailOp, stencil);
  }
  if (depth.writeEnable && passed) WriteDepth(x, y, passed, tri.depth, incoming, result, counters);
  return result;
}

bool DepthStencilSurface::WriteStencil(std::uint8_t& value, StencilOp op,
                                       const StencilState& stencil) {
  const std::uint8_t updated = ApplyStencilOp(op, value, stencil.ref);
  const auto merged = static_cast<std::uint8_t>((value & ~stencil.writeMask) | (updated & stencil.writeMask));
  const bool changed = merged != value;
  value = merged;
  return changed;
}

void DepthStencilSurface::WriteDepth(int x, int y, SampleMask passed, const ZPlane& plane,
                                     const std::array<float, kMaxCoverageSamples>& incoming,
                                     PixelDepthResult& result, RasterCounters& counters) {
  const int tx = x / kTileSize, ty = y / kTileSize;
  ZTile& tile = tiles_[TileIndex(tx, ty)];
  const int pixel = PixelIndex(x, y);
  if (tile.state != ZTileState::Decompressed) {
    const int slot = PlaneSlot(tx, ty, plane, counters);
    if (slot >= 0) {
      for (SampleMask rest = passed; rest != 0; rest &= static_cast<SampleMask>(rest - 1)) {
        const int s = std::countr_zero(rest);
        planeIndex_[pixel * config_.coverageSamples + s] = static_cast<std::uint8_t>(slot);
        result.writtenMin = std::min(result.writtenMin, incoming[s]);
        result.writtenMax = std::max(result.writtenMax, incoming[s]);
      }
      return;
    }
  }
  // Decompressed: only anchored samples have storage; unanchored ones keep testing against
  // their nearest anchor.
  const SampleMask anchored = passed & AllSamples(config_.depthSamples);
  for (SampleMask rest = anchored; rest != 0; rest &= static_cast<SampleMask>(rest - 1)) {
    const int s = std::countr_zero(rest);
    anchorDepth_[pixel * config_.depthSamples + s] = incoming[s];
    result.writtenMin = std::min(result.writtenMin, incoming[s]);
    result.writtenMax = std::max(result.writtenMax, incoming[s]);
  }
}

// The tile's slot holding `plane`, allocating one if needed; -1 once the tile had to be
// decompressed because the plane limit was reached.
int DepthStencilSurface::PlaneSlot(int tx, int ty, const ZPlane& plane, RasterCounters& counters) {
  ZTile& tile = tiles_[TileIndex(tx, ty)];
  if (tile.state == ZTileState::Cleared) {
    // hw-facts §5.1: ZMask 0 marks a wholly cleared tile, and a written tile stores planes only,
    // so from the first write on the clear depth is a plane like any other: it takes slot 0,
    // every sample points at it, and it counts against the limit while a sample still does.
    if (config_.maxZPlanes == 0) {
      DecompressTile(tx, ty);
      ++counters.zPlaneDecompressions;
      return -1;
    }
    tile.planes[0] = ZPlane{0.0, 0.0, static_cast<double>(config_.clearDepth)};
    tile.planeCount = 1;
    tile.state = ZTileState::Compressed;
    ForEachTilePixel(tx, ty, [&](int x, int y) {
      std::fill_n(&planeIndex_[PixelIndex(x, y) * config_.coverageSamples], config_.coverageSamples, 0);
    });
  }
  for (int i = tile.planeCount - 1; i >= 0; --i) {
    if (tile.planes[i] == plane) return i;
  }
  if (tile.planeCount >= config_.maxZPlanes) {
    const int before = tile.planeCount;
    CompactPlanes(tx, ty);
    if (tile.planeCount < before) ++counters.zPlaneCompactions;
  }
  if (tile.planeCount >= config_.maxZPlanes) {
    DecompressTile(tx, ty);
    ++counters.zPlaneDecompressions;
    return -1;
  }
  tile.planes[tile.planeCount] = plane;
  return tile.planeCount++;
}

// Drops every plane no sample of the tile references, keeping the order of the others. The
// samples the current write is about to overwrite still reference their old planes here.
void DepthStencilSurface::CompactPlanes(int tx, int ty) {
  ZTile& tile = tiles_[TileIndex(tx, ty)];
  constexpr std::uint8_t kUnreferenced = 0xFF;
  std::array<std::uint8_t, kMaxZPlanesPerTile> remap;
  remap.fill(kUnreferenced);
  ForEachTilePixel(tx, ty, [&](int x, int y) {
    const std::uint8_t* idx = &planeIndex_[PixelIndex(x, y) * config_.coverageSamples];
    for (int s = 0; s < config_.coverageSamples; ++s) remap[idx[s]] = 0;
  });
  std::uint8_t kept = 0;
  for (int i = 0; i < tile.planeCount; ++i) {
    if (remap[i] == kUnreferenced) continue;
    remap[i] = kept;
    tile.planes[kept++] = tile.planes[i];
  }
  tile.planeCount = kept;
  ForEachTilePixel(tx, ty, [&](int x, int y) {
    std::uint8_t* idx = &planeIndex_[PixelIndex(x, y) * config_.coverageSamples];
    for (int s = 0; s < config_.coverageSamples; ++s) idx[s] = remap[idx[s]];
  });
}

void DepthStencilSurface::DecompressTile(int tx, int ty) {
  ZTile& tile = tiles_[TileIndex(tx, ty)];
  ForEachTilePixel(tx, ty, [&](int x, int y) {
    const int pixel = PixelIndex(x, y);
    for (int a = 0; a < config_.depthSamples; ++a) {
      anchorDepth_[pixel * config_.depthSamples + a] =
          StoredDepth(tile, pixel, QuadPixelIndex(x, y), x, y, a);
    }
  });
  tile.state = ZTileState::Decompressed;
  tile.planeCount = 0;
}

void DepthStencilSurface::FinishTriangleOnTile(int tx, int ty, bool wholeTileWritten,
                                               float writtenMin, float writtenMax,
                                               bool stencilWritten) {
  ZTile& tile = tiles_[TileIndex(tx, ty)];
  if (wholeTileWritten) {
    tile.zMin = writtenMin;
    tile.zMax = writtenMax;
  } else if (writtenMin <= writtenMax) {
    tile.zMin = std::min(tile.zMin, writtenMin);
    tile.zMax = std::max(tile.zMax, writtenMax);
  }
  if (stencilWritten) tile.hiStencilStale = true;
}

void DepthStencilSurface::CountTileStates(RasterCounters& counters) const {
  for (const ZTile& tile : tiles_) {
    switch (tile.state) {
      case ZTileState::Cleared: ++counters.zTilesClearedAtEnd; break;
      case ZTileState::Compressed: ++counters.zTilesCompressedAtEnd; break;
      case ZTileState::Decompressed: ++counters.zTilesDecompressedAtEnd; break;
    }
  }
}

}  // namespace raster
