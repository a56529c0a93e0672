// The scan converter: setup -> bins -> per-bin hierarchical tile/quad/sample walk -> depth/
// stencil -> quad stream. Bins run in parallel; each owns its pixels and its counters, which
// are merged in bin order, so results do not depend on the host thread count.

#include "raster/rasterizer.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <sstream>

#include <tbb/parallel_for.h>

#include "raster/raster_error.h"

namespace raster {
namespace {

// Fixed chunking keeps setup output order independent of the scheduler.
constexpr std::size_t kSetupChunk = 4096;

void ValidateInput(const DrawInput& input) {
  if (input.indices.size() % 3 != 0) {
    throw RasterError("draw: index count " + std::to_string(input.indices.size()) +
                      " is not a multiple of 3");
  }
  for (std::size_t i = 0; i < input.clipPositions.size(); ++i) {
    const glm::vec4& p = input.clipPositions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w)) {
      std::ostringstream message;
      message << "draw: vertex " << i << " has a non-finite clip position (" << p.x << ", " << p.y
              << ", " << p.z << ", " << p.w << ")";
      throw RasterError(message.str());
    }
  }
  for (std::size_t i = 0; i < input.indices.size(); ++i) {
    if (input.indices[i] >= input.clipPositions.size()) {
      throw RasterError("draw: index " + std::to_string(input.indices[i]) + " at position " +
                        std::to_string(i) + " is out of range (" +
                        std::to_string(input.clipPositions.size()) + " vertices)");
    }
  }
}

enum class BlockClass { Empty, Partial, Full };

// The rectangle spanned by every sample position of a block of pixels, in sub-pixel units.
struct SampleExtent {
  std::int64_t x0, y0, x1, y1;
};

class BinRasterizer {
 public:
  BinRasterizer(const std::vector<TriangleSetup>& triangles, const DrawState& state,
                DepthStencilSurface& surface, const RasterOptions& options,
                std::vector<QuadFragment>& quads, std::atomic<std::size_t>& quadsCollected,
                RasterCounters& counters)
      : triangles_(triangles), state_(state), surface_(surface), pattern_(surface.Pattern()),
        options_(options), quads_(quads), quadsCollected_(quadsCollected), counters_(counters),
        width_(surface.Config().width), height_(surface.Config().height),
        samples_(surface.Config().coverageSamples) {
    int minX = kSampleOffsetMax, maxX = kSampleOffsetMin, minY = kSampleOffsetMax, maxY = kSampleOffsetMin;
    for (int p = 0; p < kQuadPixels; ++p) {
      for (int s = 0; s < samples_; ++s) {
        minX = std::min(minX, pattern_.Offset(p, s).x);
        maxX = std::max(maxX, pattern_.Offset(p, s).x);
        minY = std::min(minY, pattern_.Offset(p, s).y);
        maxY = std::max(maxY, pattern_.Offset(p, s).y);
      }
    }
    offsetMin_ = {minX, minY};
    offsetMax_ = {maxX, maxY};
  }

  void Run(const std::vector<std::uint32_t>& binTriangles, const PixelRect& bin) {
    for (std::uint32_t index : binTriangles) {
      triangleIndex_ = index;
      const TriangleSetup& tri = triangles_[index];
      const PixelRect rect{std::max(tri.bounds.x0, bin.x0), std::max(tri.bounds.y0, bin.y0),
                           std::min(tri.bounds.x1, bin.x1), std::min(tri.bounds.y1, bin.y1)};
      if (rect.Empty()) continue;
      deltasReady_ = false;
      for (int ty = rect.y0 / kTileSize; ty * kTileSize < rect.y1; ++ty) {
        for (int tx = rect.x0 / kTileSize; tx * kTileSize < rect.x1; ++tx) RasterizeTile(tri, rect, tx, ty);
      }
    }
  }

 private:
  SampleExtent Extent(int px0, int py0, int px1, int py1) const {
    return {SampleX(px0, offsetMin_.x), SampleY(py0, offsetMin_.y), SampleX(px1 - 1, offsetMax_.x),
            SampleY(py1 - 1, offsetMax_.y)};
  }

  static BlockClass Classify(const TriangleSetup& tri, const SampleExtent& e) {
    bool full = true;
    for (const EdgeFunction& edge : tri.edges) {
      const std::int64_t hi = edge.a * (edge.a > 0 ? e.x1 : e.x0) + edge.b * (edge.b > 0 ? e.y1 : e.y0) + edge.c;
      if (hi < 0) return BlockClass::Empty;
      const std::int64_t lo = edge.a * (edge.a > 0 ? e.x0 : e.x1) + edge.b * (edge.b > 0 ? e.y0 : e.y1) + edge.c;
      full &= lo >= 0;
    }
    return full ? BlockClass::Full : BlockClass::Partial;
  }

