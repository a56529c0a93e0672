#pragma once
// The depth/stencil block: per-sample depth for the Z anchored samples, the 8x8-tile Z-plane
// compression model, hi-Z per-tile bounds, per-pixel stencil and the hi-stencil pretests
// (hw-facts §5). It owns the surface memory; the rasterizer calls it per tile and per pixel.
//
// Depth model (hw-facts §5.1, §5.2, DESIGN.md "The EQAA surface"; docs/raster.md has the rules
// in full):
//  * A tile starts Cleared (every sample = clear depth; HTILE ZMask 0).
//  * Its first depth write makes it Compressed. A written tile stores planes only (§5.1), so the
//    clear depth becomes plane 0 (z = clear depth everywhere) and every sample points at it;
//    from then on it is a plane like any other. Each coverage sample (all S, not only the Z
//    anchors) names the plane that last wrote it, so depth is known exactly at every coverage
//    sample ("up to 16x quality"). A tile holds at most maxZPlanes planes, the clear included
//    while some sample references it.
//  * A write that needs one plane more first drops planes no sample references any more (a
//    compaction); if the tile is still full it is Decompressed for good: the Z anchored samples
//    get their depth evaluated from the planes, unanchored samples lose theirs and from then on
//    test against their nearest anchor (hw-facts §5.2, SI-STATE comment). This happens inside
//    the write of one pixel, so later pixels of the same quad already see the decompressed tile.
//  * hi-Z keeps conservative min/max bounds per tile (HTILE zmin/zmax, §5.1).

#include <array>
#include <cstdint>
#include <vector>

#include "raster/coverage_mask.h"
#include "raster/sample_pattern.h"
#include "raster/setup.h"

namespace raster {

// Comparison "incoming FUNC stored" (D3D/Vulkan order of operands).
enum class CompareFunc : std::uint8_t {
  Never, Less, Equal, LessEqual, Greater, NotEqual, GreaterEqual, Always
};
enum class StencilOp : std::uint8_t {
  Keep, Zero, Replace, IncrementClamp, DecrementClamp, Invert, IncrementWrap, DecrementWrap
};

template <typename T>
constexpr bool Compare(CompareFunc func, T incoming, T stored) {
  switch (func) {
    case CompareFunc::Never: return false;
    case CompareFunc::Less: return incoming < stored;
    case CompareFunc::Equal: return incoming == stored;
    case CompareFunc::LessEqual: return incoming <= stored;
    case CompareFunc::Greater: return incoming > stored;
    case CompareFunc::NotEqual: return incoming != stored;
    case CompareFunc::GreaterEqual: return incoming >= stored;
    case CompareFunc::Always: return true;
  }
  return false;
}

struct DepthState {
  bool testEnable = true;
  bool writeEnable = true;
  CompareFunc func = CompareFunc::Less;
  bool hiZEnable = true;
};

struct StencilState {
  bool enable = false;
  CompareFunc func = CompareFunc::Always;
  std::uint8_t ref = 0;
  std::uint8_t readMask = 0xFF;
  std::uint8_t writeMask = 0xFF;
  StencilOp failOp = StencilOp::Keep;
  StencilOp depthFailOp = StencilOp::Keep;
  StencilOp passOp = StencilOp::Keep;
};

// hw-facts §5.3: two pretests per stencil surface (compare function, 8-bit value and mask);
// each 8x8 tile records whether some pixel may pass and whether some pixel may fail.
struct HiStencilPretest {
  bool enable = false;
  CompareFunc func = CompareFunc::Equal;
  std::uint8_t ref = 0;
  std::uint8_t mask = 0xFF;
};
inline constexpr int kHiStencilPretests = 2;

struct DepthSurfaceConfig {
  int width = 0;
  int height = 0;
  int coverageSamples = 1;  // S
  int depthSamples = 1;     // Z, the anchored samples 0..Z-1
  int maxZPlanes = 4;       // 0 = no plane compression (hw-facts §5.2 default 4)
  float clearDepth = 1.0f;
  std::uint8_t clearStencil = 0;
  std::array<HiStencilPretest, kHiStencilPretests> hiStencil{};
};

enum class ZTileState : std::uint8_t { Cleared, Compressed, Decompressed };

struct ZTile {
  ZTileState state = ZTileState::Cleared;
  std::uint8_t planeCount = 0;
  float zMin = 1.0f;  // conservative bounds of every sample's depth (hi-Z)
  float zMax = 1.0f;
  std::array<bool, kHiStencilPretests> stencilMayPass{};
  std::array<bool, kHiStencilPretests> stencilMayFail{};
  // A stencil write marks the hi-stencil bits stale; they are recomputed from the tile's pixels
  // when next read, the same bits an update after every write would give (a full-screen stencil
  // export would otherwise rescan its tile once per pixel).
  bool hiStencilStale = false;
  std::array<ZPlane, kMaxZPlanesPerTile> planes{};
};

// What one triangle did to one pixel's samples.
struct PixelDepthResult {
  SampleMask stencilPassed = 0;
  SampleMask depthPassed = 0;  // passed depth and stencil
  // Stencil-passing samples whose depth test was exact: anchored samples, and unanchored ones
  // while the tile is cleared or compressed. The others were tested against their nearest
  // anchor, a guess the colour block treats as "untestable" (seed 001, 2F4S example).
  SampleMask depthExact = 0;
  bool stencilWritten = false;
  float writtenMin = 1.0f, writtenMax = 0.0f;  // depths written (empty when min > max)
};

class DepthStencilSurface {
 public:
  // Throws RasterError on an impossible configuration (names the field and the legal range).
  DepthStencilSurface(const DepthSurfaceConfig& config, SamplePattern pattern);

