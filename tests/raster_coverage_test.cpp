// Coverage: watertightness, the top-left rule, sample-position probes, hierarchy vs. a slow
// reference, centroid, and counters on closed-form scenes.

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "raster/raster_error.h"
#include "raster/sample_pattern.h"
#include "raster_test_util.h"

namespace raster {
namespace {

using testing::CoverageCounts;
using testing::Mesh;
using testing::Random;
using testing::ScreenToClip;

DrawState NoDepthNoCull() {
  DrawState state;
  state.cull = CullMode::None;
  state.depth.testEnable = false;
  state.depth.writeEnable = false;
  return state;
}

DepthStencilSurface MakeSurface(int width, int height, const SamplePattern& pattern, int depthSamples = 0,
                                int maxZPlanes = 4) {
  DepthSurfaceConfig config;
  config.width = width;
  config.height = height;
  config.coverageSamples = pattern.Count();
  config.depthSamples = depthSamples ? depthSamples : std::min(pattern.Count(), kMaxDepthSamples);
  config.maxZPlanes = maxZPlanes;
  return DepthStencilSurface(config, pattern);
}

// A pattern with different random offsets in each quad pixel, anywhere on the 16x16 grid.
SamplePattern RandomPattern(Random& rng, int count) {
  std::array<std::vector<SampleOffset>, kQuadPixels> pixels;
  for (auto& pixel : pixels) {
    for (int s = 0; s < count; ++s) pixel.push_back({rng.Int(kSampleOffsetMin, kSampleOffsetMax), rng.Int(kSampleOffsetMin, kSampleOffsetMax)});
  }
  return SamplePattern::Create("random", count, pixels);
}

// Property: a mesh of shared edges that covers the whole viewport covers every sample exactly
// once, for random sub-pixel vertices, patterns with samples on pixel edges, and winding mixes.
TEST(RasterWatertight, JitteredGridsCoverEverySampleOnce) {
  constexpr int kWidth = 61, kHeight = 37;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    Random rng(seed);
    const int count = 1 << rng.Int(0, 4);
    const SamplePattern pattern = seed % 3 == 0 ? MakeBuiltinPattern("standard", count) : RandomPattern(rng, count);
    const Mesh mesh = testing::JitteredGrid(rng, rng.Int(3, 40), rng.Int(3, 30), -3.3, -2.7, kWidth + 2.9,
                                            kHeight + 3.1, kWidth, kHeight);
    DepthStencilSurface surface = MakeSurface(kWidth, kHeight, pattern);
    const RasterResult result = Rasterize(mesh.Input(), NoDepthNoCull(), surface);
    const std::vector<int> counts = CoverageCounts(result, kWidth, kHeight, count, false);
    const auto [lo, hi] = std::minmax_element(counts.begin(), counts.end());
    EXPECT_EQ(*lo, 1) << "seed " << seed;
    EXPECT_EQ(*hi, 1) << "seed " << seed;
    EXPECT_EQ(result.counters.samplesCovered, counts.size()) << "seed " << seed;
  }
}

// A fan of very thin triangles around a point inside the viewport whose rim lies outside it:
// the fan tiles the screen, so again every sample is covered exactly once.
TEST(RasterWatertight, ThinFanCoversEverySampleOnce) {
  constexpr int kWidth = 48, kHeight = 40;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    Random rng(seed);
    Mesh mesh;
    const double cx = rng.Uniform(10, 38), cy = rng.Uniform(10, 30);
    mesh.clip.push_back(ScreenToClip(cx, cy, 0.5, kWidth, kHeight));
    const int spokes = 200 + rng.Int(0, 300);
    for (int i = 0; i < spokes; ++i) {
      const double angle = 2.0 * 3.14159265358979 * (i + rng.Uniform(-0.3, 0.3)) / spokes;
      mesh.clip.push_back(ScreenToClip(cx + 100 * std::cos(angle), cy + 100 * std::sin(angle), 0.5, kWidth, kHeight));
    }
    for (int i = 0; i < spokes; ++i) {
      mesh.indices.insert(mesh.indices.end(), {0u, static_cast<std::uint32_t>(1 + i), static_cast<std::uint32_t>(1 + (i + 1) % spokes)});
    }
    const int count = 1 << (seed % 5);
    const SamplePattern pattern = RandomPattern(rng, count);
    DepthStencilSurface surface = MakeSurface(kWidth, kHeight, pattern);
    const RasterResult result = Rasterize(mesh.Input(), NoDepthNoCull(), surface);
    const std::vector<int> counts = CoverageCounts(result, kWidth, kHeight, count, false);
    EXPECT_TRUE(std::all_of(counts.begin(), counts.end(), [](int c) { return c == 1; })) << "seed " << seed;
  }
}

