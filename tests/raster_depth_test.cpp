// Depth and stencil: Z-plane compression against exact per-sample depth, the plane limit,
// compaction, nearest-anchor fallback, hi-Z, stencil and hi-stencil, clipping, barycentrics
// and determinism across host thread counts.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <tuple>
#include <vector>
#include <initializer_list>
#include <string>
#include <utility>

#include <tbb/global_control.h>

#include "raster/sample_pattern.h"
#include "raster_test_util.h"

namespace raster {
namespace {

using testing::Mesh;
using testing::RandomSoup;
using testing::Random;
using testing::ScreenToClip;

DepthStencilSurface MakeDepthSurface(int width, int height, int samples, int depthSamples, int maxZPlanes,
                                const char* pattern = "standard") {
  DepthSurfaceConfig config;
  config.width = width;
  config.height = height;
  config.coverageSamples = samples;
  config.depthSamples = depthSamples;
  config.maxZPlanes = maxZPlanes;
  return DepthStencilSurface(config, MakeBuiltinPattern(pattern, samples));
}

DrawState CullNone() {
  DrawState state;
  state.cull = CullMode::None;
  return state;
}

// While tiles stay compressed, the depth the DB tests every coverage sample against (anchored
// or not) is exactly the per-sample depth of a brute-force S-sample depth buffer.
TEST(ZPlanes, CompressedDepthEqualsExactPerSampleDepth) {
  constexpr int kWidth = 40, kHeight = 32;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    Random rng(seed);
    const Mesh mesh = RandomSoup(rng, 6, kWidth, kHeight, 30.0);
    for (auto [s, z] : {std::pair{16, 4}, {8, 2}, {4, 1}}) {
      DepthStencilSurface surface = MakeDepthSurface(kWidth, kHeight, s, z, kMaxZPlanesPerTile, "eqaa");
      const RasterResult result = Rasterize(mesh.Input(), CullNone(), surface);
      ASSERT_EQ(result.counters.zPlaneDecompressions, 0u);
      const auto reference = testing::ReferenceRasterize(mesh.Input(), CullNone(), surface.Pattern(), kWidth, kHeight);
      for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
          for (int k = 0; k < s; ++k) {
            ASSERT_EQ(surface.TestDepth(x, y, k), reference.depth[(y * kWidth + x) * s + k]) << x << "," << y << " sample " << k;
          }
        }
      }
    }
  }
}

// With every sample anchored (S == Z), compression is invisible: the anchored depths and the
// depth-test results are bit-identical whether tiles keep planes or hold per-sample depth.
TEST(ZPlanes, CompressionIsInvisibleWhenEverySampleIsAnchored) {
  constexpr int kWidth = 64, kHeight = 48;
  Random rng(11);
  const Mesh mesh = RandomSoup(rng, 60, kWidth, kHeight, 10.0);
  DepthStencilSurface planes = MakeDepthSurface(kWidth, kHeight, 8, 8, 4);
  DepthStencilSurface perSample = MakeDepthSurface(kWidth, kHeight, 8, 8, 0);
  const RasterResult a = Rasterize(mesh.Input(), CullNone(), planes);
  const RasterResult b = Rasterize(mesh.Input(), CullNone(), perSample);
  EXPECT_GT(a.counters.zPlaneDecompressions, 0u);
  EXPECT_GT(a.counters.zTilesCompressedAtEnd, 0u);
  EXPECT_EQ(b.counters.zTilesCompressedAtEnd, 0u);
  EXPECT_EQ(a.counters.samplesDepthPassed, b.counters.samplesDepthPassed);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      for (int k = 0; k < 8; ++k) ASSERT_EQ(planes.AnchorDepth(x, y, k), perSample.AnchorDepth(x, y, k));
    }
  }
}

