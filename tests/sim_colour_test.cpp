// Shared colour maths: YCoCg against its published coefficients (aa-facts §5.2) and its inverse
// over a grid of 8-bit colours.

#include <gtest/gtest.h>

#include "sim/colour.h"

namespace {

TEST(YCoCg, PrimariesGiveThePublishedCoefficients) {
  const glm::vec3 red = sim::RgbToYCoCg({1, 0, 0}), green = sim::RgbToYCoCg({0, 1, 0}),
                  blue = sim::RgbToYCoCg({0, 0, 1});
  EXPECT_EQ(red, glm::vec3(0.25f, 0.5f, -0.25f));
  EXPECT_EQ(green, glm::vec3(0.5f, 0.0f, 0.5f));
  EXPECT_EQ(blue, glm::vec3(0.25f, -0.5f, -0.25f));
}

TEST(YCoCg, InverseRecoversEveryColourOfAnEightBitGrid) {
  for (int r = 0; r < 256; r += 15) {
    for (int g = 0; g < 256; g += 17) {
      for (int b = 0; b < 256; b += 5) {
        const glm::vec3 rgb(static_cast<float>(r) / 255.0f, static_cast<float>(g) / 255.0f,
                            static_cast<float>(b) / 255.0f);
        const glm::vec3 back = sim::YCoCgToRgb(sim::RgbToYCoCg(rgb));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], rgb[c], 1e-6f) << r << " " << g << " " << b;
      }
    }
  }
}

}  // namespace