// D3D top-left rule: samples exactly on a left or top edge are inside, on a right or bottom
// edge outside. A square with corners on pixel centres (0.5,0.5)-(2.5,2.5) covers the centre
// samples of pixels x, y in {0, 1} only.
TEST(RasterTopLeft, SquareOnPixelCentres) {
  constexpr int kSize = 4;
  Mesh mesh;
  for (auto [x, y] : {std::pair{0.5, 0.5}, {2.5, 0.5}, {2.5, 2.5}, {0.5, 2.5}}) mesh.clip.push_back(ScreenToClip(x, y, 0.5, kSize, kSize));
  for (auto winding : {std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}, std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2}}) {
    mesh.indices = winding;
    DepthStencilSurface surface = MakeSurface(kSize, kSize, MakeBuiltinPattern("standard", 1));
    const std::vector<int> counts = CoverageCounts(Rasterize(mesh.Input(), NoDepthNoCull(), surface), kSize, kSize, 1, false);
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) EXPECT_EQ(counts[y * kSize + x], x < 2 && y < 2 ? 1 : 0) << x << "," << y;
    }
  }
}

// Each edge orientation with a sample exactly on it: included for top and left edges only.
TEST(RasterTopLeft, EdgeOrientations) {
  struct Case {
    std::array<std::pair<double, double>, 3> v;
    bool covered;
    const char* what;
  };
  // Sample at the centre of pixel (2, 2) = (2.5, 2.5).
  const Case cases[] = {
      {{{{2.5, 2.5}, {6.5, 2.5}, {2.5, 6.5}}}, true, "top edge and left edge through the sample (vertex)"},
      {{{{0.5, 2.5}, {6.5, 2.5}, {3.5, 6.5}}}, true, "horizontal top edge"},
      {{{{0.5, 2.5}, {6.5, 2.5}, {3.5, -1.5}}}, false, "horizontal bottom edge"},
      {{{{2.5, 0.5}, {2.5, 6.5}, {6.5, 3.5}}}, true, "vertical left edge"},
      {{{{2.5, 0.5}, {2.5, 6.5}, {-1.5, 3.5}}}, false, "vertical right edge"},
      {{{{0.5, 0.5}, {4.5, 4.5}, {4.5, 0.5}}}, true, "diagonal left edge (triangle to its upper right)"},
      {{{{0.5, 0.5}, {4.5, 4.5}, {0.5, 4.5}}}, false, "diagonal right edge (triangle to its lower left)"},
  };
  for (const Case& c : cases) {
    Mesh mesh;
    for (auto [x, y] : c.v) mesh.clip.push_back(ScreenToClip(x, y, 0.5, 8, 8));
    mesh.indices = {0, 1, 2};
    DepthStencilSurface surface = MakeSurface(8, 8, MakeBuiltinPattern("standard", 1));
    const std::vector<int> counts = CoverageCounts(Rasterize(mesh.Input(), NoDepthNoCull(), surface), 8, 8, 1, false);
    EXPECT_EQ(counts[2 * 8 + 2], c.covered ? 1 : 0) << c.what;
  }
}