// A fan of P triangles covering one tile, each with its own plane. While the k-th triangle
// makes its first write, the pixels of wedges k..P still hold the clear depth, so the tile
// references the clear plus k - 1 planes and needs one more: it needs P + 1 slots at the last
// triangle (hw-facts §5.1: once written, the clear is a plane like any other). It therefore
// decompresses exactly once with a limit of P and stays compressed with P + 1; afterwards
// unanchored samples read their anchor.
TEST(ZPlanes, PlaneLimitDecompresses) {
  constexpr int kSize = 8;
  for (int planes : {3, 6, 15}) {
    Mesh mesh;
    mesh.clip.push_back(ScreenToClip(4.0, 4.0, 0.5, kSize, kSize));
    for (int k = 0; k < planes; ++k) {
      const double angle = 2.0 * 3.14159265358979 * k / planes;
      mesh.clip.push_back(ScreenToClip(4.0 + 20.0 * std::cos(angle), 4.0 + 20.0 * std::sin(angle), 0.5 + 0.01 * k, kSize, kSize));
      mesh.indices.insert(mesh.indices.end(), {0u, static_cast<std::uint32_t>(1 + k), static_cast<std::uint32_t>(1 + (k + 1) % planes)});
    }
    for (int maxPlanes : {planes, planes + 1}) {
      DepthStencilSurface surface = MakeDepthSurface(kSize, kSize, 8, 2, maxPlanes);
      const RasterResult result = Rasterize(mesh.Input(), CullNone(), surface);
      const bool overflow = maxPlanes == planes;
      EXPECT_EQ(result.counters.zPlaneDecompressions, overflow ? 1u : 0u) << "limit " << maxPlanes;
      EXPECT_EQ(result.counters.zPlaneCompactions, 0u) << "limit " << maxPlanes;
      EXPECT_EQ(surface.Tile(0, 0).state, overflow ? ZTileState::Decompressed : ZTileState::Compressed);
      if (!overflow) {
        // The clear stays in the table, unreferenced, until a compaction needs its slot.
        EXPECT_EQ(surface.Tile(0, 0).planeCount, planes + 1);
        continue;
      }
      for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
          for (int s = 0; s < 8; ++s) {
            EXPECT_EQ(surface.TestDepth(x, y, s), surface.AnchorDepth(x, y, surface.NearestAnchor(QuadPixelIndex(x, y), s)));
          }
        }
      }
    }
  }
}

// Flat triangles over one 8x8 tile, derived by hand: "left" covers x < 4 (every sample of
// columns 0..3; the standard 4x offsets never reach a pixel edge), "right" covers x > 4, "all"
// the whole tile. Every vertex stays inside the guard band, so nothing is clipped.
Mesh FlatTriangles(std::initializer_list<std::pair<const char*, double>> triangles) {
  Mesh mesh;
  for (const auto& [region, z] : triangles) {
    const std::string name = region;
    std::array<std::array<double, 2>, 3> v{};
    if (name == "left") v = {{{4.0, -20.0}, {4.0, 28.0}, {-22.0, 4.0}}};
    if (name == "right") v = {{{4.0, -20.0}, {30.0, 4.0}, {4.0, 28.0}}};
    if (name == "all") v = {{{-20.0, -4.0}, {30.0, -4.0}, {5.0, 30.0}}};
    for (const auto& [x, y] : v) {
      mesh.indices.push_back(static_cast<std::uint32_t>(mesh.clip.size()));
      mesh.clip.push_back(ScreenToClip(x, y, z, 8, 8));
    }
  }
  return mesh;
}

// hw-facts §5.1: ZMask 0 means "cleared" and a written tile stores planes only, so a tile that
// is partly written holds the clear depth as one of its planes.
TEST(ZPlanes, ClearIsAPlaneOnceTheTileIsPartlyWritten) {
  struct Case {
    const char* what;
    Mesh mesh;
    int maxPlanes;
    std::uint64_t decompressions, compactions;
    int planesAtEnd;  // when still compressed
  };
  const Case cases[] = {
      // clear + left = 2 slots; right needs a third while the clear (columns 4..7) and left
      // (columns 0..3) are both referenced.
      {"left then right, limit 2", FlatTriangles({{"left", 0.5}, {"right", 0.25}}), 2, 1, 0, 0},
      {"left then right, limit 3", FlatTriangles({{"left", 0.5}, {"right", 0.25}}), 3, 0, 0, 3},
      // "all" leaves the clear unreferenced; "right" drops it to make room.
      {"all then right, limit 2", FlatTriangles({{"all", 0.5}, {"right", 0.25}}), 2, 0, 1, 2},
      // One slot cannot hold the clear and a triangle: the first write decompresses, even when
      // the triangle covers the whole tile (the clear is still referenced by the pixels it has
      // not written yet).
      {"all, limit 1", FlatTriangles({{"all", 0.5}}), 1, 1, 0, 0},
      {"all, limit 0", FlatTriangles({{"all", 0.5}}), 0, 1, 0, 0},
  };
  for (const Case& c : cases) {
    DepthStencilSurface surface = MakeDepthSurface(8, 8, 4, 1, c.maxPlanes);
    DrawState state = CullNone();
    state.depth.hiZEnable = false;
    const RasterResult result = Rasterize(c.mesh.Input(), state, surface);
    EXPECT_EQ(result.counters.zPlaneDecompressions, c.decompressions) << c.what;
    EXPECT_EQ(result.counters.zPlaneCompactions, c.compactions) << c.what;
    const bool decompressed = c.decompressions > 0;
    EXPECT_EQ(surface.Tile(0, 0).state, decompressed ? ZTileState::Decompressed : ZTileState::Compressed) << c.what;
    if (!decompressed) {
      EXPECT_EQ(surface.Tile(0, 0).planeCount, c.planesAtEnd) << c.what;
    }
  }
}

