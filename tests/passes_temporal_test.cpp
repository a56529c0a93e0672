// The temporal passes' shared history sampling (passes/temporal/): the cubic weights' identities,
// the two 5-tap filters on constant, ramp and random textures, the reprojected fetch position,
// and the colour boxes' clamp and clip against brute-force checks.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "passes/temporal/colour_box.h"
#include "passes/temporal/history_filter.h"
#include "sim/dispatch.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"

namespace passes::temporal {
namespace {

// Power-of-two sizes keep uv * size exact, so a texel-centre coordinate stays one.
constexpr int kTexW = 32, kTexH = 16;

// Runs `body` on one compute lane with the texture bound.
void OnLane(const sim::Texture2D<glm::vec4>& texture,
            const std::function<void(const sim::TextureView<glm::vec4>&, const sim::ComputeLane&)>& body) {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  sim::Dispatch d("test/history", {.vgprs = 24, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 10});
  const sim::TextureView<glm::vec4> view = d.Read(texture);
  machine.Compute(d, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}}, [&](sim::ComputeLane& lane) { body(view, lane); });
}

sim::Texture2D<glm::vec4> TextureOf(const std::function<glm::vec4(int, int)>& texel) {
  sim::Texture2D<glm::vec4> image("history", kTexW, kTexH, sim::Format::RGBA16Float);
  for (int y = 0; y < kTexH; ++y) {
    for (int x = 0; x < kTexW; ++x) image.At(x, y) = texel(x, y);
  }
  return image;
}

glm::vec2 TexelUv(float x, float y) { return {x / kTexW, y / kTexH}; }

TEST(PassesTemporal, CubicWeightsSumToOneAndCatmullRomReproducesLinearRamps) {
  for (int i = 0; i < 64; ++i) {
    const float f = static_cast<float>(i) / 64.0f;
    for (const float c : {0.4f, 0.5f, 0.6f, 1.0f}) {
      const CubicWeights w = CubicWeightsAt({f, f}, c);
      EXPECT_NEAR(w.w0.x + w.w1.x + w.w2.x + w.w3.x, 1.0f, 1e-6f) << c << " " << f;
    }
    // A ramp's texel values at -1, 0, 1, 2 from texel 1: the weights' first moment is
    // (4c - 2) f³ + (3 - 6c) f² + 2c f, which is f for c = 0.5 only.
    const CubicWeights catmullRom = CubicWeightsAt({f, f}, kCatmullRom);
    EXPECT_NEAR(-catmullRom.w0.x + catmullRom.w2.x + 2.0f * catmullRom.w3.x, f, 1e-6f) << f;
    const CubicWeights sharper = CubicWeightsAt({f, f}, 0.6f);
    const float moment = -sharper.w0.x + sharper.w2.x + 2.0f * sharper.w3.x;
    EXPECT_NEAR(moment, 0.4f * f * f * f - 0.6f * f * f + 1.2f * f, 1e-6f) << f;
  }
  // Catmull-Rom interpolates: weight 1 on texel 1 at f = 0.
  const CubicWeights at0 = CubicWeightsAt({0.0f, 0.0f}, kCatmullRom);
  EXPECT_EQ(at0.w1.x, 1.0f);
  EXPECT_EQ(at0.w0.x + at0.w2.x + at0.w3.x, 0.0f);
}

// Random positions over the texture (away from the border, where clamping repeats edge texels).
std::vector<glm::vec2> Positions(std::mt19937& rng, int n) {
  std::uniform_real_distribution<float> x(3.0f, kTexW - 3.0f), y(3.0f, kTexH - 3.0f);
  std::vector<glm::vec2> positions;
  for (int i = 0; i < n; ++i) positions.emplace_back(x(rng), y(rng));
  return positions;
}

TEST(PassesTemporal, RenormalisedFilmicWeightsSumToOneSoAConstantStaysConstant) {
  const glm::vec4 grey(0.3f, 0.6f, 0.9f, 1.0f);
  const sim::Texture2D<glm::vec4> image = TextureOf([&](int, int) { return grey; });
  std::mt19937 rng(7);
  const std::vector<glm::vec2> positions = Positions(rng, 200);
  OnLane(image, [&](const auto& view, const auto& lane) {
    for (const glm::vec2 p : positions) {
      for (const float c : {0.4f, 0.5f, 0.6f, 1.0f}) {
        const glm::vec4 filmic = SampleHistoryFilmic(view, lane, TexelUv(p.x, p.y), c);
        for (int k = 0; k < 4; ++k) EXPECT_NEAR(filmic[k], grey[k], 1e-6f) << p.x << "," << p.y << " c " << c;
      }
      // The Intel form's weights sum to 1 without renormalising.
      const glm::vec4 intel = SampleHistoryIntel(view, lane, TexelUv(p.x, p.y));
      for (int k = 0; k < 4; ++k) EXPECT_NEAR(intel[k], grey[k], 1e-6f) << p.x << "," << p.y;
    }
  });
}

