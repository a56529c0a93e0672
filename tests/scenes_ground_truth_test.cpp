// Tests of the Embree ground truth (scenes/ground_truth.h) and the normals it shares with the
// raster path (scenes/normals.h): analytic half-plane scenes with known per-pixel coverage,
// exact shading of covered pixels, the edge mask, determinism across thread counts, the disk
// cache with its corruption checks, and input validation.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>

#include "scenes/ground_truth.h"
#include "scenes/normals.h"
#include "scenes/scene.h"
#include "scenes/shading.h"
#include "scenes_test_util.h"

namespace {

namespace fs = std::filesystem;

// The test camera: at (0, 0, kDistance) looking at the origin, so the plane z = 0 is parallel
// to the image and screen positions map to it by a scale and an offset.
constexpr float kDistance = 2.0f;
constexpr float kFov = 0.8f;

scenes::Camera TestCamera() {
  scenes::Camera camera;
  camera.eye = {0.0f, 0.0f, kDistance};
  camera.target = {0.0f, 0.0f, 0.0f};
  camera.up = {0.0f, 1.0f, 0.0f};
  camera.verticalFovRadians = kFov;
  camera.zNear = 0.5f;
  camera.zFar = 10.0f;
  return camera;
}

// Screen position (D3D: +y down, pixels of unit size) -> the point of the plane z = 0 it shows.
glm::vec3 ScreenToWorld(glm::dvec2 screen, int width, int height) {
  const double halfHeight = static_cast<double>(kDistance) * std::tan(0.5 * static_cast<double>(kFov));
  const double halfWidth = halfHeight * width / height;
  return {static_cast<float>((2.0 * screen.x / width - 1.0) * halfWidth),
          static_cast<float>((1.0 - 2.0 * screen.y / height) * halfHeight), 0.0f};
}

// One triangle on z = 0 with normal +z whose edge runs along the screen line through a and b and
// whose other two edges stay hundreds of pixels off screen: the covered region on screen is the
// half-plane on `inside`'s side of the line. Front-facing unless `backFacing`.
scenes::Scene HalfPlaneScene(int width, int height, glm::dvec2 a, glm::dvec2 b, glm::dvec2 inside,
                             bool backFacing = false) {
  constexpr double kFar = 2000.0;
  const glm::dvec2 along = glm::normalize(b - a);
  glm::dvec2 normal{-along.y, along.x};
  if (glm::dot(normal, inside - a) < 0.0) normal = -normal;
  std::array<glm::dvec2, 3> screen{a - along * kFar, a + along * kFar, a + normal * kFar};
  std::array<glm::vec3, 3> world{};
  for (std::size_t i = 0; i < 3; ++i) world[i] = ScreenToWorld(screen[i], width, height);
  const bool counterClockwise = glm::cross(world[1] - world[0], world[2] - world[0]).z > 0.0f;
  if (counterClockwise == backFacing) std::swap(world[1], world[2]);

  scenes::Scene scene;
  scene.name = "half-plane";
  scenes::Mesh mesh;
  mesh.name = "edge";
  mesh.positions = {world.begin(), world.end()};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.indices = {0, 1, 2};
  mesh.material = 0;
  scene.meshes.push_back(mesh);
  scene.materials.push_back({.name = "flat", .baseColourFactor = {0.3f, 0.6f, 0.9f, 1.0f}, .baseColourTexture = -1});
  scene.bounds = scenes::ComputeBounds(scene.meshes);
  scene.camera = TestCamera();
  return scene;
}

scenes::GroundTruthSettings GroundTruthSettingsFor(int width, int height, int samples) {
  scenes::GroundTruthSettings settings;
  settings.width = width;
  settings.height = height;
  settings.samplesPerPixel = samples;
  return settings;
}

scenes::GroundTruthImage RenderGroundTruth(const scenes::Scene& scene, const scenes::GroundTruthSettings& settings) {
  return scenes::RenderGroundTruth(scene, scene.camera, settings);
}

// Area of the unit pixel [x, x+1] x [y, y+1] on `inside`'s side of the line through a and b:
// the pixel square clipped by one half-plane (Sutherland-Hodgman), then the shoelace formula.
double AnalyticCoverage(int x, int y, glm::dvec2 a, glm::dvec2 b, glm::dvec2 inside) {
  const glm::dvec2 along = b - a;
  auto side = [&](glm::dvec2 p) { return along.x * (p.y - a.y) - along.y * (p.x - a.x); };
  const double sign = side(inside) > 0.0 ? 1.0 : -1.0;
  const std::array<glm::dvec2, 4> square{{{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}}};
  std::vector<glm::dvec2> clipped;
  for (std::size_t i = 0; i < square.size(); ++i) {
    const glm::dvec2 p = square[i], q = square[(i + 1) % square.size()];
    const double sp = sign * side(p), sq = sign * side(q);
    if (sp >= 0.0) clipped.push_back(p);
    if ((sp >= 0.0) != (sq >= 0.0)) clipped.push_back(p + (q - p) * (sp / (sp - sq)));
  }
  double twiceArea = 0.0;
  for (std::size_t i = 0; i < clipped.size(); ++i) {
    const glm::dvec2 p = clipped[i], q = clipped[(i + 1) % clipped.size()];
    twiceArea += p.x * q.y - q.x * p.y;
  }
  return std::abs(twiceArea) * 0.5;
}

bool SameBits(const scenes::GroundTruthImage& a, const scenes::GroundTruthImage& b) {
  return a.width == b.width && a.height == b.height && a.samplesPerPixel == b.samplesPerPixel &&
         a.colour.size() == b.colour.size() && a.coverage.size() == b.coverage.size() && a.edge == b.edge &&
         std::memcmp(a.colour.data(), b.colour.data(), a.colour.size() * sizeof(glm::vec3)) == 0 &&
         std::memcmp(a.coverage.data(), b.coverage.data(), a.coverage.size() * sizeof(float)) == 0;
}

// A fresh directory per test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("aasim-gt-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& Path() const { return path_; }