// The decompression takes effect inside the write of one pixel. Clear + "left" fill a
// two-plane table; a flat triangle over the quad at (4, 4) only makes its first write in the
// quad's pixel 0 (4, 4): that pixel was tested exactly (all four samples), its unanchored
// samples' new depth is lost (they read anchor 0's), and pixels 1..3 of the same quad test
// unanchored samples against their nearest anchor.
TEST(ZPlanes, DecompressionTakesEffectInsideTheQuad) {
  Mesh mesh = FlatTriangles({{"left", 0.5}});
  for (const auto& [x, y] : {std::pair{4.03125, 4.03125}, {8.0, 4.03125}, {4.03125, 8.0}}) {
    mesh.indices.push_back(static_cast<std::uint32_t>(mesh.clip.size()));
    mesh.clip.push_back(ScreenToClip(x, y, 0.25, 8, 8));
  }
  DepthStencilSurface surface = MakeDepthSurface(8, 8, 4, 1, 2);
  DrawState state = CullNone();
  state.depth.hiZEnable = false;
  const RasterResult result = Rasterize(mesh.Input(), state, surface);
  EXPECT_EQ(result.counters.zPlaneDecompressions, 1u);
  const QuadFragment* quad = nullptr;
  for (const QuadFragment& q : result.quadsByBin[0]) {
    if (q.primitiveId == 1 && q.x == 4 && q.y == 4) quad = &q;
  }
  ASSERT_NE(quad, nullptr);
  // Standard 4x (hw-facts §4.1): every sample of pixels 4 and 5 lies right of and below
  // 4.03125 and above x + y = 12.03125, so the whole quad is covered and passes the clear.
  for (int p = 0; p < kQuadPixels; ++p) {
    EXPECT_EQ(quad->covered.Pixel(p), 0xF) << p;
    EXPECT_EQ(quad->passed.Pixel(p), 0xF) << p;
    EXPECT_EQ(quad->depthExact.Pixel(p), p == 0 ? 0xF : 0x1) << p;
  }
  // Pixel (4, 4) wrote sample 0 only; samples 1..3 read it. The triangle is flat, so every
  // anchored depth in the quad is 0.25.
  for (int s = 0; s < 4; ++s) EXPECT_EQ(surface.TestDepth(4, 4, s), 0.25f) << s;
  EXPECT_EQ(surface.TestDepth(0, 0, 3), 0.5f);
  EXPECT_EQ(surface.TestDepth(7, 0, 3), 1.0f);
}

// Each new full-screen triangle in front hides every earlier plane, so compaction makes room
// and tiles never decompress however many are drawn.
TEST(ZPlanes, CompactionDropsHiddenPlanes) {
  Mesh mesh;
  for (int i = 0; i < 10; ++i) {
    const float z = 0.9f - 0.05f * static_cast<float>(i);
    const std::uint32_t base = static_cast<std::uint32_t>(mesh.clip.size());
    mesh.clip.insert(mesh.clip.end(), {{-1, -1, z, 1}, {3, -1, z + 0.01f, 1}, {-1, 3, z, 1}});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
  }
  DepthStencilSurface surface = MakeDepthSurface(16, 16, 4, 4, 2);
  DrawState state;
  state.depth.hiZEnable = false;
  const RasterResult result = Rasterize(mesh.Input(), state, surface);
  EXPECT_EQ(result.counters.zPlaneDecompressions, 0u);
  EXPECT_GT(result.counters.zPlaneCompactions, 0u);
  EXPECT_EQ(result.counters.zTilesCompressedAtEnd, 4u);
}

// The depth rules of docs/raster.md ("Depth, Z planes and hi-Z"), re-implemented slowly and
// apart from DepthStencilSurface: a tile is a list of planes, a sample the position of its
// plane in that list; triangles in submission order, per tile quads in row-major order and
// the quad's pixels in the order X0Y0, X1Y0, X0Y1, X1Y1; depth LESS with writes, no stencil,
// no hi-Z. It records the passed and exact masks of every (set-up, pixel).
class ReferenceDepthModel {
 public:
  ReferenceDepthModel(int width, int height, const SamplePattern& pattern, int anchors, int maxPlanes)
      : width_(width), height_(height), pattern_(pattern), samples_(pattern.Count()), anchors_(anchors),
        maxPlanes_(maxPlanes), tilesX_((width + 7) / 8), tiles_(static_cast<std::size_t>(tilesX_ * ((height + 7) / 8))),
        planeOf_(static_cast<std::size_t>(width * height * samples_), -1),
        anchorDepth_(static_cast<std::size_t>(width * height * anchors), 1.0f) {}

  struct Record {
    SampleMask passed = 0, exact = 0;
  };
  std::map<std::tuple<std::size_t, int, int>, Record> records;  // (set-up, x, y)
  std::uint64_t decompressions = 0, compactions = 0;

