// Temporal stability measures (study/stability.h): reprojection by velocity and object id, the
// motion-compensated difference (exact for integer motion), pixel ages carried along the motion,
// the error on young pixels and the convergence frame.

#include <gtest/gtest.h>

#include <cmath>

#include "sim/formats.h"
#include "study/stability.h"

namespace study {
namespace {

constexpr int kStabilitySize = 16;

// A grey ramp in 8-bit codes whose value depends on x and y, moved `shift` pixels right.
sim::Texture2D<glm::vec4> RampTexture(int shift) {
  sim::Texture2D<glm::vec4> image("ramp", kStabilitySize, kStabilitySize);
  for (int y = 0; y < kStabilitySize; ++y) {
    for (int x = 0; x < kStabilitySize; ++x) {
      const float v = sim::Srgb8ToFloat(static_cast<std::uint8_t>(((x - shift) * 13 + y * 7) & 0xFF));
      image.At(x, y) = glm::vec4(v, v, v, 1.0f);
    }
  }
  return image;
}

DisplayImage Ramp(int shift) { return ToDisplay(RampTexture(shift)); }

sim::Texture2D<glm::vec2> Velocity(glm::vec2 v) {
  sim::Texture2D<glm::vec2> velocity("velocity", kStabilitySize, kStabilitySize);
  velocity.Fill(v);
  return velocity;
}

sim::Texture2D<std::uint32_t> Ids(std::uint32_t id) {
  sim::Texture2D<std::uint32_t> ids("ids", kStabilitySize, kStabilitySize);
  ids.Fill(id);
  return ids;
}

TEST(Stability, IntegerMotionIsCompensatedExactly) {
  const Reprojection reprojection = Reproject(Velocity({2.0f, 0.0f}), Ids(1), Ids(1));
  // Pixels x = 0, 1 came from off the screen.
  EXPECT_EQ(reprojection.disoccludedPixels, 2u * kStabilitySize);
  EXPECT_EQ(CompensatedDifference(Ramp(2), Ramp(0), reprojection), 0.0);
  // Without compensation the same pair differs.
  const Reprojection still = Reproject(Velocity({0.0f, 0.0f}), Ids(1), Ids(1));
  EXPECT_GT(CompensatedDifference(Ramp(2), Ramp(0), still), 1.0);
}

TEST(Stability, AnotherObjectAtTheSourceIsADisocclusion) {
  sim::Texture2D<std::uint32_t> previous = Ids(1);
  previous.At(5, 5) = 2;  // the pixel that maps onto (5, 5) showed another object
  const Reprojection reprojection = Reproject(Velocity({0.0f, 0.0f}), Ids(1), previous);
  EXPECT_EQ(reprojection.disoccludedPixels, 1u);
  EXPECT_EQ(reprojection.tracked[5 * kStabilitySize + 5], 0);
}

TEST(Stability, AgesFollowTheMotionAndRestartOnDisocclusion) {
  const Reprojection right = Reproject(Velocity({1.0f, 0.0f}), Ids(1), Ids(1));
  std::vector<std::uint8_t> ages = AdvanceAges({}, right, 9);
  EXPECT_EQ(ages[0], 9);  // frame 0: nothing disoccluded yet
  ages = AdvanceAges(ages, right, 9);
  EXPECT_EQ(ages[0], 0);       // x = 0 entered from the left edge
  EXPECT_EQ(ages[1], 9);       // capped
  ages = AdvanceAges(ages, right, 9);
  EXPECT_EQ(ages[0], 0);
  EXPECT_EQ(ages[1], 1);       // the pixel that entered one frame ago moved to x = 1
  const DisplayImage image = Ramp(0), truth = Ramp(1);
  const std::optional<double> young = YoungPixelError(image, truth, ages, 2);
  ASSERT_TRUE(young.has_value());
  EXPECT_GT(*young, 0.0);
  EXPECT_FALSE(YoungPixelError(image, truth, std::vector<std::uint8_t>(kStabilitySize * kStabilitySize, 9), 2).has_value());
}

// The display form is the sRGB codes: a linear value decoded from code k shows as k.
TEST(Stability, TheDisplayFormHoldsTheSrgbCodes) {
  const DisplayImage ramp = Ramp(0);
  for (int y = 0; y < kStabilitySize; ++y) {
    for (int x = 0; x < kStabilitySize; ++x) {
      const std::uint8_t code = static_cast<std::uint8_t>((x * 13 + y * 7) & 0xFF);
      const std::size_t i = 3 * static_cast<std::size_t>(y * kStabilitySize + x);
      EXPECT_EQ(ramp.rgb[i], code);
      EXPECT_EQ(ramp.rgb[i + 2], code);
    }
  }
}

TEST(Stability, ConvergenceIsTheFirstFrameFromWhichEveryLaterOneIsClose) {
  EXPECT_EQ(ConvergenceFrame({5.0, 0.2, 0.9, 0.3, 0.0}, 0.5), 3);
  EXPECT_EQ(ConvergenceFrame({0.1, 0.0}, 0.5), 0);
  EXPECT_EQ(ConvergenceFrame({}, 0.5), std::nullopt);
  EXPECT_EQ(MeanCodeDifference(Ramp(0), Ramp(0)), 0.0);
  // A mask restricts the mean to its pixels; one selecting nothing means every pixel.
  DisplayImage changed = Ramp(0);
  changed.rgb[0] = changed.rgb[1] = changed.rgb[2] = static_cast<std::uint8_t>(changed.rgb[0] + 30);
  std::vector<float> mask(kStabilitySize * kStabilitySize, 0.0f);
  EXPECT_DOUBLE_EQ(MeanCodeDifference(changed, Ramp(0), mask), 30.0 / (kStabilitySize * kStabilitySize));
  mask[0] = 1.0f;
  EXPECT_DOUBLE_EQ(MeanCodeDifference(changed, Ramp(0), mask), 30.0);
}

}  // namespace
}  // namespace study