 private:
  fs::path path_;
};

// Sets an environment variable for one scope and restores the previous value.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value != nullptr) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// --- Shared normals (scenes/normals.h). ---

TEST(GroundTruthNormals, SmoothNormalsAreAreaWeightedAndNeverZero) {
  // A flat quad in z = 0, counter-clockwise seen from +z, and one unused vertex.
  const std::vector<glm::vec3> flat{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {5, 5, 5}};
  const std::vector<glm::vec3> normals = scenes::SmoothNormals(flat, std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
  for (const glm::vec3& n : normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));

  // A roof: a big face tilted towards +x and a small one towards -y share edge 0-1; their shared
  // vertices lean towards the big face.
  const std::vector<glm::vec3> roof{{0, 0, 0}, {0, 0, 1}, {4, 0, 0}, {0, -1, 0}};
  const std::vector<glm::vec3> leaning = scenes::SmoothNormals(roof, std::vector<std::uint32_t>{0, 2, 1, 0, 1, 3});
  EXPECT_NEAR(glm::length(leaning[0]), 1.0f, 1e-6f);
  EXPECT_GT(std::abs(leaning[0].y), std::abs(leaning[0].x));
}

TEST(GroundTruthNormals, VertexNormalsPreferTheMeshsOwn) {
  scenes::Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2};
  EXPECT_EQ(scenes::VertexNormals(mesh), std::vector<glm::vec3>(3, glm::vec3(0, 0, 1)));
  mesh.normals = {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
  EXPECT_EQ(scenes::VertexNormals(mesh), mesh.normals);
}

// --- Rendering. ---

// A vertical edge at x = 20.3: columns right of it are covered, column 20 is 70% covered.
TEST(GroundTruth, CoveredPixelsShadeExactlyLikeShadeLambertAndTheEdgeColumnIsMarked) {
  constexpr int kWidth = 48, kHeight = 32;
  const scenes::Scene scene = HalfPlaneScene(kWidth, kHeight, {20.3, 0.0}, {20.3, 1.0}, {40.0, 16.0});
  const scenes::GroundTruthSettings settings = GroundTruthSettingsFor(kWidth, kHeight, 256);
  const scenes::GroundTruthImage image = RenderGroundTruth(scene, settings);
  ASSERT_EQ(image.colour.size(), std::size_t{kWidth} * kHeight);

  const glm::vec3 lit = scenes::ShadeLambert(scene.lighting, glm::vec3(scenes::BaseColour(scene, 0, glm::vec2(0.0f))),
                                             glm::vec3(0.0f, 0.0f, 1.0f));
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t i = image.Index(x, y);
      if (x > 20) {
        EXPECT_EQ(image.colour[i], lit) << x << "," << y;
        EXPECT_EQ(image.coverage[i], 1.0f);
        EXPECT_EQ(image.edge[i], 0);
      } else if (x < 20) {
        EXPECT_EQ(image.colour[i], settings.clearColour) << x << "," << y;
        EXPECT_EQ(image.coverage[i], 0.0f);
        EXPECT_EQ(image.edge[i], 0);
      } else {
        // 16 x 16 strata: columns 0-3 lie left of 0.3, column 4 straddles it, 5-15 lie right.
        EXPECT_GE(image.coverage[i], 11.0f * 16.0f / 256.0f);
        EXPECT_LE(image.coverage[i], 12.0f * 16.0f / 256.0f);
        EXPECT_EQ(image.edge[i], 1);
        const glm::vec3 blend = lit * image.coverage[i] + settings.clearColour * (1.0f - image.coverage[i]);
        EXPECT_NEAR(glm::length(image.colour[i] - blend), 0.0f, 1e-6f);
      }
    }
  }
}

