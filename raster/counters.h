#pragma once
// Counters of the raster layer, counted where the work happens (setup, tile walk, depth unit)
// and merged in a fixed order. The field table below is the only list of names: merge, JSON,
// CSV and the summary are generated from it (style.md habits 14-15, anti-pattern 1).

#include <cstdint>

namespace raster {

struct RasterCounters {
  // Triangle setup.
  std::uint64_t trianglesIn = 0;
  std::uint64_t trianglesClipped = 0;      // crossed a clip plane and were cut
  std::uint64_t trianglesOutsideView = 0;  // clipped away entirely
  std::uint64_t trianglesCulled = 0;       // back/front-face culling
  std::uint64_t trianglesZeroArea = 0;     // zero area after snapping
  std::uint64_t trianglesRasterized = 0;   // setups (a clipped triangle may make several)
  // 8x8 tiles, per triangle that touches them.
  std::uint64_t tilesEmpty = 0;
  std::uint64_t tilesPartial = 0;
  std::uint64_t tilesFull = 0;
  std::uint64_t tilesHiZRejected = 0;
  std::uint64_t tilesHiStencilRejected = 0;
  // 2x2 quads inside non-empty tiles.
  std::uint64_t quadsEmpty = 0;
  std::uint64_t quadsPartial = 0;
  std::uint64_t quadsFull = 0;
  // Quads with any tested coverage, by live (covered) pixel count before depth/stencil.
  std::uint64_t quadsLive0 = 0;
  std::uint64_t quadsLive1 = 0;
  std::uint64_t quadsLive2 = 0;
  std::uint64_t quadsLive3 = 0;
  std::uint64_t quadsLive4 = 0;
  // Samples.
  std::uint64_t samplesTested = 0;   // per-sample edge tests (full blocks skip them)
  std::uint64_t samplesCovered = 0;
  std::uint64_t samplesStencilPassed = 0;
  std::uint64_t samplesDepthPassed = 0;
  // Depth compression (hw-facts §5.2).
  std::uint64_t zPlaneDecompressions = 0;  // tiles that exceeded the plane limit
  std::uint64_t zPlaneCompactions = 0;     // unreferenced planes dropped to make room
  std::uint64_t zTilesClearedAtEnd = 0;
  std::uint64_t zTilesCompressedAtEnd = 0;
  std::uint64_t zTilesDecompressedAtEnd = 0;

  void Merge(const RasterCounters& other);
  friend bool operator==(const RasterCounters&, const RasterCounters&) = default;
};

struct RasterCounterField {
  const char* name;  // "category/name", stable: JSON keys and CSV columns
  std::uint64_t RasterCounters::*member;
  const char* description;
};

inline constexpr RasterCounterField kRasterCounterFields[] = {
    {"triangles/in", &RasterCounters::trianglesIn, "triangles submitted"},
    {"triangles/clipped", &RasterCounters::trianglesClipped, "cut by a clip plane"},
    {"triangles/outside_view", &RasterCounters::trianglesOutsideView, "clipped away entirely"},
    {"triangles/culled", &RasterCounters::trianglesCulled, "removed by face culling"},
    {"triangles/zero_area", &RasterCounters::trianglesZeroArea, "zero area after snapping"},
    {"triangles/rasterized", &RasterCounters::trianglesRasterized, "set-ups rasterized"},
    {"tiles/empty", &RasterCounters::tilesEmpty, "8x8 tiles in a triangle's bounds it misses"},
    {"tiles/partial", &RasterCounters::tilesPartial, "8x8 tiles partly covered"},
    {"tiles/full", &RasterCounters::tilesFull, "8x8 tiles fully covered"},
    {"tiles/hiz_rejected", &RasterCounters::tilesHiZRejected, "tiles rejected by hi-Z"},
    {"tiles/histencil_rejected", &RasterCounters::tilesHiStencilRejected,
     "tiles rejected by a hi-stencil pretest"},
    {"quads/empty", &RasterCounters::quadsEmpty, "quads of partial tiles the triangle misses"},
    {"quads/partial", &RasterCounters::quadsPartial, "quads needing per-sample tests"},
    {"quads/full", &RasterCounters::quadsFull, "quads covered at every sample"},
    {"quads/live0", &RasterCounters::quadsLive0, "partial quads with no covered sample"},
    {"quads/live1", &RasterCounters::quadsLive1, "quads with 1 covered pixel"},
    {"quads/live2", &RasterCounters::quadsLive2, "quads with 2 covered pixels"},
    {"quads/live3", &RasterCounters::quadsLive3, "quads with 3 covered pixels"},
    {"quads/live4", &RasterCounters::quadsLive4, "quads with 4 covered pixels"},
    {"samples/tested", &RasterCounters::samplesTested, "per-sample edge tests"},
    {"samples/covered", &RasterCounters::samplesCovered, "covered samples"},
    {"samples/stencil_passed", &RasterCounters::samplesStencilPassed,
     "covered samples passing stencil"},
    {"samples/depth_passed", &RasterCounters::samplesDepthPassed,
     "covered samples passing depth and stencil"},
    {"zplanes/decompressions", &RasterCounters::zPlaneDecompressions,
     "tiles decompressed on exceeding the plane limit"},
    {"zplanes/compactions", &RasterCounters::zPlaneCompactions,
     "unreferenced planes dropped to make room"},
    {"zplanes/tiles_cleared", &RasterCounters::zTilesClearedAtEnd, "tiles still cleared at end"},
    {"zplanes/tiles_compressed", &RasterCounters::zTilesCompressedAtEnd,
     "tiles holding Z planes at end"},
    {"zplanes/tiles_decompressed", &RasterCounters::zTilesDecompressedAtEnd,
     "tiles holding per-sample depth at end"},
};

inline void RasterCounters::Merge(const RasterCounters& other) {
  for (const auto& field : kRasterCounterFields) this->*field.member += other.*field.member;
}

}  // namespace raster