  void Draw(const std::vector<TriangleSetup>& setups) {
    for (std::size_t t = 0; t < setups.size(); ++t) {
      for (int ty = 0; ty * 8 < height_; ++ty) {
        for (int tx = 0; tx * 8 < width_; ++tx) {
          for (int qy = ty * 8; qy < std::min(ty * 8 + 8, height_); qy += 2) {
            for (int qx = tx * 8; qx < std::min(tx * 8 + 8, width_); qx += 2) {
              for (int p = 0; p < 4; ++p) {
                const int x = qx + (p & 1), y = qy + (p >> 1);
                if (x < width_ && y < height_) Pixel(t, setups[t], x, y);
              }
            }
          }
        }
      }
    }
  }

  // The sample's depth as the depth unit sees it.
  float Stored(int x, int y, int s) const {
    const Tile& tile = TileOf(x, y);
    if (tile.state == State::Cleared) return 1.0f;
    if (tile.state == State::Decompressed) return anchorDepth_[static_cast<std::size_t>(PixelOf(x, y) * anchors_ + Nearest(x, y, s))];
    return tile.planes[static_cast<std::size_t>(planeOf_[Index(x, y, s)])].Evaluate(X(x, y, s), Y(x, y, s));
  }

 private:
  enum class State { Cleared, Compressed, Decompressed };
  struct Tile {
    State state = State::Cleared;
    std::vector<ZPlane> planes;
  };

  int PixelOf(int x, int y) const { return y * width_ + x; }
  std::size_t Index(int x, int y, int s) const { return static_cast<std::size_t>(PixelOf(x, y) * samples_ + s); }
  std::int64_t X(int x, int y, int s) const { return x * 256 + 128 + 16 * pattern_.Offset(QuadPixelIndex(x, y), s).x; }
  std::int64_t Y(int x, int y, int s) const { return y * 256 + 128 + 16 * pattern_.Offset(QuadPixelIndex(x, y), s).y; }
  Tile& TileOf(int x, int y) { return tiles_[static_cast<std::size_t>((y / 8) * tilesX_ + x / 8)]; }
  const Tile& TileOf(int x, int y) const { return tiles_[static_cast<std::size_t>((y / 8) * tilesX_ + x / 8)]; }

  // Euclidean distance in the pixel's own offsets; the lower index wins ties.
  int Nearest(int x, int y, int s) const {
    if (s < anchors_) return s;
    const int q = QuadPixelIndex(x, y);
    int best = 0, bestDistance = 1 << 30;
    for (int a = 0; a < anchors_; ++a) {
      const int dx = pattern_.Offset(q, s).x - pattern_.Offset(q, a).x, dy = pattern_.Offset(q, s).y - pattern_.Offset(q, a).y;
      if (dx * dx + dy * dy < bestDistance) {
        best = a;
        bestDistance = dx * dx + dy * dy;
      }
    }
    return best;
  }

  void ForTilePixels(int x, int y, const std::function<void(int, int)>& fn) const {
    const int x0 = x / 8 * 8, y0 = y / 8 * 8;
    for (int py = y0; py < std::min(y0 + 8, height_); ++py) {
      for (int px = x0; px < std::min(x0 + 8, width_); ++px) fn(px, py);
    }
  }

  void Pixel(std::size_t t, const TriangleSetup& tri, int x, int y) {
    SampleMask covered = 0, passed = 0;
    std::array<float, 16> incoming{};
    for (int s = 0; s < samples_; ++s) {
      bool inside = true;
      for (const EdgeFunction& e : tri.edges) inside &= e.a * X(x, y, s) + e.b * Y(x, y, s) + e.c >= 0;
      if (!inside) continue;
      covered |= static_cast<SampleMask>(1u << s);
      incoming[static_cast<std::size_t>(s)] = tri.depth.Evaluate(X(x, y, s), Y(x, y, s));  // at its own position
      if (incoming[static_cast<std::size_t>(s)] < Stored(x, y, s)) passed |= static_cast<SampleMask>(1u << s);
    }
    if (covered == 0) return;
    Tile& tile = TileOf(x, y);
    const SampleMask anchored = static_cast<SampleMask>((1u << anchors_) - 1u);
    records[{t, x, y}] = {passed, tile.state == State::Decompressed ? static_cast<SampleMask>(covered & anchored) : covered};
    if (passed == 0) return;
    int slot = -1;
    if (tile.state != State::Decompressed) slot = Slot(tile, tri.depth, x, y);
    for (int s = 0; s < samples_; ++s) {
      if (!((passed >> s) & 1)) continue;
      if (slot >= 0) {
        planeOf_[Index(x, y, s)] = slot;
      } else if (s < anchors_) {
        anchorDepth_[static_cast<std::size_t>(PixelOf(x, y) * anchors_ + s)] = incoming[static_cast<std::size_t>(s)];
      }
    }
  }