// A horizontal edge at y = 10.6 covering what lies below it: screen +y is down, as in D3D.
TEST(GroundTruth, ScreenYPointsDown) {
  constexpr int kWidth = 24, kHeight = 16;
  const scenes::Scene scene = HalfPlaneScene(kWidth, kHeight, {0.0, 10.6}, {1.0, 10.6}, {12.0, 15.0});
  const scenes::GroundTruthImage image = RenderGroundTruth(scene, GroundTruthSettingsFor(kWidth, kHeight, 16));
  for (int x = 0; x < kWidth; ++x) {
    EXPECT_EQ(image.coverage[image.Index(x, 9)], 0.0f);
    EXPECT_GT(image.coverage[image.Index(x, 10)], 0.0f);
    EXPECT_LT(image.coverage[image.Index(x, 10)], 1.0f);
    EXPECT_EQ(image.coverage[image.Index(x, 11)], 1.0f);
  }
}

// The raster kernel negates the normal of back-facing triangles; the ground truth must too.
TEST(GroundTruth, BackFacingTrianglesShadeWithTheNegatedNormal) {
  constexpr int kWidth = 16, kHeight = 16;
  const scenes::Scene scene =
      HalfPlaneScene(kWidth, kHeight, {-1.0, 0.0}, {-1.0, 1.0}, {8.0, 8.0}, /*backFacing=*/true);
  const scenes::GroundTruthImage image = RenderGroundTruth(scene, GroundTruthSettingsFor(kWidth, kHeight, 4));
  const glm::vec3 base = glm::vec3(scenes::BaseColour(scene, 0, glm::vec2(0.0f)));
  const glm::vec3 expected = scenes::ShadeLambert(scene.lighting, base, glm::vec3(0.0f, 0.0f, -1.0f));
  ASSERT_NE(expected, scenes::ShadeLambert(scene.lighting, base, glm::vec3(0.0f, 0.0f, 1.0f)));
  for (const glm::vec3& colour : image.colour) EXPECT_EQ(colour, expected);
}

// A slanted edge: per-pixel coverage converges to the exact area as the strata get finer.
TEST(GroundTruth, CoverageConvergesToTheAnalyticArea) {
  constexpr int kSize = 32;
  const glm::dvec2 a{0.0, 7.3}, b{32.0, 19.1}, inside{0.0, 31.0};
  const scenes::Scene scene = HalfPlaneScene(kSize, kSize, a, b, inside);
  double previousMean = 1.0, meanAt16 = 0.0;
  for (const int samples : {16, 64, 256, 1024}) {
    const scenes::GroundTruthImage image = RenderGroundTruth(scene, GroundTruthSettingsFor(kSize, kSize, samples));
    double sumError = 0.0, maxError = 0.0, rendered = 0.0, exact = 0.0;
    int crossed = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const double area = AnalyticCoverage(x, y, a, b, inside);
        const double coverage = static_cast<double>(image.coverage[image.Index(x, y)]);
        rendered += coverage;
        exact += area;
        const double error = std::abs(coverage - area);
        maxError = std::max(maxError, error);
        if (area > 0.0 && area < 1.0) {
          sumError += error;
          ++crossed;
        } else {
          EXPECT_EQ(error, 0.0) << "pixel " << x << "," << y << " away from the edge at " << samples << " spp";
        }
      }
    }
    const double meanError = sumError / crossed;
    EXPECT_LT(meanError, previousMean) << samples << " spp";
    previousMean = meanError;
    if (samples == 16) meanAt16 = meanError;
    if (samples == 1024) {
      // Jittered strata: about sqrt(n) of them straddle the edge, each off by less than 1/n
      // with random sign, so the error falls like n^-3/4 (measured mean per crossed pixel:
      // 0.034, 0.013, 0.0051, 0.0014 at 16, 64, 256, 1024 spp; worst pixel 0.0043 at 1024).
      // The bounds leave room for another jitter sequence, not for a wrong rate or a bias.
      EXPECT_LT(meanError, meanAt16 / 10.0);
      EXPECT_LT(meanError, 2.5e-3);
      EXPECT_LT(maxError, 1e-2);
      // Over the ~45 crossed pixels the errors cancel: the covered area is within 0.02 px of
      // the exact 32 x 32 - (7.3 + 19.1) / 2 * 32 (measured 0.006).
      EXPECT_NEAR(rendered, exact, 0.02);
      EXPECT_NEAR(exact, 32.0 * 32.0 - (7.3 + 19.1) / 2.0 * 32.0, 1e-9);
    }
  }
}

