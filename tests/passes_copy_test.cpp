// The copy pass: the output is the input bit for bit and every pixel is in the work set, under
// both strategies (the registry test checks what every pass shares).

#include <gtest/gtest.h>

#include "passes/copy/copy.h"
#include "raster_test_util.h"

namespace passes {
namespace {

TEST(PassesCopy, CopiesEveryPixelUnderBothStrategies) {
  const int w = 37, h = 21;
  sim::Texture2D<glm::vec4> input("input", w, h, 4);
  raster::testing::Random rng(3);
  for (glm::vec4& texel : input.Texels()) texel = glm::vec4(rng.Uniform(0, 1), rng.Uniform(-1, 2), -0.0f, 1.0f);
  for (const Strategy strategy : kAllStrategies) {
    sim::Machine machine(sim::GpuConfigByName("ps4-class"));
    const PassOutput output = copy::Make(PassSettings("copy", {}))->Run(machine, FrameInputs{.colour = &input}, strategy);
    EXPECT_EQ(output.workItems, static_cast<std::uint64_t>(w) * h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) ASSERT_EQ(std::memcmp(&output.colour.At(x, y), &input.At(x, y), sizeof(glm::vec4)), 0);
    }
  }
}

}  // namespace
}  // namespace passes