// Finds every sample's position by sweeping a half-plane's edge across the quad in 1/16-px
// steps (as the Vulkan CTS sample_locations verify_location cases do) and compares with the
// pattern's table.
void ProbeSamplePositions(const SamplePattern& pattern) {
  constexpr int kSize = 2;
  const int count = pattern.Count();
  std::vector<std::array<int, 2>> coveredSteps(static_cast<std::size_t>(kQuadPixels) * count, {0, 0});
  for (int axis = 0; axis < 2; ++axis) {
    for (int k = 0; k <= 16 * kSize; ++k) {
      const double edge = k / 16.0;
      // Half-plane "coordinate >= edge" as a large triangle whose left (or top) edge is the line.
      Mesh mesh;
      if (axis == 0) {
        for (auto [x, y] : {std::pair{edge, -50.0}, {edge + 100.0, 1.0}, {edge, 50.0}}) mesh.clip.push_back(ScreenToClip(x, y, 0.5, kSize, kSize));
      } else {
        for (auto [x, y] : {std::pair{-50.0, edge}, {50.0, edge}, {1.0, edge + 100.0}}) mesh.clip.push_back(ScreenToClip(x, y, 0.5, kSize, kSize));
      }
      mesh.indices = {0, 1, 2};
      DepthStencilSurface surface = MakeSurface(kSize, kSize, pattern);
      const RasterResult result = Rasterize(mesh.Input(), NoDepthNoCull(), surface);
      for (const auto& bin : result.quadsByBin) {
        for (const QuadFragment& q : bin) {
          for (int p = 0; p < kQuadPixels; ++p) {
            for (int s = 0; s < count; ++s) coveredSteps[p * count + s][axis] += q.covered.Sample(p, s);
          }
        }
      }
    }
  }
  for (int p = 0; p < kQuadPixels; ++p) {
    for (int s = 0; s < count; ++s) {
      // The sample at pixel-relative position (8 + o) / 16 is covered for every edge step
      // k / 16 <= its absolute position, i.e. for k = 0 .. 16 * px + 8 + o.
      const int px = p & 1, py = p >> 1;
      const SampleOffset expected = pattern.Offset(p, s);
      EXPECT_EQ(coveredSteps[p * count + s][0] - 1 - 16 * px - 8, expected.x) << pattern.Name() << " pixel " << p << " sample " << s;
      EXPECT_EQ(coveredSteps[p * count + s][1] - 1 - 16 * py - 8, expected.y) << pattern.Name() << " pixel " << p << " sample " << s;
    }
  }
}

TEST(RasterProbe, BuiltinPatternsAreWhereTheTablesSay) {
  for (int count : {1, 2, 4, 8, 16}) ProbeSamplePositions(MakeBuiltinPattern("standard", count));
  for (int count : {2, 4, 8, 16}) ProbeSamplePositions(MakeBuiltinPattern("eqaa", count));
  ProbeSamplePositions(MakeBuiltinPattern("flipquad", 2));
  ProbeSamplePositions(MakeBuiltinPattern("quincunx", 2));
  Random rng(77);
  ProbeSamplePositions(RandomPattern(rng, 16));
}

// The hierarchical walk (full tiles and quads skip sample tests) against testing every sample.
TEST(RasterDifferential, HierarchyMatchesBruteForce) {
  constexpr int kWidth = 70, kHeight = 45;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    Random rng(seed);
    Mesh mesh;
    for (int t = 0; t < 40; ++t) {
      const double size = rng.Uniform(0.2, 60.0);
      const double cx = rng.Uniform(-10, kWidth + 10), cy = rng.Uniform(-10, kHeight + 10);
      for (int v = 0; v < 3; ++v) {
        mesh.clip.push_back(ScreenToClip(cx + rng.Uniform(-size, size), cy + rng.Uniform(-size, size), rng.Uniform(0, 1), kWidth, kHeight));
        mesh.indices.push_back(static_cast<std::uint32_t>(mesh.indices.size()));
      }
    }
    const int count = 1 << (seed % 5);
    const SamplePattern pattern = seed % 2 ? MakeBuiltinPattern("standard", count) : RandomPattern(rng, count);
    DrawState state;
    state.cull = CullMode::None;
    const auto reference = testing::ReferenceRasterize(mesh.Input(), state, pattern, kWidth, kHeight);
    // Hi-Z drops whole tiles before coverage is computed, so compare coverage without it ...
    state.depth.hiZEnable = false;
    DepthStencilSurface surface = MakeSurface(kWidth, kHeight, pattern, std::min(count, 8));
    const RasterResult result = Rasterize(mesh.Input(), state, surface);
    EXPECT_EQ(CoverageCounts(result, kWidth, kHeight, count, false), reference.covered) << "seed " << seed;
    if (count > kMaxDepthSamples) continue;
    // ... and the depth results with it: every sample anchored makes them exact whatever the
    // tiles' compression state, and hi-Z may only drop work that would fail anyway.
    EXPECT_EQ(CoverageCounts(result, kWidth, kHeight, count, true), reference.passed) << "seed " << seed;
    state.depth.hiZEnable = true;
    surface.Clear(1.0f, 0);
    const RasterResult withHiZ = Rasterize(mesh.Input(), state, surface);
    EXPECT_EQ(CoverageCounts(withHiZ, kWidth, kHeight, count, true), reference.passed) << "seed " << seed;
  }
}

