// Depth and stencil: Z-plane compression against exact per-sample depth, the plane limit,
// compaction, nearest-anchor fallback, hi-Z, stencil and hi-stencil, clipping, barycentrics
// and determinism across host thread counts.

#include <gtest/gtest.h>

#include <cmath>

#include <tbb/global_control.h>

#include "raster/sample_pattern.h"
#include "raster_test_util.h"

namespace raster {
namespace {

using testing::Mesh;
using testing::RandomSoup;
using testing::Random;
using testing::ScreenToClip;

DepthStencilSurface MakeSurface(int width, int height, int samples, int depthSamples, int maxZPlanes,
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
      DepthStencilSurface surface = MakeSurface(kWidth, kHeight, s, z, kMaxZPlanesPerTile, "eqaa");
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
  DepthStencilSurface planes = MakeSurface(kWidth, kHeight, 8, 8, 4);
  DepthStencilSurface perSample = MakeSurface(kWidth, kHeight, 8, 8, 0);
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

// N + 1 visible planes in one tile: the tile decompresses exactly once with a limit of N and
// stays compressed with a limit of N + 1; afterwards unanchored samples read their anchor.
TEST(ZPlanes, PlaneLimitDecompresses) {
  constexpr int kSize = 8;
  for (int limit : {2, 4, 7, 15}) {
    // A fan of limit + 1 triangles around the tile centre, each with its own plane.
    const int planes = limit + 1;
    Mesh mesh;
    mesh.clip.push_back(ScreenToClip(4.0, 4.0, 0.5, kSize, kSize));
    for (int k = 0; k < planes; ++k) {
      const double angle = 2.0 * 3.14159265358979 * k / planes;
      mesh.clip.push_back(ScreenToClip(4.0 + 20.0 * std::cos(angle), 4.0 + 20.0 * std::sin(angle), 0.5 + 0.01 * k, kSize, kSize));
      mesh.indices.insert(mesh.indices.end(), {0u, static_cast<std::uint32_t>(1 + k), static_cast<std::uint32_t>(1 + (k + 1) % planes)});
    }
    for (int maxPlanes : {limit, planes}) {
      DepthStencilSurface surface = MakeSurface(kSize, kSize, 8, 2, maxPlanes);
      const RasterResult result = Rasterize(mesh.Input(), CullNone(), surface);
      const bool overflow = maxPlanes < planes;
      EXPECT_EQ(result.counters.zPlaneDecompressions, overflow ? 1u : 0u) << "limit " << maxPlanes;
      EXPECT_EQ(surface.Tile(0, 0).state, overflow ? ZTileState::Decompressed : ZTileState::Compressed);
      if (!overflow) {
        EXPECT_EQ(surface.Tile(0, 0).planeCount, planes);
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
  DepthStencilSurface surface = MakeSurface(16, 16, 4, 4, 2);
  DrawState state;
  state.depth.hiZEnable = false;
  const RasterResult result = Rasterize(mesh.Input(), state, surface);
  EXPECT_EQ(result.counters.zPlaneDecompressions, 0u);
  EXPECT_GT(result.counters.zPlaneCompactions, 0u);
  EXPECT_EQ(result.counters.zTilesCompressedAtEnd, 4u);
}

TEST(ZPlanes, NearestAnchorIsTheClosestAnchoredSample) {
  const DepthStencilSurface surface = MakeSurface(8, 8, 16, 4, 4, "eqaa");
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
  DepthStencilSurface surface = MakeSurface(32, 24, 4, 4, 4);
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
    DepthStencilSurface surface = MakeSurface(kWidth, kHeight, 4, 4, 4);
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

TEST(Stencil, OpsApplyPerPixel) {
  DepthStencilSurface surface = MakeSurface(8, 8, 1, 1, 4);
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
  DepthStencilSurface surface = MakeSurface(kWidth, kHeight, 1, 1, 4);
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
  DepthStencilSurface surface = MakeSurface(16, 16, 1, 1, 4);
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
    DepthStencilSurface surface = MakeSurface(kWidth, kHeight, 8, 4, 4);
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