  // Depth range of the triangle over a tile: the plane at the extent's corners (rounding to
  // float is monotonic, so the corner values bound every sample's), narrowed to the vertices'.
  static std::pair<float, float> DepthRange(const TriangleSetup& tri, const SampleExtent& e) {
    const float corners[4] = {tri.depth.Evaluate(e.x0, e.y0), tri.depth.Evaluate(e.x1, e.y0),
                              tri.depth.Evaluate(e.x0, e.y1), tri.depth.Evaluate(e.x1, e.y1)};
    const auto [lo, hi] = std::minmax_element(std::begin(corners), std::end(corners));
    return {std::max(*lo, tri.zMin), std::min(*hi, tri.zMax)};
  }

  void RasterizeTile(const TriangleSetup& tri, const PixelRect& rect, int tx, int ty) {
    const int x0 = tx * kTileSize, y0 = ty * kTileSize;
    const int x1 = std::min(x0 + kTileSize, width_), y1 = std::min(y0 + kTileSize, height_);
    const SampleExtent extent = Extent(x0, y0, x1, y1);
    const BlockClass tileClass = Classify(tri, extent);
    if (tileClass == BlockClass::Empty) {
      ++counters_.tilesEmpty;
      return;
    }
    ++(tileClass == BlockClass::Full ? counters_.tilesFull : counters_.tilesPartial);
    if (surface_.HiStencilRejects(tx, ty, state_.stencil)) {
      ++counters_.tilesHiStencilRejected;
      return;
    }
    // Skipping a tile must not skip stencil depth-fail writes.
    const bool hiZAllowed = !state_.stencil.enable || state_.stencil.depthFailOp == StencilOp::Keep;
    const auto [triMin, triMax] = DepthRange(tri, extent);
    if (hiZAllowed && surface_.HiZRejects(tx, ty, state_.depth, triMin, triMax)) {
      ++counters_.tilesHiZRejected;
      return;
    }
    TileWrites writes;
    const int qy0 = std::max(y0, rect.y0 & ~1), qx0 = std::max(x0, rect.x0 & ~1);
    for (int qy = qy0; qy < std::min(y1, rect.y1); qy += 2) {
      for (int qx = qx0; qx < std::min(x1, rect.x1); qx += 2) RasterizeQuad(tri, tileClass, qx, qy, writes);
    }
    const int tilePixels = (x1 - x0) * (y1 - y0);
    surface_.FinishTriangleOnTile(tx, ty, writes.fullyWrittenPixels == tilePixels && state_.depth.writeEnable,
                                  writes.min, writes.max, writes.stencilWritten);
  }

  struct TileWrites {
    int fullyWrittenPixels = 0;
    float min = 1.0f, max = 0.0f;
    bool stencilWritten = false;
  };

  void RasterizeQuad(const TriangleSetup& tri, BlockClass tileClass, int qx, int qy, TileWrites& writes) {
    const int px1 = std::min(qx + 2, width_), py1 = std::min(qy + 2, height_);
    BlockClass quadClass = tileClass;
    if (tileClass == BlockClass::Partial) quadClass = Classify(tri, Extent(qx, qy, px1, py1));
    if (quadClass == BlockClass::Empty) {
      ++counters_.quadsEmpty;
      return;
    }
    ++(quadClass == BlockClass::Full ? counters_.quadsFull : counters_.quadsPartial);

    QuadFragment quad;
    quad.x = static_cast<std::uint16_t>(qx);
    quad.y = static_cast<std::uint16_t>(qy);
    for (int y = qy; y < py1; ++y) {
      for (int x = qx; x < px1; ++x) {
        const SampleMask mask = quadClass == BlockClass::Full ? AllSamples(samples_) : TestSamples(tri, x, y);
        quad.covered.SetPixel(QuadPixelIndex(x, y), mask);
      }
    }
    const int live = quad.covered.LivePixelCount();
    std::uint64_t* liveHistogram[] = {&counters_.quadsLive0, &counters_.quadsLive1, &counters_.quadsLive2,
                                      &counters_.quadsLive3, &counters_.quadsLive4};
    ++*liveHistogram[live];
    if (live == 0) return;
    counters_.samplesCovered += static_cast<std::uint64_t>(quad.covered.SampleCount());
    ShadeQuadDepth(tri, quad, writes);
    if (options_.collectQuads) Collect(quad);
  }