  int Slot(Tile& tile, const ZPlane& plane, int x, int y) {
    if (tile.state == State::Cleared) {
      if (maxPlanes_ == 0) return Decompress(tile, x, y);
      tile.state = State::Compressed;
      tile.planes = {ZPlane{0.0, 0.0, 1.0}};
      ForTilePixels(x, y, [&](int px, int py) {
        for (int s = 0; s < samples_; ++s) planeOf_[Index(px, py, s)] = 0;
      });
    }
    for (std::size_t i = 0; i < tile.planes.size(); ++i) {
      if (tile.planes[i] == plane) return static_cast<int>(i);
    }
    if (static_cast<int>(tile.planes.size()) >= maxPlanes_) {
      std::vector<int> uses(tile.planes.size(), 0);
      ForTilePixels(x, y, [&](int px, int py) {
        for (int s = 0; s < samples_; ++s) ++uses[static_cast<std::size_t>(planeOf_[Index(px, py, s)])];
      });
      std::vector<ZPlane> kept;
      std::vector<int> renumber(tile.planes.size(), -1);
      for (std::size_t i = 0; i < tile.planes.size(); ++i) {
        if (uses[i] == 0) continue;
        renumber[i] = static_cast<int>(kept.size());
        kept.push_back(tile.planes[i]);
      }
      if (kept.size() < tile.planes.size()) {
        ++compactions;
        tile.planes = kept;
        ForTilePixels(x, y, [&](int px, int py) {
          for (int s = 0; s < samples_; ++s) planeOf_[Index(px, py, s)] = renumber[static_cast<std::size_t>(planeOf_[Index(px, py, s)])];
        });
      }
    }
    if (static_cast<int>(tile.planes.size()) >= maxPlanes_) return Decompress(tile, x, y);
    tile.planes.push_back(plane);
    return static_cast<int>(tile.planes.size()) - 1;
  }

  int Decompress(Tile& tile, int x, int y) {
    ForTilePixels(x, y, [&](int px, int py) {
      for (int a = 0; a < anchors_; ++a) anchorDepth_[static_cast<std::size_t>(PixelOf(px, py) * anchors_ + a)] = Stored(px, py, a);
    });
    tile.state = State::Decompressed;
    ++decompressions;
    return -1;
  }

  int width_, height_;
  const SamplePattern& pattern_;
  int samples_, anchors_, maxPlanes_, tilesX_;
  std::vector<Tile> tiles_;
  std::vector<int> planeOf_;
  std::vector<float> anchorDepth_;
};

// The rasterizer's depth unit against the documented model, on random overlapping soups with
// small plane limits (so tiles compact and decompress) and unanchored samples.
TEST(ZPlanes, MatchesTheDocumentedModel) {
  constexpr int kWidth = 40, kHeight = 24;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    Random rng(seed);
    const Mesh mesh = RandomSoup(rng, 40, kWidth, kHeight, 8.0);
    for (auto [s, z] : {std::pair{4, 1}, {8, 2}, {16, 4}, {2, 2}}) {
      for (int maxPlanes : {0, 1, 2, 3, 4}) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed << " S " << s << " Z " << z << " planes " << maxPlanes);
        DepthStencilSurface surface = MakeDepthSurface(kWidth, kHeight, s, z, maxPlanes, seed % 2 ? "eqaa" : "standard");
        DrawState state = CullNone();
        state.depth.hiZEnable = false;
        const RasterResult result = Rasterize(mesh.Input(), state, surface);
        ReferenceDepthModel reference(kWidth, kHeight, surface.Pattern(), z, maxPlanes);
        reference.Draw(result.triangles);
        EXPECT_EQ(result.counters.zPlaneDecompressions, reference.decompressions);
        EXPECT_EQ(result.counters.zPlaneCompactions, reference.compactions);
        std::size_t pixelsSeen = 0;
        for (const auto& bin : result.quadsByBin) {
          for (const QuadFragment& q : bin) {
            for (int p = 0; p < kQuadPixels; ++p) {
              if (q.covered.Pixel(p) == 0) continue;
              ++pixelsSeen;
              const auto found = reference.records.find({q.setupIndex, q.x + (p & 1), q.y + (p >> 1)});
              ASSERT_NE(found, reference.records.end());
              ASSERT_EQ(q.passed.Pixel(p), found->second.passed) << q.x + (p & 1) << "," << q.y + (p >> 1);
              ASSERT_EQ(q.depthExact.Pixel(p), found->second.exact) << q.x + (p & 1) << "," << q.y + (p >> 1);
            }
          }
        }
        EXPECT_EQ(pixelsSeen, reference.records.size());
        for (int y = 0; y < kHeight; ++y) {
          for (int x = 0; x < kWidth; ++x) {
            for (int k = 0; k < s; ++k) ASSERT_EQ(surface.TestDepth(x, y, k), reference.Stored(x, y, k)) << x << "," << y << " sample " << k;
          }
        }
      }
    }
  }
}