TEST(RasterCentroid, FirstCoveredSampleInPriorityOrder) {
  const SamplePattern pattern = MakeBuiltinPattern("standard", 4);
  // Half-plane x >= 1.5 + 1/16: covers samples of pixel 1 with offset x >= 1 only.
  Mesh mesh;
  for (auto [x, y] : {std::pair{1.5 + 1 / 16.0, -50.0}, {101.0, 1.0}, {1.5 + 1 / 16.0, 50.0}}) mesh.clip.push_back(ScreenToClip(x, y, 0.5, 2, 2));
  mesh.indices = {0, 1, 2};
  DepthStencilSurface surface = MakeSurface(2, 2, pattern);
  const RasterResult result = Rasterize(mesh.Input(), NoDepthNoCull(), surface);
  ASSERT_EQ(result.QuadCount(), 1u);
  const QuadFragment& q = result.quadsByBin[0][0];
  const SampleMask mask = q.covered.Pixel(1);
  ASSERT_NE(mask, 0);
  ASSERT_NE(mask, AllSamples(4));
  std::uint8_t expected = kCentroidNone;
  for (std::uint8_t s : pattern.CentroidPriority()) {
    if ((mask >> s) & 1) {
      expected = s;
      break;
    }
  }
  EXPECT_EQ(q.centroid[1], expected);
  EXPECT_EQ(q.centroid[0], kCentroidNone);
  const auto position = CentroidPosition(q, 1, pattern);
  const auto sample = SamplePosition(1, 0, pattern, expected);
  EXPECT_EQ(position, sample);
}

// One oversized triangle covering the screen: every tile and quad is full, no sample is
// tested individually, every sample is covered and passes against a cleared depth buffer.
TEST(RasterCounters, FullScreenTriangle) {
  constexpr int kWidth = 64, kHeight = 48, kSamples = 4;
  Mesh mesh;
  mesh.clip = {{-1, -1, 0.5f, 1}, {3, -1, 0.5f, 1}, {-1, 3, 0.5f, 1}};
  mesh.indices = {0, 1, 2};
  DepthStencilSurface surface = MakeSurface(kWidth, kHeight, MakeBuiltinPattern("standard", kSamples));
  const RasterCounters c = Rasterize(mesh.Input(), DrawState{}, surface).counters;
  const std::uint64_t tiles = (kWidth / 8) * (kHeight / 8), quads = kWidth * kHeight / 4;
  EXPECT_EQ(c.trianglesIn, 1u);
  EXPECT_EQ(c.trianglesRasterized, 1u);
  EXPECT_EQ(c.trianglesClipped, 0u);
  EXPECT_EQ(c.tilesFull, tiles);
  EXPECT_EQ(c.tilesPartial, 0u);
  EXPECT_EQ(c.tilesEmpty, 0u);
  EXPECT_EQ(c.quadsFull, quads);
  EXPECT_EQ(c.quadsLive4, quads);
  EXPECT_EQ(c.samplesTested, 0u);
  EXPECT_EQ(c.samplesCovered, std::uint64_t{kWidth} * kHeight * kSamples);
  EXPECT_EQ(c.samplesDepthPassed, c.samplesCovered);
  EXPECT_EQ(c.zTilesCompressedAtEnd, tiles);
  EXPECT_EQ(c.zPlaneDecompressions, 0u);
}