// The edge mask marks only pixels the edge crosses, and every pixel it crosses with at least
// 1/8 of the area on each side (such a part always holds a whole stratum of a 16 x 16 grid, so
// a sample lands there whatever the jitter).
TEST(GroundTruth, EdgeMaskMarksThePixelsTheEdgeCrosses) {
  constexpr int kSize = 32;
  const glm::dvec2 a{0.0, 7.3}, b{32.0, 19.1}, inside{0.0, 31.0};
  const scenes::GroundTruthImage image =
      RenderGroundTruth(HalfPlaneScene(kSize, kSize, a, b, inside), GroundTruthSettingsFor(kSize, kSize, 256));
  int marked = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const double area = AnalyticCoverage(x, y, a, b, inside);
      const bool edge = image.edge[image.Index(x, y)] != 0;
      marked += edge ? 1 : 0;
      if (edge) {
        EXPECT_TRUE(area > 0.0 && area < 1.0) << x << "," << y;
      }
      if (std::min(area, 1.0 - area) >= 0.125) {
        EXPECT_TRUE(edge) << x << "," << y << " area " << area;
      }
    }
  }
  EXPECT_GE(marked, kSize);  // the line crosses every column
}

// Base colour comes from the texture at the hit's interpolated texcoords: u runs from 0.25 at
// the left border to 0.75 at the right one over a black | white 2x1 texture, so the bilinear
// base colour is sx / width.
TEST(GroundTruth, TexturesAreSampledAtTheInterpolatedTexcoords) {
  constexpr int kWidth = 32, kHeight = 8;
  scenes::Scene scene = HalfPlaneScene(kWidth, kHeight, {-5.0, 0.0}, {-5.0, 1.0}, {16.0, 4.0});
  scenes::Mesh& mesh = scene.meshes[0];
  for (const glm::vec3& p : mesh.positions) {
    // Inverse of ScreenToWorld for x only: u is affine in the screen x of the vertex.
    const double halfWidth = static_cast<double>(kDistance) * std::tan(0.5 * static_cast<double>(kFov)) * kWidth / kHeight;
    const double sx = (static_cast<double>(p.x) / halfWidth + 1.0) * 0.5 * kWidth;
    mesh.texcoords.emplace_back(static_cast<float>(0.25 + 0.5 * sx / kWidth), 0.5f);
  }
  scene.textures.push_back({.name = "ramp", .width = 2, .height = 1, .texels = {{0, 0, 0, 1}, {1, 1, 1, 1}}});
  scene.materials[0] = {.name = "textured", .baseColourFactor = glm::vec4(1.0f), .baseColourTexture = 0};
  const scenes::GroundTruthImage image = RenderGroundTruth(scene, GroundTruthSettingsFor(kWidth, kHeight, 256));
  const glm::vec3 white = scenes::ShadeLambert(scene.lighting, glm::vec3(1.0f), glm::vec3(0.0f, 0.0f, 1.0f));
  for (int x = 0; x < kWidth; ++x) {
    // The samples' mean x is within 1/32 px of the centre (one jittered sample per 1/16 stratum).
    const glm::vec3 expected = white * ((static_cast<float>(x) + 0.5f) / kWidth);
    EXPECT_NEAR(glm::length(image.colour[image.Index(x, 4)] - expected), 0.0f, 2e-3f) << x;
  }
}