TEST(ZPlanes, NearestAnchorIsTheClosestAnchoredSample) {
  const DepthStencilSurface surface = MakeDepthSurface(8, 8, 16, 4, 4, "eqaa");
  const SamplePattern& pattern = surface.Pattern();
  for (int p = 0; p < kQuadPixels; ++p) {
    for (int s = 0; s < 16; ++s) {
      const int anchor = surface.NearestAnchor(p, s);
      ASSERT_LT(anchor, 4);
      if (s < 4) {
        EXPECT_EQ(anchor, s);
      }
      auto d2 = [&](int a) {
        const SampleOffset u = pattern.Offset(p, s), v = pattern.Offset(p, a);
        return (u.x - v.x) * (u.x - v.x) + (u.y - v.y) * (u.y - v.y);
      };
      for (int a = 0; a < 4; ++a) EXPECT_LE(d2(anchor), d2(a));
    }
  }
}

// A near full-screen triangle, then a far one: hi-Z rejects every tile of the second draw
// before any per-sample work.
TEST(HiZ, RejectsHiddenTiles) {
  Mesh mesh;
  mesh.clip = {{-1, -1, 0.2f, 1}, {3, -1, 0.2f, 1}, {-1, 3, 0.2f, 1}, {-1, -1, 0.6f, 1}, {3, -1, 0.6f, 1}, {-1, 3, 0.6f, 1}};
  mesh.indices = {0, 1, 2, 3, 4, 5};
  DepthStencilSurface surface = MakeDepthSurface(32, 24, 4, 4, 4);
  const RasterCounters c = Rasterize(mesh.Input(), DrawState{}, surface).counters;
  EXPECT_EQ(c.tilesHiZRejected, 4u * 3u);
  EXPECT_EQ(c.samplesDepthPassed, 32u * 24u * 4u);
  DrawState noHiZ;
  noHiZ.depth.hiZEnable = false;
  surface.Clear(1.0f, 0);
  const RasterCounters d = Rasterize(mesh.Input(), noHiZ, surface).counters;
  EXPECT_EQ(d.tilesHiZRejected, 0u);
  EXPECT_EQ(d.samplesDepthPassed, c.samplesDepthPassed);
  EXPECT_EQ(d.samplesCovered, 2 * c.samplesCovered);
}

// Stencil in a checkerboard of 8x8 tiles; a draw testing stencil == 1 is pre-rejected on the
// tiles holding 0 by the matching hi-stencil pretest, and per pixel gives the same image.
TEST(HiStencil, RejectsTilesWhereNoPixelCanPass) {
  constexpr int kWidth = 32, kHeight = 32;
  for (bool pretest : {true, false}) {
    DepthStencilSurface surface = MakeDepthSurface(kWidth, kHeight, 4, 4, 4);
    surface.SetHiStencilPretests({HiStencilPretest{pretest, CompareFunc::Equal, 1, 0xFF}, HiStencilPretest{}});
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) surface.SetStencil(x, y, static_cast<std::uint8_t>(((x / 8) + (y / 8)) % 2));
    }
    Mesh mesh;
    mesh.clip = {{-1, -1, 0.5f, 1}, {3, -1, 0.5f, 1}, {-1, 3, 0.5f, 1}};
    mesh.indices = {0, 1, 2};
    DrawState state;
    state.stencil = StencilState{true, CompareFunc::Equal, 1, 0xFF, 0xFF, StencilOp::Keep, StencilOp::Keep, StencilOp::Keep};
    const RasterCounters c = Rasterize(mesh.Input(), state, surface).counters;
    EXPECT_EQ(c.tilesHiStencilRejected, pretest ? 8u : 0u);
    EXPECT_EQ(c.samplesDepthPassed, 8u * 64u * 4u);
    EXPECT_EQ(c.samplesStencilPassed, 8u * 64u * 4u);
  }
}

// D3D's stencil test, (ref & mask) FUNC (value & mask), written out per function.
bool ReferenceStencilPasses(CompareFunc func, int ref, int mask, int value) {
  const int a = ref & mask, b = value & mask;
  switch (func) {
    case CompareFunc::Never: return false;
    case CompareFunc::Less: return a < b;
    case CompareFunc::Equal: return a == b;
    case CompareFunc::LessEqual: return a <= b;
    case CompareFunc::Greater: return a > b;
    case CompareFunc::NotEqual: return a != b;
    case CompareFunc::GreaterEqual: return a >= b;
    case CompareFunc::Always: return true;
  }
  return false;
}