  // The count is shared by all bins: whether a draw exceeds the cap depends only on its total,
  // so the error is as deterministic as the quads themselves.
  void Collect(const QuadFragment& quad) {
    if (quadsCollected_.fetch_add(1, std::memory_order_relaxed) >= options_.maxQuads) {
      throw QuadStreamError("the draw streams more than " + std::to_string(options_.maxQuads) + " quads of " +
                            std::to_string(sizeof(QuadFragment)) + " bytes, the limit kMaxQuadStreamBytes (" +
                            std::to_string(kMaxQuadStreamBytes) + " bytes, raster/limits.h) allows: overdraw too "
                            "deep for " + std::to_string(width_) + "x" + std::to_string(height_));
    }
    quads_.push_back(quad);
  }

  void ShadeQuadDepth(const TriangleSetup& tri, QuadFragment& quad, TileWrites& writes) {
    quad.primitiveId = tri.primitiveId;
    quad.setupIndex = triangleIndex_;
    quad.frontFacing = tri.frontFacing;
    const SampleMask all = AllSamples(samples_);
    for (int p = 0; p < kQuadPixels; ++p) {
      const SampleMask covered = quad.covered.Pixel(p);
      quad.centroid[p] = Centroid(covered);
      if (covered == 0) continue;
      const int x = quad.x + (p & 1), y = quad.y + (p >> 1);
      const PixelDepthResult r = surface_.TestPixel(x, y, covered, tri, state_.depth, state_.stencil, counters_);
      quad.passed.SetPixel(p, r.depthPassed);
      quad.depthExact.SetPixel(p, r.depthExact);
      writes.fullyWrittenPixels += r.depthPassed == all;
      writes.min = std::min(writes.min, r.writtenMin);
      writes.max = std::max(writes.max, r.writtenMax);
      writes.stencilWritten |= r.stencilWritten;
    }
  }

  std::uint8_t Centroid(SampleMask covered) const {
    if (covered == 0) return kCentroidNone;
    if (covered == AllSamples(samples_)) return kCentroidAtCentre;
    for (std::uint8_t s : pattern_.CentroidPriority()) {
      if ((covered >> s) & 1u) return s;
    }
    return kCentroidNone;
  }

  // Per-sample edge offsets for each quad pixel, computed once per triangle and bin: testing a
  // sample is then three integer adds and a sign test.
  void PrepareDeltas(const TriangleSetup& tri) {
    for (int p = 0; p < kQuadPixels; ++p) {
      for (int s = 0; s < samples_; ++s) {
        const SampleOffset o = pattern_.Offset(p, s);
        for (int e = 0; e < 3; ++e) {
          deltas_[p][e][s] = (tri.edges[e].a * o.x + tri.edges[e].b * o.y) * kSubPixelPerSampleUnit;
        }
      }
    }
    deltasReady_ = true;
  }

  SampleMask TestSamples(const TriangleSetup& tri, int x, int y) {
    if (!deltasReady_) PrepareDeltas(tri);
    const std::int64_t cx = SampleX(x, 0), cy = SampleY(y, 0);
    const std::int64_t e0 = tri.edges[0].Evaluate(cx, cy);
    const std::int64_t e1 = tri.edges[1].Evaluate(cx, cy);
    const std::int64_t e2 = tri.edges[2].Evaluate(cx, cy);
    const auto& d = deltas_[QuadPixelIndex(x, y)];
    unsigned mask = 0;
    for (int s = 0; s < samples_; ++s) {
      mask |= static_cast<unsigned>(((e0 + d[0][s]) | (e1 + d[1][s]) | (e2 + d[2][s])) >= 0) << s;
    }
    counters_.samplesTested += static_cast<std::uint64_t>(samples_);
    return static_cast<SampleMask>(mask);
  }

  const std::vector<TriangleSetup>& triangles_;
  const DrawState& state_;
  DepthStencilSurface& surface_;
  const SamplePattern& pattern_;
  const RasterOptions& options_;
  std::vector<QuadFragment>& quads_;
  std::atomic<std::size_t>& quadsCollected_;
  RasterCounters& counters_;
  int width_, height_, samples_;
  SampleOffset offsetMin_, offsetMax_;
  std::uint32_t triangleIndex_ = 0;
  bool deltasReady_ = false;
  std::array<std::array<std::array<std::int64_t, kMaxCoverageSamples>, 3>, kQuadPixels> deltas_{};
};

}  // namespace

std::size_t RasterResult::QuadCount() const {
  std::size_t count = 0;
  for (const auto& bin : quadsByBin) count += bin.size();
  return count;
}

