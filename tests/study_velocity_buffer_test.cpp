// Seed 000's low-footprint velocity buffers (study/velocity_buffer.h): every 8-bit code decodes to
// a value that encodes back to it, the two pieces' precision over 0..40 px, the range's end
// counted, and the half-resolution pack keeping each 2x2 block's front-most velocity.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "study/velocity_buffer.h"

namespace study {
namespace {

TEST(VelocityBuffer, EveryCodeRoundTripsAndDecodingIsMonotonic) {
  for (int code = 1; code < 256; ++code) {
    const float value = DecodeVelocityComponent(static_cast<std::uint8_t>(code));
    EXPECT_EQ(EncodeVelocityComponent(value), code) << code;
    if (code > 1) {
      EXPECT_LT(DecodeVelocityComponent(static_cast<std::uint8_t>(code - 1)), value) << code;
    }
  }
  EXPECT_EQ(DecodeVelocityComponent(128), 0.0f);
  EXPECT_EQ(DecodeVelocityComponent(255), kVelocityRangePixels);
  EXPECT_EQ(DecodeVelocityComponent(1), -kVelocityRangePixels);
}

// Fine piece: 1/32 px steps up to 2 px, so at most 1/64 px off; coarse: 38/63 px steps.
TEST(VelocityBuffer, ErrorStaysWithinHalfAStepOfEachPiece) {
  for (int i = -40000; i <= 40000; ++i) {
    const float v = static_cast<float>(i) / 1000.0f;
    const float error = std::abs(DecodeVelocityComponent(EncodeVelocityComponent(v)) - v);
    const float halfStep = std::abs(v) <= 2.0f ? 1.0f / 64.0f : 0.5f * 38.0f / 63.0f;
    ASSERT_LE(error, halfStep + 1e-5f) << v;
  }
  EXPECT_EQ(EncodeVelocityComponent(55.0f), EncodeVelocityComponent(kVelocityRangePixels));
}

sim::Texture2D<glm::vec2> VelocityRamp(int width, int height) {
  sim::Texture2D<glm::vec2> velocity("velocity", width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) velocity.At(x, y) = {0.25f * static_cast<float>(x), -0.5f * static_cast<float>(y)};
  }
  return velocity;
}

TEST(VelocityBuffer, HalfResolutionKeepsEachBlocksFrontMostVelocityAndCountsClamps) {
  constexpr int kW = 6, kH = 5;  // odd height: the last block row is one pixel tall
  sim::Texture2D<glm::vec2> velocity = VelocityRamp(kW, kH);
  velocity.At(5, 4) = {90.0f, 0.0f};  // beyond the range
  sim::Texture2D<float> depth("depth", kW, kH);
  depth.Fill(0.5f);
  depth.At(3, 1) = 0.25f;  // the front-most of block (1, 0)
  depth.At(5, 4) = 0.1f;
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const sim::Texture2D<glm::vec2> decoded = PackVelocity(machine, VelocityBuffer::Rg8Half, velocity, depth);
  ASSERT_EQ(decoded.Width(), kW);
  auto expect = [](glm::vec2 v) {
    return glm::vec2(DecodeVelocityComponent(EncodeVelocityComponent(v.x)), DecodeVelocityComponent(EncodeVelocityComponent(v.y)));
  };
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const int bx = x / 2, by = y / 2;
      glm::ivec2 source{2 * bx, 2 * by};  // ties keep the block's first pixel
      if (bx == 1 && by == 0) source = {3, 1};
      if (bx == 2 && by == 2) source = {5, 4};
      EXPECT_EQ(decoded.At(x, y), expect(velocity.At(source.x, source.y))) << x << "," << y;
    }
  }
  const std::vector<sim::DispatchReport> reports = machine.TakeReports();
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].name, "frame/velocity-pack");
  ASSERT_EQ(reports[0].passCounters.size(), 1u);
  EXPECT_EQ(reports[0].passCounters[0].value, 1u);
  EXPECT_EQ(reports[0].lanes.lanesActive, 9u);  // 3x3 packed texels
}

TEST(VelocityBuffer, FullResolutionQuantisesEveryPixelAndFloatIsUntouched) {
  const sim::Texture2D<glm::vec2> velocity = VelocityRamp(5, 3);
  sim::Texture2D<float> depth("depth", 5, 3);
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const sim::Texture2D<glm::vec2> rg8 = PackVelocity(machine, VelocityBuffer::Rg8, velocity, depth);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      EXPECT_NEAR(rg8.At(x, y).x, velocity.At(x, y).x, 1.0f / 64.0f);
      EXPECT_NEAR(rg8.At(x, y).y, velocity.At(x, y).y, 1.0f / 64.0f);
    }
  }
  const sim::Texture2D<glm::vec2> same = PackVelocity(machine, VelocityBuffer::Float, velocity, depth);
  EXPECT_TRUE(std::equal(same.Texels().begin(), same.Texels().end(), velocity.Texels().begin()));
  EXPECT_EQ(VelocityBufferByName("rg8-half"), VelocityBuffer::Rg8Half);
  EXPECT_EQ(VelocityBufferByName("rg16"), std::nullopt);
}

}  // namespace
}  // namespace study