// A tile is rejected exactly when none of its pixels passes the matching pretest, whatever the
// tile holds: one value, one value but one pixel, a few values or noise; whole and partial tiles;
// pretests set before or after the stencil writes (the bits are then refreshed when read).
TEST(HiStencil, TileRejectionIsThatOfAPerPixelTest) {
  Random rng(0x5713);
  for (const auto& [width, height] : {std::pair{16, 16}, std::pair{24, 8}, std::pair{21, 13}, std::pair{5, 3}}) {
    for (int trial = 0; trial < 60; ++trial) {
      DepthStencilSurface surface = MakeDepthSurface(width, height, 1, 1, 4);
      std::array<HiStencilPretest, kHiStencilPretests> pretests{};
      for (HiStencilPretest& pretest : pretests) {
        pretest = {true, static_cast<CompareFunc>(rng.Int(0, 7)), static_cast<std::uint8_t>(rng.Int(0, 3)),
                   static_cast<std::uint8_t>(rng.Int(0, 1) == 0 ? 0xFF : rng.Int(0, 255))};
      }
      const bool pretestsFirst = trial % 2 == 0;
      if (pretestsFirst) surface.SetHiStencilPretests(pretests);
      std::vector<int> stencil(static_cast<std::size_t>(width * height));
      const int tilesX = (width + 7) / 8, tilesY = (height + 7) / 8;
      for (int ty = 0; ty < tilesY; ++ty) {
        for (int tx = 0; tx < tilesX; ++tx) {
          const int kind = rng.Int(0, 3), base = rng.Int(0, 3);
          const int oddX = tx * 8 + rng.Int(0, 7), oddY = ty * 8 + rng.Int(0, 7);
          for (int y = ty * 8; y < std::min(ty * 8 + 8, height); ++y) {
            for (int x = tx * 8; x < std::min(tx * 8 + 8, width); ++x) {
              int value = base;
              if (kind == 1 && x == oddX && y == oddY) value = base ^ 1;
              if (kind == 2) value = rng.Int(0, 3);
              if (kind == 3) value = rng.Int(0, 255);
              stencil[static_cast<std::size_t>(y * width + x)] = value;
              surface.SetStencil(x, y, static_cast<std::uint8_t>(value));
            }
          }
        }
      }
      if (!pretestsFirst) surface.SetHiStencilPretests(pretests);
      for (int ty = 0; ty < tilesY; ++ty) {
        for (int tx = 0; tx < tilesX; ++tx) {
          for (const HiStencilPretest& pretest : pretests) {
            bool anyPasses = false;
            for (int y = ty * 8; y < std::min(ty * 8 + 8, height); ++y) {
              for (int x = tx * 8; x < std::min(tx * 8 + 8, width); ++x) {
                anyPasses |= ReferenceStencilPasses(pretest.func, pretest.ref, pretest.mask,
                                                    stencil[static_cast<std::size_t>(y * width + x)]);
              }
            }
            const StencilState test{true, pretest.func, pretest.ref, pretest.mask, 0, StencilOp::Keep, StencilOp::Keep,
                                    StencilOp::Keep};
            EXPECT_EQ(surface.HiStencilRejects(tx, ty, test), !anyPasses)
                << width << "x" << height << " trial " << trial << " tile (" << tx << ", " << ty << ") func "
                << static_cast<int>(pretest.func) << " ref " << int{pretest.ref} << " mask " << int{pretest.mask};
          }
        }
      }
    }
  }
}

TEST(Stencil, OpsApplyPerPixel) {
  DepthStencilSurface surface = MakeDepthSurface(8, 8, 1, 1, 4);
  Mesh mesh;
  mesh.clip = {{-1, -1, 0.5f, 1}, {3, -1, 0.5f, 1}, {-1, 3, 0.5f, 1}};
  mesh.indices = {0, 1, 2};
  DrawState state;
  state.stencil = StencilState{true, CompareFunc::Always, 7, 0xFF, 0xFF, StencilOp::Keep, StencilOp::Keep, StencilOp::Replace};
  Rasterize(mesh.Input(), state, surface);
  EXPECT_EQ(surface.Stencil(3, 3), 7);
  // Same depth again with LESS: depth fails everywhere, the depth-fail op increments.
  state.stencil.depthFailOp = StencilOp::IncrementClamp;
  Rasterize(mesh.Input(), state, surface);
  EXPECT_EQ(surface.Stencil(3, 3), 8);
  EXPECT_EQ(surface.Stencil(7, 7), 8);
}