TEST(GroundTruth, ResultsDoNotDependOnTheThreadCount) {
  const scenes::Scene scene = scenes::MakeBuiltinScene(scenes::kDefaultSceneName, 16.0f / 9.0f);
  const scenes::GroundTruthSettings settings = GroundTruthSettingsFor(128, 72, 16);
  auto renderWith = [&](std::size_t threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return RenderGroundTruth(scene, settings);
  };
  const scenes::GroundTruthImage one = renderWith(1);
  const scenes::GroundTruthImage two = renderWith(2);
  EXPECT_TRUE(SameBits(one, two));
  // Not trivially equal: the scene covers part of the image and has edges.
  const auto edges = std::count(one.edge.begin(), one.edge.end(), std::uint8_t{1});
  EXPECT_GT(edges, 100);
  EXPECT_GT(std::count(one.coverage.begin(), one.coverage.end(), 1.0f), 500);
}

// Embree turns on flush-to-zero and denormals-are-zero in the thread that builds its BVH, and
// oneTBB's arena for a thread keeps the float settings the thread had when the arena was set up,
// applying them to every task it runs. A thread whose first oneTBB work was Embree's build would
// then flush denormals in all its later parallel loops (the machine's, the passes', the metrics'):
// a pass's output would depend on whether the ground truth was rendered or read from the cache.
// The render runs on a new thread, whose arena does not exist yet, as a fresh process's would not.
TEST(GroundTruth, LeavesParallelLoopsAfterItWithDenormals) {
  const scenes::Scene scene = scenes::MakeBuiltinScene(scenes::kDefaultSceneName, 16.0f / 9.0f);
  std::atomic<int> flushed{0};
  std::atomic<int> chunks{0};
  std::thread([&] {
    RenderGroundTruth(scene, GroundTruthSettingsFor(128, 72, 4));
    volatile float denormal = 1e-40f;
    tbb::parallel_for(tbb::blocked_range<int>(0, 512, 1), [&](const tbb::blocked_range<int>&) {
      // Long enough that every worker takes some of the range.
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      if (denormal * 1.0f == 0.0f) flushed.fetch_add(1);
      chunks.fetch_add(1);
    });
  }).join();
  EXPECT_GT(chunks.load(), 0);
  EXPECT_EQ(flushed.load(), 0) << "of " << chunks.load() << " chunks";
}

TEST(GroundTruth, ProgressIsReportedUpToExactlyOne) {
  const scenes::Scene scene = HalfPlaneScene(40, 40, {20.0, 0.0}, {21.0, 40.0}, {40.0, 0.0});
  std::vector<double> fractions;
  scenes::RenderGroundTruth(scene, scene.camera, GroundTruthSettingsFor(40, 40, 1),
                            [&](double fraction) { fractions.push_back(fraction); });
  ASSERT_EQ(fractions.size(), 9u);  // 3 x 3 tiles of 16 x 16
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.back(), 1.0);

  ::testing::internal::CaptureStderr();
  const scenes::ProgressCallback bar = scenes::StderrProgressBar("ground truth", /*force=*/true);
  ASSERT_TRUE(bar);
  bar(0.5);
  bar(0.504);  // same percentage: not redrawn
  bar(1.0);
  const std::string drawn = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(std::count(drawn.begin(), drawn.end(), '\r'), 2);
  EXPECT_NE(drawn.find("ground truth ["), std::string::npos);
  EXPECT_TRUE(drawn.ends_with("100%\n")) << drawn;
}