// The bicubic filters reproduce a ramp along an axis wherever the other axis sits on a texel
// centre (no corner weight); off the centres the dropped corners show, by design.
TEST(PassesTemporal, FiveTapFiltersReproduceAxisRampsOnTexelRowsAndColumns) {
  const sim::Texture2D<glm::vec4> rampX = TextureOf([](int x, int) { return glm::vec4(0.25f * static_cast<float>(x)); });
  const sim::Texture2D<glm::vec4> rampY = TextureOf([](int, int y) { return glm::vec4(0.25f * static_cast<float>(y)); });
  for (int i = 0; i < 33; ++i) {
    const float t = 6.5f + static_cast<float>(i) / 16.0f;  // fractions 0..2 past texel 6's centre
    OnLane(rampX, [&](const auto& view, const auto& lane) {
      const float expected = 0.25f * (t - 0.5f);
      EXPECT_NEAR(SampleHistoryFilmic(view, lane, TexelUv(t, 5.5f), kCatmullRom).r, expected, 1e-5f) << t;
      EXPECT_NEAR(SampleHistoryIntel(view, lane, TexelUv(t, 5.5f)).r, expected, 1e-5f) << t;
    });
    OnLane(rampY, [&](const auto& view, const auto& lane) {
      const float y = t - 1.0f;  // rows 5..7
      EXPECT_NEAR(SampleHistoryFilmic(view, lane, TexelUv(9.5f, y), kCatmullRom).r, 0.25f * (y - 0.5f), 1e-5f) << y;
      EXPECT_NEAR(SampleHistoryIntel(view, lane, TexelUv(9.5f, y)).r, 0.25f * (y - 0.5f), 1e-5f) << y;
    });
  }
  // Off the centres the Filmic form's dropped corners pull a ramp off its value: the test above
  // would see it if the taps lay elsewhere.
  OnLane(rampX, [&](const auto& view, const auto& lane) {
    EXPECT_GT(std::abs(SampleHistoryFilmic(view, lane, TexelUv(9.75f, 5.0f), kCatmullRom).r - 0.25f * 9.25f), 1e-4f);
  });
}

TEST(PassesTemporal, IntegerOffsetFetchReturnsTheTexelExactly) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  sim::Texture2D<glm::vec4> image = TextureOf([&](int, int) { return glm::vec4(unit(rng), unit(rng), unit(rng), 1.0f); });
  sim::Texture2D<glm::vec4> srgb("history8", kTexW, kTexH, sim::Format::RGBA8Srgb);
  for (int y = 0; y < kTexH; ++y) {
    for (int x = 0; x < kTexW; ++x) srgb.Set(x, y, image.At(x, y));  // quantised through its sRGB format
  }
  for (const sim::Texture2D<glm::vec4>* texture : {&image, &srgb}) {
    OnLane(*texture, [&](const auto& view, const auto& lane) {
      for (int y = 0; y < kTexH; ++y) {
        for (int x = 0; x < kTexW; ++x) {
          // Reprojected by whole pixels: velocity (2, -1) brings pixel (x + 2, y - 1)'s history from (x, y).
          const glm::vec2 uv = HistoryUv(x + 2, y - 1, {2.0f, -1.0f}, kTexW, kTexH);
          const glm::vec4 texel = view.Load(lane, x, y);
          EXPECT_EQ(SampleHistoryFilmic(view, lane, uv, 0.6f), texel) << x << "," << y;
          EXPECT_EQ(SampleHistoryIntel(view, lane, uv), texel) << x << "," << y;
        }
      }
    });
  }
}