TEST(Clipping, NearPlaneCutsAndGuardBandKeepsCoverage) {
  constexpr int kWidth = 32, kHeight = 32;
  // z from -0.5 (behind the near plane) to 1 across the screen, w = 1.
  Mesh mesh;
  mesh.clip = {{-1, -1, -0.5f, 1}, {3, -1, 1.0f, 1}, {-1, 3, -0.5f, 1}};
  mesh.indices = {0, 1, 2};
  DepthStencilSurface surface = MakeDepthSurface(kWidth, kHeight, 1, 1, 4);
  DrawState state = CullNone();
  state.depth.func = CompareFunc::Always;
  const RasterResult result = Rasterize(mesh.Input(), state, surface);
  EXPECT_EQ(result.counters.trianglesClipped, 1u);
  // z = -0.5 + 1.5 * (ndcX + 1) / 4 >= 0  <=>  ndcX >= 1/3  <=>  pixel centre x >= 2/3 * 32.
  const auto counts = testing::CoverageCounts(result, kWidth, kHeight, 1, false);
  for (int x = 0; x < kWidth; ++x) {
    const double ndcX = (x + 0.5) / kWidth * 2 - 1;
    if (std::abs(ndcX - 1.0 / 3.0) < 0.05) continue;  // the clip edge snaps to 1/256 px
    EXPECT_EQ(counts[5 * kWidth + x], ndcX > 1.0 / 3.0 ? 1 : 0) << x;
  }
  // Vertices far outside the guard band: clipped, and still every sample is covered once.
  Mesh huge;
  huge.clip = {{-1000, -1000, 0.5f, 1}, {3000, -1000, 0.5f, 1}, {-1000, 3000, 0.5f, 1}};
  huge.indices = {0, 1, 2};
  surface.Clear(1.0f, 0);
  const RasterResult big = Rasterize(huge.Input(), state, surface);
  EXPECT_EQ(big.counters.trianglesClipped, 1u);
  EXPECT_EQ(big.counters.samplesCovered, std::uint64_t{kWidth} * kHeight);
  // Entirely behind the camera, and entirely off screen.
  Mesh gone;
  gone.clip = {{0, 0, -1, 1}, {1, 0, -1, 1}, {0, 1, -1, 1}, {5, 5, 0.5f, 1}, {6, 5, 0.5f, 1}, {5, 6, 0.5f, 1}};
  gone.indices = {0, 1, 2, 3, 4, 5};
  const RasterCounters c = Rasterize(gone.Input(), state, surface).counters;
  EXPECT_EQ(c.trianglesOutsideView, 2u);
  EXPECT_EQ(c.trianglesRasterized, 0u);
}

TEST(Barycentrics, PerspectiveCorrect) {
  Mesh mesh;
  // Vertex 1 twice as far (w = 2): screen-space midpoints are not attribute midpoints.
  mesh.clip = {{-1, -1, 0.5f, 1}, {2, -2, 1.0f, 2}, {-1, 1, 0.5f, 1}};
  mesh.indices = {0, 1, 2};
  DepthStencilSurface surface = MakeDepthSurface(16, 16, 1, 1, 4);
  const RasterResult result = Rasterize(mesh.Input(), CullNone(), surface);
  ASSERT_EQ(result.triangles.size(), 1u);
  const TriangleSetup& tri = result.triangles[0];
  // Screen positions of the vertices: (0,16), (16,16), (0,0).
  const auto at0 = PerspectiveBarycentrics(tri, 0.0, 16.0);
  EXPECT_NEAR(at0[0], 1.0f, 1e-5f);
  const auto at1 = PerspectiveBarycentrics(tri, 16.0, 16.0);
  EXPECT_NEAR(at1[1], 1.0f, 1e-5f);
  // Screen midpoint of v0-v1: linear weights 1/2, 1/2 -> perspective 1/w: (1, 1/2) -> (2/3, 1/3).
  const auto mid = PerspectiveBarycentrics(tri, 8.0, 16.0);
  EXPECT_NEAR(mid[0], 2.0f / 3.0f, 1e-5f);
  EXPECT_NEAR(mid[1], 1.0f / 3.0f, 1e-5f);
  EXPECT_NEAR(mid[0] + mid[1] + mid[2], 1.0f, 1e-6f);
}

TEST(Determinism, IdenticalForAnyThreadCount) {
  constexpr int kWidth = 200, kHeight = 150;
  Random rng(5);
  const Mesh mesh = RandomSoup(rng, 3000, kWidth, kHeight, 15.0);
  auto run = [&](int threads, std::vector<float>& depth) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    DepthStencilSurface surface = MakeDepthSurface(kWidth, kHeight, 8, 4, 4);
    RasterResult result = Rasterize(mesh.Input(), CullNone(), surface);
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        for (int s = 0; s < 8; ++s) depth.push_back(surface.TestDepth(x, y, s));
      }
    }
    return result;
  };
  std::vector<float> depth1, depth2;
  const RasterResult one = run(1, depth1);
  const RasterResult two = run(2, depth2);
  EXPECT_EQ(one.counters, two.counters);
  EXPECT_EQ(depth1, depth2);
  ASSERT_EQ(one.quadsByBin.size(), two.quadsByBin.size());
  for (std::size_t b = 0; b < one.quadsByBin.size(); ++b) {
    ASSERT_EQ(one.quadsByBin[b].size(), two.quadsByBin[b].size());
    for (std::size_t q = 0; q < one.quadsByBin[b].size(); ++q) {
      const QuadFragment &a = one.quadsByBin[b][q], &c = two.quadsByBin[b][q];
      ASSERT_TRUE(a.x == c.x && a.y == c.y && a.primitiveId == c.primitiveId && a.covered == c.covered &&
                  a.passed == c.passed && a.centroid == c.centroid);
    }
  }
}

}  // namespace
}  // namespace raster