TEST(GroundTruth, BadInputsThrowOneLine) {
  const scenes::Scene scene = HalfPlaneScene(8, 8, {4.0, 0.0}, {4.0, 1.0}, {8.0, 4.0});
  auto expectInvalid = [&](const scenes::GroundTruthSettings& settings, const char* mentions) {
    try {
      RenderGroundTruth(scene, settings);
      ADD_FAILURE() << "no exception for " << mentions;
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_NE(message.find(mentions), std::string::npos) << message;
    }
  };
  expectInvalid(GroundTruthSettingsFor(8, 8, 0), "perfect square");
  expectInvalid(GroundTruthSettingsFor(8, 8, 8), "perfect square");
  expectInvalid(GroundTruthSettingsFor(8, 8, 512 * 512), "perfect square");
  expectInvalid(GroundTruthSettingsFor(0, 8, 16), "image size 0x8");
  expectInvalid(GroundTruthSettingsFor(8, -1, 16), "image size 8x-1");
  scenes::Scene badCamera = scene;
  badCamera.camera.zNear = 0.0f;
  EXPECT_THROW(RenderGroundTruth(badCamera, GroundTruthSettingsFor(8, 8, 1)), std::invalid_argument);

  scenes::Scene badIndex = scene;
  badIndex.meshes[0].indices[2] = 7;
  EXPECT_THROW(RenderGroundTruth(badIndex, GroundTruthSettingsFor(8, 8, 1)), scenes::SceneError);
  scenes::Scene badNormals = scene;
  badNormals.meshes[0].normals.pop_back();
  EXPECT_THROW(RenderGroundTruth(badNormals, GroundTruthSettingsFor(8, 8, 1)), scenes::SceneError);

  // The cache checks its inputs before it touches the disk.
  const ScratchDir dir;
  const scenes::GroundTruthCache cache(dir.Path() / "cache");
  EXPECT_THROW(cache.LoadOrRender(scene, scene.camera, GroundTruthSettingsFor(8, 8, 2)), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir.Path() / "cache"));
}

// --- The cache. ---

TEST(GroundTruthCache, SecondCallReadsIdenticalBitsBack) {
  const ScratchDir dir;
  const scenes::GroundTruthCache cache(dir.Path() / "nested" / "cache");
  const scenes::Scene scene = HalfPlaneScene(24, 16, {0.0, 3.0}, {24.0, 12.0}, {0.0, 16.0});
  const scenes::GroundTruthSettings settings = GroundTruthSettingsFor(24, 16, 16);

  const scenes::CachedGroundTruth first = cache.LoadOrRender(scene, scene.camera, settings);
  EXPECT_FALSE(first.cacheHit);
  EXPECT_TRUE(fs::exists(first.file));
  EXPECT_EQ(first.file, cache.FileFor(scenes::GroundTruthKey(scene, scene.camera, settings)));
  EXPECT_EQ(first.file.parent_path(), dir.Path() / "nested" / "cache");
  // Nothing but the file itself is left behind (the temporary was renamed into place).
  EXPECT_EQ(std::distance(fs::directory_iterator(first.file.parent_path()), fs::directory_iterator()), 1);

  const scenes::CachedGroundTruth second = cache.LoadOrRender(scene, scene.camera, settings);
  EXPECT_TRUE(second.cacheHit);
  EXPECT_TRUE(SameBits(first.image, second.image));
  EXPECT_TRUE(SameBits(first.image, RenderGroundTruth(scene, settings)));
}

TEST(GroundTruthCache, KeyCoversEveryInputThatChangesTheImage) {
  const scenes::Scene scene = HalfPlaneScene(24, 16, {0.0, 3.0}, {24.0, 12.0}, {0.0, 16.0});
  const scenes::GroundTruthSettings settings = GroundTruthSettingsFor(24, 16, 16);
  const std::uint64_t key = scenes::GroundTruthKey(scene, scene.camera, settings);
  EXPECT_EQ(key, scenes::GroundTruthKey(scene, scene.camera, settings));

  std::vector<std::uint64_t> changed;
  auto withSettings = [&](auto change) {
    scenes::GroundTruthSettings s = settings;
    change(s);
    changed.push_back(scenes::GroundTruthKey(scene, scene.camera, s));
  };
  auto withScene = [&](auto change) {
    scenes::Scene s = scene;
    change(s);
    changed.push_back(scenes::GroundTruthKey(s, s.camera, settings));
  };
  withSettings([](scenes::GroundTruthSettings& s) { s.width = 25; });
  withSettings([](scenes::GroundTruthSettings& s) { s.height = 17; });
  withSettings([](scenes::GroundTruthSettings& s) { s.samplesPerPixel = 25; });
  withSettings([](scenes::GroundTruthSettings& s) { s.clearColour.b = 0.5f; });
  withScene([](scenes::Scene& s) { s.camera.eye.x += 0.01f; });
  withScene([](scenes::Scene& s) { s.camera.verticalFovRadians += 0.01f; });
  withScene([](scenes::Scene& s) { s.meshes[0].positions[0].y += 0.01f; });
  withScene([](scenes::Scene& s) { s.meshes[0].normals[1].x += 0.01f; });
  withScene([](scenes::Scene& s) { s.meshes[0].texcoords.assign(3, glm::vec2(0.5f)); });
  withScene([](scenes::Scene& s) { std::swap(s.meshes[0].indices[1], s.meshes[0].indices[2]); });
  withScene([](scenes::Scene& s) { s.materials[0].baseColourFactor.r = 0.31f; });
  withScene([](scenes::Scene& s) { s.lighting.ambient = 0.2f; });
  withScene([](scenes::Scene& s) { s.lighting.towardsLight.z = 1.0f; });
  withScene([](scenes::Scene& s) { s.textures.push_back({.name = "t", .width = 1, .height = 1, .texels = {glm::vec4(1.0f)}}); });
  for (std::size_t i = 0; i < changed.size(); ++i) {
    EXPECT_NE(changed[i], key) << "change " << i;
    for (std::size_t j = 0; j < i; ++j) EXPECT_NE(changed[i], changed[j]) << i << " vs " << j;
  }
  // Names do not change the image, so they do not change the key.
  scenes::Scene renamed = scene;
  renamed.name = "other";
  renamed.meshes[0].name = "other";
  EXPECT_EQ(scenes::GroundTruthKey(renamed, renamed.camera, settings), key);
}

