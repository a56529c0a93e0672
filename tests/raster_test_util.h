#pragma once
// Shared helpers for the raster tests: screen-space triangles as clip-space input, per-sample
// coverage tallies from a quad stream, and a slow reference rasterizer for differential tests.

#include <cstdint>
#include <random>
#include <vector>

#include <glm/vec4.hpp>

#include "raster/rasterizer.h"

namespace raster::testing {

// Screen position (pixels, +y down) and depth to D3D clip space with w = 1.
inline glm::vec4 ScreenToClip(double sx, double sy, double z, int width, int height) {
  return {static_cast<float>(sx / width * 2.0 - 1.0), static_cast<float>(1.0 - sy / height * 2.0),
          static_cast<float>(z), 1.0f};
}

struct Mesh {
  std::vector<glm::vec4> clip;
  std::vector<std::uint32_t> indices;
  DrawInput Input() const { return DrawInput{clip, indices, 0}; }
};

// How many quads covered each sample: [(y * width + x) * S + s].
inline std::vector<int> CoverageCounts(const RasterResult& result, int width, int height, int samples,
                                       bool afterDepth) {
  std::vector<int> counts(static_cast<std::size_t>(width) * height * samples, 0);
  for (const auto& bin : result.quadsByBin) {
    for (const QuadFragment& q : bin) {
      const QuadCoverage mask = afterDepth ? q.passed : q.covered;
      for (int p = 0; p < kQuadPixels; ++p) {
        for (int s = 0; s < samples; ++s) {
          if (!mask.Sample(p, s)) continue;
          const int x = q.x + (p & 1), y = q.y + (p >> 1);
          ++counts[(static_cast<std::size_t>(y) * width + x) * samples + s];
        }
      }
    }
  }
  return counts;
}

// Deterministic uniform doubles (no std distributions: their output differs between libraries).
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double Uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  }
  int Int(int lo, int hiInclusive) {
    return lo + static_cast<int>(engine_() % static_cast<std::uint64_t>(hiInclusive - lo + 1));
  }

 private:
  std::mt19937_64 engine_;
};

// A jittered grid of (cols+1) x (rows+1) shared vertices spanning [x0,x1] x [y0,y1] in pixels,
// two triangles per cell with a random diagonal: a watertight mesh. Jitter below 0.15 of a
// cell keeps every cell convex (an affine image of a square whose corners move less than a
// third of the distance to the diagonal), so the triangles never overlap.
inline Mesh JitteredGrid(Random& rng, int cols, int rows, double x0, double y0, double x1, double y1,
                         int width, int height) {
  Mesh mesh;
  const double cw = (x1 - x0) / cols, ch = (y1 - y0) / rows;
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= cols; ++i) {
      const bool border = i == 0 || j == 0 || i == cols || j == rows;
      const double jx = border ? 0.0 : rng.Uniform(-0.15, 0.15) * cw;
      const double jy = border ? 0.0 : rng.Uniform(-0.15, 0.15) * ch;
      mesh.clip.push_back(ScreenToClip(x0 + i * cw + jx, y0 + j * ch + jy, rng.Uniform(0.1, 0.9), width, height));
    }
  }
  auto v = [&](int i, int j) { return static_cast<std::uint32_t>(j * (cols + 1) + i); };
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      if (rng.Int(0, 1)) {
        mesh.indices.insert(mesh.indices.end(), {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i, j + 1)});
      } else {
        mesh.indices.insert(mesh.indices.end(), {v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
      }
    }
  }
  return mesh;
}

// Triangles of random size up to maxSize px with random depth, scattered over the viewport.
inline Mesh RandomSoup(Random& rng, int triangles, int width, int height, double maxSize) {
  Mesh mesh;
  for (int t = 0; t < triangles; ++t) {
    const double size = rng.Uniform(0.5, maxSize);
    const double cx = rng.Uniform(0, width), cy = rng.Uniform(0, height);
    for (int v = 0; v < 3; ++v) {
      mesh.clip.push_back(ScreenToClip(cx + rng.Uniform(-size, size), cy + rng.Uniform(-size, size), rng.Uniform(0.05, 0.95), width, height));
      mesh.indices.push_back(static_cast<std::uint32_t>(mesh.indices.size()));
    }
  }
  return mesh;
}

// Slow reference: every sample of every pixel in a triangle's bounds tested directly against
// the edge functions, depth kept for all S samples (what an uncompressed, fully anchored
// surface would hold). Per-sample coverage before and after the depth test is returned.
struct ReferenceResult {
  std::vector<int> covered;
  std::vector<int> passed;
  std::vector<float> depth;  // [(y * width + x) * S + s]
};

inline ReferenceResult ReferenceRasterize(const DrawInput& input, const DrawState& state,
                                          const SamplePattern& pattern, int width, int height) {
  const int samples = pattern.Count();
  const std::size_t n = static_cast<std::size_t>(width) * height * samples;
  ReferenceResult ref{std::vector<int>(n, 0), std::vector<int>(n, 0), std::vector<float>(n, 1.0f)};
  RasterCounters counters;
  for (std::size_t t = 0; t < input.indices.size() / 3; ++t) {
    std::vector<TriangleSetup> setups;
    SetupTriangle({input.clipPositions[input.indices[3 * t]], input.clipPositions[input.indices[3 * t + 1]],
                   input.clipPositions[input.indices[3 * t + 2]]},
                  static_cast<std::uint32_t>(t), Viewport{width, height}, state.cull, setups, counters);
    for (const TriangleSetup& tri : setups) {
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          for (int s = 0; s < samples; ++s) {
            const SampleOffset o = pattern.Offset(QuadPixelIndex(x, y), s);
            const std::int64_t sx = SampleX(x, o.x), sy = SampleY(y, o.y);
            bool inside = true;
            for (const EdgeFunction& e : tri.edges) inside &= e.Evaluate(sx, sy) >= 0;
            if (!inside) continue;
            const std::size_t i = (static_cast<std::size_t>(y) * width + x) * samples + s;
            ++ref.covered[i];
            const float z = tri.depth.Evaluate(sx, sy);
            if (!state.depth.testEnable || Compare(state.depth.func, z, ref.depth[i])) {
              ++ref.passed[i];
              if (state.depth.writeEnable) ref.depth[i] = z;
            }
          }
        }
      }
    }
  }
  return ref;
}

}  // namespace raster::testing