void Rasterizer::SetupAll(const DrawInput& input, const Viewport& viewport, CullMode cull) {
  const std::size_t triangleCount = input.indices.size() / 3;
  const std::size_t chunks = (triangleCount + kSetupChunk - 1) / kSetupChunk;
  if (chunkSetups_.size() < chunks) chunkSetups_.resize(chunks);
  chunkCounters_.assign(chunks, RasterCounters{});
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t chunk) {
    std::vector<TriangleSetup>& out = chunkSetups_[chunk];
    out.clear();
    const std::size_t end = std::min(triangleCount, (chunk + 1) * kSetupChunk);
    for (std::size_t t = chunk * kSetupChunk; t < end; ++t) {
      const std::array<glm::vec4, 3> clip = {input.clipPositions[input.indices[3 * t]],
                                             input.clipPositions[input.indices[3 * t + 1]],
                                             input.clipPositions[input.indices[3 * t + 2]]};
      SetupTriangle(clip, input.firstPrimitiveId + static_cast<std::uint32_t>(t), viewport, cull,
                    out, chunkCounters_[chunk]);
    }
  });
  std::vector<TriangleSetup>& all = result_.triangles;
  all.clear();
  for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
    all.insert(all.end(), chunkSetups_[chunk].begin(), chunkSetups_[chunk].end());
    result_.counters.Merge(chunkCounters_[chunk]);
  }
}

void Rasterizer::BinTriangles() {
  bins_.resize(static_cast<std::size_t>(result_.binsX) * result_.binsY);
  for (auto& bin : bins_) bin.clear();
  for (std::size_t i = 0; i < result_.triangles.size(); ++i) {
    const PixelRect& b = result_.triangles[i].bounds;
    for (int by = b.y0 / kBinSize; by <= (b.y1 - 1) / kBinSize; ++by) {
      for (int bx = b.x0 / kBinSize; bx <= (b.x1 - 1) / kBinSize; ++bx) {
        bins_[static_cast<std::size_t>(by) * result_.binsX + bx].push_back(static_cast<std::uint32_t>(i));
      }
    }
  }
}

const RasterResult& Rasterizer::Run(const DrawInput& input, const DrawState& state,
                                    DepthStencilSurface& surface, const RasterOptions& options) {
  ValidateInput(input);
  const DepthSurfaceConfig& config = surface.Config();
  result_.counters = RasterCounters{};
  SetupAll(input, Viewport{config.width, config.height}, state.cull);
  result_.binsX = (config.width + kBinSize - 1) / kBinSize;
  result_.binsY = (config.height + kBinSize - 1) / kBinSize;
  BinTriangles();
  result_.quadsByBin.resize(bins_.size());
  binCounters_.assign(bins_.size(), RasterCounters{});
  std::atomic<std::size_t> quadsCollected{0};
  tbb::parallel_for(std::size_t{0}, bins_.size(), [&](std::size_t bin) {
    const int bx = static_cast<int>(bin % static_cast<std::size_t>(result_.binsX));
    const int by = static_cast<int>(bin / static_cast<std::size_t>(result_.binsX));
    const PixelRect rect{bx * kBinSize, by * kBinSize, std::min((bx + 1) * kBinSize, config.width),
                         std::min((by + 1) * kBinSize, config.height)};
    result_.quadsByBin[bin].clear();
    BinRasterizer(result_.triangles, state, surface, options, result_.quadsByBin[bin], quadsCollected,
                  binCounters_[bin])
        .Run(bins_[bin], rect);
  });
  for (const RasterCounters& c : binCounters_) result_.counters.Merge(c);
  surface.CountTileStates(result_.counters);
  return result_;
}

RasterResult Rasterize(const DrawInput& input, const DrawState& state,
                       DepthStencilSurface& surface, const RasterOptions& options) {
  Rasterizer rasterizer;
  rasterizer.Run(input, state, surface, options);
  return rasterizer.Release();
}

std::array<double, 2> SamplePosition(int x, int y, const SamplePattern& pattern, int sample) {
  const SampleOffset o = pattern.Offset(QuadPixelIndex(x, y), sample);
  constexpr double kStepsPerPixel = 1 << kSampleGridBits;
  return {x + 0.5 + o.x / kStepsPerPixel, y + 0.5 + o.y / kStepsPerPixel};
}

std::array<double, 2> CentroidPosition(const QuadFragment& quad, int quadPixel,
                                       const SamplePattern& pattern) {
  const int x = quad.x + (quadPixel & 1), y = quad.y + (quadPixel >> 1);
  const std::uint8_t c = quad.centroid[quadPixel];
  if (c == kCentroidAtCentre || c == kCentroidNone) return {x + 0.5, y + 0.5};
  return SamplePosition(x, y, pattern, c);
}

}  // namespace raster