// Two triangles forming a full-screen quad: shared diagonal, every sample covered once; the
// tiles the diagonal crosses are partial for both triangles.
TEST(RasterCounters, FullScreenQuadPair) {
  constexpr int kSize = 64, kSamples = 8;
  Mesh mesh;
  mesh.clip = {{-1, 1, 0.5f, 1}, {1, 1, 0.5f, 1}, {1, -1, 0.5f, 1}, {-1, -1, 0.5f, 1}};
  mesh.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise in NDC: front-facing
  DepthStencilSurface surface = MakeSurface(kSize, kSize, MakeBuiltinPattern("standard", kSamples));
  const RasterResult result = Rasterize(mesh.Input(), DrawState{}, surface);
  const RasterCounters& c = result.counters;
  EXPECT_EQ(c.trianglesRasterized, 2u);
  EXPECT_EQ(c.trianglesCulled, 0u);
  EXPECT_EQ(c.samplesCovered, std::uint64_t{kSize} * kSize * kSamples);
  EXPECT_EQ(c.samplesDepthPassed, c.samplesCovered);
  // The diagonal from (0,0) to (64,64) crosses the 8 diagonal tiles; each triangle owns the 28
  // tiles strictly on its side in full.
  EXPECT_EQ(c.tilesPartial, 2u * 8);
  EXPECT_EQ(c.tilesFull, 2u * 28);
  // Quads on the diagonal are shared: the live-pixel histogram counts each triangle's part.
  EXPECT_EQ(c.quadsLive0 + c.quadsLive1 + c.quadsLive2 + c.quadsLive3 + c.quadsLive4,
            c.quadsPartial + c.quadsFull);
  EXPECT_EQ(result.QuadCount(), c.quadsPartial + c.quadsFull - c.quadsLive0);
}

TEST(RasterCounters, CullingAndZeroArea) {
  Mesh mesh;
  mesh.clip = {{-1, -1, 0.5f, 1}, {1, -1, 0.5f, 1}, {-1, 1, 0.5f, 1}, {0.5f, 0.5f, 0.5f, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 1, 0, 0, 1, 3, 3, 3};
  DepthStencilSurface surface = MakeSurface(16, 16, MakeBuiltinPattern("standard", 1));
  DrawState state;
  state.cull = CullMode::Back;
  RasterCounters c = Rasterize(mesh.Input(), state, surface).counters;
  EXPECT_EQ(c.trianglesIn, 4u);
  EXPECT_EQ(c.trianglesRasterized, 1u);
  EXPECT_EQ(c.trianglesCulled, 1u);
  EXPECT_EQ(c.trianglesZeroArea, 2u);
  state.cull = CullMode::Front;
  surface.Clear(1.0f, 0);
  c = Rasterize(mesh.Input(), state, surface).counters;
  EXPECT_EQ(c.trianglesRasterized, 1u);
  EXPECT_EQ(c.trianglesCulled, 1u);
}

TEST(RasterInput, BadInputsNameTheProblem) {
  DepthStencilSurface surface = MakeSurface(8, 8, MakeBuiltinPattern("standard", 1));
  const std::vector<glm::vec4> positions = {{0, 0, 0.5f, 1}, {1, 0, 0.5f, 1}, {0, 1, 0.5f, 1}, {NAN, 0, 0, 1}};
  const std::vector<std::uint32_t> outOfRange = {0, 1, 7};
  const std::vector<std::uint32_t> notTriangles = {0, 1};
  auto message = [&](std::span<const glm::vec4> p, std::span<const std::uint32_t> i) {
    try {
      Rasterize(DrawInput{p, i, 0}, DrawState{}, surface);
    } catch (const RasterError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(std::span(positions).first(3), outOfRange).find("index 7 at position 2 is out of range (3 vertices)"), std::string::npos);
  EXPECT_NE(message(positions, notTriangles).find("not a multiple of 3"), std::string::npos);
  EXPECT_NE(message(positions, std::vector<std::uint32_t>{0, 1, 2}).find("vertex 3 has a non-finite"), std::string::npos);
}

TEST(RasterInput, ImpossibleSurfacesAreRefused) {
  auto message = [](DepthSurfaceConfig config, int patternSamples) {
    try {
      DepthStencilSurface surface(config, MakeBuiltinPattern("standard", patternSamples));
    } catch (const RasterError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  DepthSurfaceConfig good{16, 16, 4, 4};
  EXPECT_EQ(message(good, 4), "no error");
  DepthSurfaceConfig c = good;
  c.depthSamples = 8;
  c.coverageSamples = 4;
  EXPECT_NE(message(c, 4).find("need S >= Z"), std::string::npos);
  c = good;
  c.coverageSamples = 3;
  EXPECT_NE(message(c, 4).find("3 coverage samples"), std::string::npos);
  c = good;
  c.width = kMaxDimension + 1;
  EXPECT_NE(message(c, 4).find("outside 1..16384"), std::string::npos);
  c = good;
  c.maxZPlanes = 17;
  EXPECT_NE(message(c, 4).find("max Z planes 17"), std::string::npos);
  EXPECT_NE(message(good, 8).find("has 8 samples but the surface has 4"), std::string::npos);
}

}  // namespace
}  // namespace raster