TEST(PassesTemporal, BoxesOfTheNeighbourhoods) {
  // Values 0..8 on the 3x3 offsets in row order: the '+' holds 1, 3, 4, 5, 7.
  const auto fetch = [](glm::ivec2 o) { return glm::vec3(static_cast<float>((o.y + 1) * 3 + o.x + 1)); };
  const ColourBox box = MinMaxBox(Neighbourhood::Box3x3, fetch);
  const ColourBox plus = MinMaxBox(Neighbourhood::Plus, fetch);
  EXPECT_EQ(box.min, glm::vec3(0.0f));
  EXPECT_EQ(box.max, glm::vec3(8.0f));
  EXPECT_EQ(plus.min, glm::vec3(1.0f));
  EXPECT_EQ(plus.max, glm::vec3(7.0f));
  const ColourBox shaped = AverageBox(box, plus);
  EXPECT_EQ(shaped.min, glm::vec3(0.5f));
  EXPECT_EQ(shaped.max, glm::vec3(7.5f));
  // Mean 4, population variance (0² + 1² + ... + 8²) / 9 - 16 = 60/9.
  const ColourBox variance = VarianceBox(MomentsOf(Neighbourhood::Box3x3, fetch), 1.5f);
  EXPECT_NEAR(variance.min.x, 4.0f - 1.5f * std::sqrt(60.0f / 9.0f), 1e-5f);
  EXPECT_NEAR(variance.max.x, 4.0f + 1.5f * std::sqrt(60.0f / 9.0f), 1e-5f);
  // A flat neighbourhood has sigma 0 (not NaN from a rounding-negative variance).
  const ColourBox flat = VarianceBox(MomentsOf(Neighbourhood::Plus, [](glm::ivec2) { return glm::vec3(0.1f); }), 1.0f);
  EXPECT_NEAR(flat.min.x, 0.1f, 1e-7f);
  EXPECT_FALSE(std::isnan(flat.max.y));
}

bool Inside(const glm::vec3& p, const ColourBox& box, float slack) {
  for (int c = 0; c < 3; ++c) {
    if (p[c] < box.min[c] - slack || p[c] > box.max[c] + slack) return false;
  }
  return true;
}

TEST(PassesTemporal, ClipLeavesInsidePointsAndPutsOutsidePointsOnTheBoxSurfaceTowardsTheCentre) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
  int outside = 0;
  for (int i = 0; i < 5000; ++i) {
    glm::vec3 a(coord(rng), coord(rng), coord(rng)), b(coord(rng), coord(rng), coord(rng));
    if (i % 10 == 0) b.y = a.y;  // degenerate boxes: one channel of zero extent
    const ColourBox box{glm::min(a, b), glm::max(a, b)};
    const glm::vec3 p(2.0f * coord(rng), 2.0f * coord(rng), 2.0f * coord(rng));
    const glm::vec3 clipped = ClipTowardsCentre(p, box);
    const glm::vec3 clamped = ClampToBox(p, box);
    if (Inside(p, box, 0.0f)) {
      EXPECT_EQ(clipped, p);
      EXPECT_EQ(clamped, p);
      continue;
    }
    ++outside;
    EXPECT_TRUE(Inside(clamped, box, 0.0f));
    EXPECT_TRUE(Inside(clipped, box, 1e-5f));
    // On the surface: some channel at a face.
    bool onFace = false;
    for (int c = 0; c < 3; ++c) {
      onFace |= std::abs(clipped[c] - box.min[c]) < 1e-5f || std::abs(clipped[c] - box.max[c]) < 1e-5f;
    }
    EXPECT_TRUE(onFace);
    // On the segment from the centre to p: the offsets are parallel and no longer than p's.
    const glm::vec3 toP = p - box.Centre(), toClipped = clipped - box.Centre();
    EXPECT_LT(glm::length(glm::cross(toP, toClipped)), 1e-4f * (1.0f + glm::length(toP)));
    EXPECT_LE(glm::dot(toClipped, toClipped), glm::dot(toP, toClipped) + 1e-5f);
  }
  EXPECT_GT(outside, 1000);
}

TEST(PassesTemporal, ClipTowardsAPointStopsWhereTheSegmentLeavesTheBox) {
  const ColourBox box{glm::vec3(0.0f), glm::vec3(1.0f)};
  // From target (0.5, 0.5, 0.5) towards (2.5, 0.5, 0.5): leaves at x = 1.
  EXPECT_EQ(ClipTowards({2.5f, 0.5f, 0.5f}, box, glm::vec3(0.5f)), glm::vec3(1.0f, 0.5f, 0.5f));
  // From (0.25, 0.5, 0.5) towards (1.25, 1.5, 0.5): y leaves first (t = 0.5).
  EXPECT_EQ(ClipTowards({1.25f, 1.5f, 0.5f}, box, {0.25f, 0.5f, 0.5f}), glm::vec3(0.75f, 1.0f, 0.5f));
}

}  // namespace
}  // namespace passes::temporal
