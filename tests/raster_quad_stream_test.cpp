// The quad stream is bounded: deep overdraw (200k stacked triangles at 256x256 once took 5 GB)
// is refused with one line naming the limit, and whether a draw is refused depends only on its
// quad count, never on the thread count. Through the command line the line also names the scene.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_test_util.h"
#include "raster/limits.h"
#include "raster/raster_error.h"
#include "raster/rasterizer.h"
#include "raster/sample_pattern.h"
#include "raster_test_util.h"
#include "scenes_test_util.h"

namespace raster {
namespace {

constexpr int kQuadStreamSize = 64;  // 32x32 = 1024 quads per full-screen triangle pair

// `layers` copies of a full-screen quad (two triangles), no depth test: every layer adds the
// 32x32 quads of the screen to the stream, and those on the diagonal twice.
struct StackedQuads {
  std::vector<glm::vec4> clip;
  std::vector<std::uint32_t> indices;
  explicit StackedQuads(int layers) {
    for (int layer = 0; layer < layers; ++layer) {
      const auto base = static_cast<std::uint32_t>(clip.size());
      constexpr int kCorners[4][2] = {{0, 0}, {kQuadStreamSize, 0}, {0, kQuadStreamSize}, {kQuadStreamSize, kQuadStreamSize}};
      for (const auto& corner : kCorners) {
        clip.push_back(testing::ScreenToClip(corner[0], corner[1], 0.5, kQuadStreamSize, kQuadStreamSize));
      }
      for (std::uint32_t i : {0u, 1u, 2u, 2u, 1u, 3u}) indices.push_back(base + i);
    }
  }
  DrawInput Input() const { return {clip, indices, 0}; }
};

RasterResult DrawStacked(const StackedQuads& mesh, std::size_t maxQuads) {
  DepthSurfaceConfig config;
  config.width = kQuadStreamSize;
  config.height = kQuadStreamSize;
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
  const std::size_t kQuads = DrawStacked(mesh, RasterOptions{}.maxQuads).QuadCount();
  EXPECT_GT(kQuads, std::size_t{6 * (kQuadStreamSize / 2) * (kQuadStreamSize / 2)});
  for (int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    EXPECT_EQ(DrawStacked(mesh, kQuads).QuadCount(), kQuads);
    try {
      DrawStacked(mesh, kQuads - 1);
      ADD_FAILURE() << "no error";
    } catch (const QuadStreamError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("more than " + std::to_string(kQuads - 1) + " quads"), std::string::npos) << message;
      EXPECT_NE(message.find("kMaxQuadStreamBytes"), std::string::npos) << message;
      EXPECT_NE(message.find("64x64"), std::string::npos) << message;
    }
  }
}

// --- End to end: `aasim raster` and `aasim frame` name the scene and the limit ---

namespace fs = std::filesystem;

class CliQuadStream : public cli::testing::ScratchDirTest {};

// `layers` squares [-1, 1]^2 stacked along +z, counter-clockwise seen from +z, where the default
// camera looks from (scenes::FrameBounds): each layer is nearer than the last, so every one passes
// the depth test and hi-Z rejects none. At 1024x1024 a layer is ~85k quads; 320 layers pass the
// 22.4M quads of kMaxQuadStreamBytes.
std::string StackedSquaresGltf(int layers) {
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  for (int layer = 0; layer < layers; ++layer) {
    const float z = 0.5f * static_cast<float>(layer) / static_cast<float>(layers);
    const auto base = static_cast<std::uint32_t>(positions.size() / 3);
    positions.insert(positions.end(), {-1, -1, z, 1, -1, z, -1, 1, z, 1, 1, z});
    for (std::uint32_t i : {0u, 1u, 2u, 2u, 1u, 3u}) indices.push_back(base + i);
  }
  return scenes_test::TriangleGltf(positions, indices);
}

TEST_F(CliQuadStream, TooDeepAnOverdrawIsOneLineNamingTheSceneAndTheLimit) {
  const fs::path scene = cli::testing::WriteFile(scratch_ / "stacked.gltf", StackedSquaresGltf(320));
  const std::string kMaxQuads = std::to_string(kMaxQuadStreamBytes / sizeof(QuadFragment));
  // One sample per pixel keeps the 22.4M quads cheap; `frame` then needs the 1S/1Z/1F mode.
  for (const std::vector<std::string>& command : {std::vector<std::string>{"raster"}, {"frame", "--fragments", "1"}}) {
    SCOPED_TRACE(command[0]);
    const fs::path out = scratch_ / "out";
    std::vector<std::string> args = command;
    args.insert(args.end(), {"--scene", scene.string(), "--width", "1024", "--height", "1024", "--samples", "1",
                             "--depth-samples", "1", "--out", out.string()});
    const cli::testing::CommandResult run = cli::testing::RunAasim(args, scratch_);
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_EQ(run.err.rfind("aasim: " + scene.string() + ": the draw streams more than " + kMaxQuads + " quads", 0),
              0u)
        << run.err;
    EXPECT_NE(run.err.find("kMaxQuadStreamBytes (1073741824 bytes"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("1024x1024"), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
}  // namespace raster
