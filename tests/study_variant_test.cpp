// How far a pass's image is from the pass it varies (study::CompareVariant): pixels whose 8-bit
// sRGB codes differ, those differing by more than one code, the largest difference and the PSNR.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/vec4.hpp>

#include "sim/formats.h"
#include "sim/resources.h"
#include "study/study.h"

namespace study {
namespace {

// A 3x1 image of linear values that encode to the given sRGB codes (grey).
sim::Texture2D<glm::vec4> GreyCodes(int a, int b, int c) {
  sim::Texture2D<glm::vec4> image("codes", 3, 1);
  const int codes[] = {a, b, c};
  for (int x = 0; x < 3; ++x) {
    const float linear = sim::Srgb8ToFloat(static_cast<std::uint8_t>(codes[x]));
    image.At(x, 0) = glm::vec4(linear, linear, linear, 1.0f);
  }
  return image;
}

TEST(StudyVariant, CountsPixelsByCodesAndTheLargestDifference) {
  const VariantDifference difference = CompareVariant("base", GreyCodes(10, 101, 205), GreyCodes(10, 100, 200));
  EXPECT_EQ(difference.baseline, "base");
  EXPECT_EQ(difference.pixels, 2u);
  EXPECT_EQ(difference.pixelsOverOneCode, 1u);
  EXPECT_EQ(difference.maxCodes, 5);
  EXPECT_TRUE(std::isfinite(difference.psnr));
  EXPECT_GT(difference.psnr, 30.0);
}

TEST(StudyVariant, IdenticalImagesDifferNowhere) {
  const VariantDifference difference = CompareVariant("base", GreyCodes(0, 128, 255), GreyCodes(0, 128, 255));
  EXPECT_EQ(difference.pixels, 0u);
  EXPECT_EQ(difference.pixelsOverOneCode, 0u);
  EXPECT_EQ(difference.maxCodes, 0);
  EXPECT_TRUE(std::isinf(difference.psnr));
}

}  // namespace
}  // namespace study