  const DepthSurfaceConfig& Config() const { return config_; }
  const SamplePattern& Pattern() const { return pattern_; }
  int TilesX() const { return tilesX_; }
  int TilesY() const { return tilesY_; }
  const ZTile& Tile(int tx, int ty) const { return tiles_[TileIndex(tx, ty)]; }

  void Clear(float depth, std::uint8_t stencil);
  // Moves the samples (a per-frame jitter or pattern schedule) without reallocating: validated as
  // at construction, then the surface is cleared, since stored depths belong to the old positions.
  void SetPattern(SamplePattern pattern);
  void SetHiStencilPretests(const std::array<HiStencilPretest, kHiStencilPretests>& pretests);

  // The depth the DB tests coverage sample `sample` of pixel (x, y) against.
  float TestDepth(int x, int y, int sample) const;
  // The depth of anchored sample `anchor` (< Z) as a depth decompress would write it.
  float AnchorDepth(int x, int y, int anchor) const;
  // Nearest anchored sample of `sample` in the pixel's pattern (Euclidean, lower index on ties).
  int NearestAnchor(int quadPixel, int sample) const { return nearestAnchor_[quadPixel][sample]; }

  std::uint8_t Stencil(int x, int y) const { return stencil_[PixelIndex(x, y)]; }
  void SetStencil(int x, int y, std::uint8_t value);  // refreshes the tile's hi-stencil bits

  // --- Used by the rasterizer, one tile at a time (tiles of different bins never alias). ---
  bool HiZRejects(int tx, int ty, const DepthState& depth, float triMin, float triMax) const;
  bool HiStencilRejects(int tx, int ty, const StencilState& stencil);
  PixelDepthResult TestPixel(int x, int y, SampleMask covered, const TriangleSetup& tri,
                             const DepthState& depth, const StencilState& stencil,
                             RasterCounters& counters);
  // After a triangle finished a tile: update hi-Z bounds and hi-stencil bits.
  void FinishTriangleOnTile(int tx, int ty, bool wholeTileWritten, float writtenMin,
                            float writtenMax, bool stencilWritten);
  void CountTileStates(RasterCounters& counters) const;

 private:
  int PixelIndex(int x, int y) const { return y * config_.width + x; }
  int TileIndex(int tx, int ty) const { return ty * tilesX_ + tx; }
  void FindNearestAnchors();
  float StoredDepth(const ZTile& tile, int pixel, int quadPixel, int x, int y, int sample) const;
  int PlaneSlot(int tx, int ty, const ZPlane& plane, RasterCounters& counters);
  bool WriteStencil(std::uint8_t& value, StencilOp op, const StencilState& stencil);
  void WriteDepth(int x, int y, SampleMask passed, const ZPlane& plane,
                  const std::array<float, kMaxCoverageSamples>& incoming,
                  PixelDepthResult& result, RasterCounters& counters);
  template <typename Fn>
  void ForEachTilePixel(int tx, int ty, Fn&& fn) const;
  void CompactPlanes(int tx, int ty);
  void DecompressTile(int tx, int ty);
  // One bit per 8-bit stencil value.
  using StencilValues = std::array<std::uint64_t, 4>;
  void BuildPretestTables();
  StencilValues TileStencilValues(int tx, int ty) const;
  void SetHiStencilBits(ZTile& tile, const StencilValues& present) const;
  void RefreshHiStencil(int tx, int ty);

  DepthSurfaceConfig config_;
  // The values each hi-stencil pretest passes, built when the pretests are set: a tile's bits
  // then come from the set of values its pixels hold, not from a compare per pixel.
  std::array<StencilValues, kHiStencilPretests> pretestPasses_{};
  SamplePattern pattern_;
  int tilesX_ = 0, tilesY_ = 0;
  std::vector<ZTile> tiles_;
  std::vector<std::uint8_t> planeIndex_;  // [pixel * S + sample], valid in Compressed tiles
  std::vector<float> anchorDepth_;        // [pixel * Z + anchor], valid in Decompressed tiles
  std::vector<std::uint8_t> stencil_;     // [pixel]
  std::array<std::array<std::uint8_t, kMaxCoverageSamples>, kQuadPixels> nearestAnchor_{};
};

}  // namespace raster