TEST(GroundTruthCache, CorruptFilesAreRenderedAgainWithAOneLineWarning) {
  const ScratchDir dir;
  const scenes::GroundTruthCache cache(dir.Path());
  const scenes::Scene scene = HalfPlaneScene(24, 16, {0.0, 3.0}, {24.0, 12.0}, {0.0, 16.0});
  const scenes::GroundTruthSettings settings = GroundTruthSettingsFor(24, 16, 16);
  const scenes::CachedGroundTruth good = cache.LoadOrRender(scene, scene.camera, settings);
  const fs::path file = good.file;
  const auto size = fs::file_size(file);

  auto damageAndReload = [&](const std::function<void()>& damage, const char* reason) {
    damage();
    ::testing::internal::CaptureStderr();
    const scenes::CachedGroundTruth reloaded = cache.LoadOrRender(scene, scene.camera, settings);
    const std::string warning = ::testing::internal::GetCapturedStderr();
    EXPECT_FALSE(reloaded.cacheHit) << reason;
    EXPECT_TRUE(SameBits(reloaded.image, good.image)) << reason;
    EXPECT_EQ(std::count(warning.begin(), warning.end(), '\n'), 1) << warning;
    EXPECT_NE(warning.find("corrupt"), std::string::npos) << warning;
    EXPECT_NE(warning.find(reason), std::string::npos) << warning;
    // Rewritten: the next call hits again.
    EXPECT_EQ(fs::file_size(file), size);
    EXPECT_TRUE(cache.LoadOrRender(scene, scene.camera, settings).cacheHit) << reason;
  };
  damageAndReload([&] { fs::resize_file(file, size - 7); }, "size");
  damageAndReload([&] { fs::resize_file(file, 0); }, "size");
  damageAndReload(
      [&] {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(static_cast<std::streamoff>(size - 100));
        f.put('\x55');
      },
      "payload hash");
  damageAndReload(
      [&] {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(0);
        f.write("garbage!", 8);
      },
      "header");
}

TEST(GroundTruthCache, DefaultDirectoryFollowsXdgThenHome) {
  {
    const ScopedEnv xdg("XDG_CACHE_HOME", "/var/tmp/xdg");
    EXPECT_EQ(scenes::GroundTruthCache::DefaultDirectory(), fs::path("/var/tmp/xdg/aasim/ground-truth"));
  }
  {
    const ScopedEnv xdg("XDG_CACHE_HOME", "relative/ignored");
    const ScopedEnv home("HOME", "/home/someone");
    EXPECT_EQ(scenes::GroundTruthCache::DefaultDirectory(), fs::path("/home/someone/.cache/aasim/ground-truth"));
  }
  {
    const ScopedEnv xdg("XDG_CACHE_HOME", nullptr);
    const ScopedEnv home("HOME", nullptr);
    EXPECT_THROW(scenes::GroundTruthCache::DefaultDirectory(), std::runtime_error);
  }
}

}  // namespace
