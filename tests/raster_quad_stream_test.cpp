// The quad stream is bounded: deep overdraw (200k stacked triangles at 256x256 once took 5 GB)
// is refused with one line naming the limit, and whether a draw is refused depends only on its
// quad count, never on the thread count.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <string>
#include <vector>

#include "raster/raster_error.h"
#include "raster/rasterizer.h"
#include "raster/sample_pattern.h"
#include "raster_test_util.h"

namespace raster {
namespace {

constexpr int kSize = 64;  // 32x32 = 1024 quads per full-screen triangle pair

// `layers` copies of a full-screen quad (two triangles), no depth test: every layer adds the
// 32x32 quads of the screen to the stream, and those on the diagonal twice.
struct StackedQuads {
  std::vector<glm::vec4> clip;
  std::vector<std::uint32_t> indices;
  explicit StackedQuads(int layers) {
    for (int layer = 0; layer < layers; ++layer) {
      const auto base = static_cast<std::uint32_t>(clip.size());
      constexpr int kCorners[4][2] = {{0, 0}, {kSize, 0}, {0, kSize}, {kSize, kSize}};
      for (const auto& corner : kCorners) {
        clip.push_back(testing::ScreenToClip(corner[0], corner[1], 0.5, kSize, kSize));
      }
      for (std::uint32_t i : {0u, 1u, 2u, 2u, 1u, 3u}) indices.push_back(base + i);
    }
  }
  DrawInput Input() const { return {clip, indices, 0}; }
};

RasterResult Draw(const StackedQuads& mesh, std::size_t maxQuads) {
  DepthSurfaceConfig config;
  config.width = kSize;
  config.height = kSize;
  DepthStencilSurface surface(config, MakeBuiltinPattern("standard", 1));
  DrawState state;
  state.cull = CullMode::None;
  state.depth.testEnable = false;
  RasterOptions options;
  options.maxQuads = maxQuads;
  return Rasterize(mesh.Input(), state, surface, options);
}

TEST(RasterQuadStream, ADrawAtTheLimitIsKeptOnePastItIsRefused) {
  const StackedQuads mesh(6);
  // Quads on the shared diagonal come once per triangle, so the count is taken from a free draw.
  const std::size_t kQuads = Draw(mesh, RasterOptions{}.maxQuads).QuadCount();
  EXPECT_GT(kQuads, std::size_t{6 * (kSize / 2) * (kSize / 2)});
  for (int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    EXPECT_EQ(Draw(mesh, kQuads).QuadCount(), kQuads);
    try {
      Draw(mesh, kQuads - 1);
      ADD_FAILURE() << "no error";
    } catch (const RasterError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("more than " + std::to_string(kQuads - 1) + " quads"), std::string::npos) << message;
      EXPECT_NE(message.find("kMaxQuadStreamBytes"), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace raster
