// Texture sampling in closed form: point sampling picks the texel containing the normalised
// coordinate, bilinear sampling weights the four nearest texel centres, and the address modes
// decide what lies past the border. Every sample call is one fetch instruction.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "sim/dispatch.h"
#include "sim_test_util.h"

namespace sim {
namespace {

using sim::testing::SmallKernel;

// 4x8 (not square, so a swapped axis shows) with texel (x, y) = x + 10 y. Power-of-two sizes
// keep every uv below exact in binary.
constexpr int kViewW = 4, kViewH = 8;

Texture2D<float> ViewRamp() {
  Texture2D<float> texture("ramp", kViewW, kViewH, 2);  // a 16-bit format in the model
  for (int y = 0; y < kViewH; ++y) {
    for (int x = 0; x < kViewW; ++x) texture.At(x, y) = static_cast<float>(x + 10 * y);
  }
  return texture;
}

float T(int x, int y) { return static_cast<float>(x + 10 * y); }

// Runs `body` on one compute lane with the texture bound, returns the binding's traffic.
ResourceTraffic Sample(const Texture2D<float>& texture,
                       const std::function<void(const TextureView<float>&, const ComputeLane&)>& body) {
  Machine machine(GpuConfigByName("ps4-class"));
  Dispatch d("test/sample", SmallKernel());
  const TextureView<float> view = d.Read(texture);
  const DispatchReport& r = machine.Compute(d, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}},
                                            [&](ComputeLane& lane) { body(view, lane); });
  return r.resources.at(0);
}

glm::vec2 ViewUv(double x, double y) { return {static_cast<float>(x / kViewW), static_cast<float>(y / kViewH)}; }

// The float filter blends a vec4 as one 4-float vector; each channel must be the scalar formula's
// float, bit for bit, zeros' signs, infinities, NaNs and denormals included.
TEST(SimViews, TheVectorBlendIsThePerChannelBlend) {
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> special{0.0f, -0.0f, 1.0f, -1.0f, 1e-40f, -1e-40f, 1e30f, inf, -inf,
                                   std::numeric_limits<float>::quiet_NaN(), 0.1f, 65504.0f};
  const std::vector<float> fractions{0.0f, 0.5f, 0.25f, 1.0f / 3.0f, 0.999f, 1e-7f};
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-4.0f, 4.0f);
  std::uniform_int_distribution<std::size_t> pick(0, special.size() - 1);
  int mismatches = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    glm::vec4 t[4];
    for (glm::vec4& texel : t) {
      for (int c = 0; c < 4; ++c) texel[c] = trial % 2 == 0 ? value(random) : special[pick(random)];
    }
    const glm::vec2 f(fractions[static_cast<std::size_t>(trial) % fractions.size()],
                      fractions[static_cast<std::size_t>(trial / 7) % fractions.size()]);
    const glm::vec4 blended = detail::BilinearBlend(t[0], t[1], t[2], t[3], f);
    for (int c = 0; c < 4; ++c) {
      const float expected = detail::BilinearBlend(t[0][c], t[1][c], t[2][c], t[3][c], f);
      // NaN payloads may differ between paths; NaN must stay NaN.
      const bool same = std::isnan(expected) ? std::isnan(blended[c])
                                             : std::bit_cast<std::uint32_t>(expected) == std::bit_cast<std::uint32_t>(blended[c]);
      if (!same) ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(SimViews, PointSamplingPicksTheTexelContainingTheCoordinate) {
  const Texture2D<float> texture = ViewRamp();
  int calls = 0;
  const ResourceTraffic traffic = Sample(texture, [&](const TextureView<float>& view, const ComputeLane& lane) {
    for (int y = 0; y < kViewH; ++y) {
      for (int x = 0; x < kViewW; ++x) {
        // uv spans [0, 1] over the texture: texel (x, y) covers [x, x+1) / size, lower edge inclusive.
        for (const double offset : {0.0, 0.25, 0.5, 0.96875}) {
          for (const AddressMode mode : {AddressMode::Clamp, AddressMode::Repeat}) {
            EXPECT_EQ(view.SamplePoint(lane, ViewUv(x + offset, y + offset), mode), T(x, y)) << x << "," << y << "+" << offset;
            ++calls;
          }
        }
      }
    }
    // Clamp pins the coordinate to the edge texels; uv = 1 is already past the last texel.
    EXPECT_EQ(view.SamplePoint(lane, {1.0f, 1.0f}), T(kViewW - 1, kViewH - 1));
    EXPECT_EQ(view.SamplePoint(lane, ViewUv(-0.5, 9.5), AddressMode::Clamp), T(0, kViewH - 1));
    EXPECT_EQ(view.SamplePoint(lane, ViewUv(-20.0, -0.001), AddressMode::Clamp), T(0, 0));
    // Repeat wraps the texel index modulo the size, negative coordinates included.
    EXPECT_EQ(view.SamplePoint(lane, {1.0f, 1.0f}, AddressMode::Repeat), T(0, 0));
    EXPECT_EQ(view.SamplePoint(lane, ViewUv(-0.5, 9.5), AddressMode::Repeat), T(kViewW - 1, 1));
    EXPECT_EQ(view.SamplePoint(lane, ViewUv(-5.5, -0.001), AddressMode::Repeat), T(2, kViewH - 1));
    calls += 6;
  });
  // One fetch instruction and one texel per call.
  EXPECT_EQ(traffic.fetches, static_cast<std::uint64_t>(calls));
  EXPECT_EQ(traffic.bytesRead, 2u * static_cast<std::uint64_t>(calls));
}

TEST(SimViews, BilinearSamplingWeightsTheNearestTexelCentres) {
  const Texture2D<float> texture = ViewRamp();
  int calls = 0;
  const ResourceTraffic traffic = Sample(texture, [&](const TextureView<float>& view, const ComputeLane& lane) {
    // Texel centres sit at +0.5: there the sample is the texel itself.
    EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(2.5, 3.5)), T(2, 3));
    // Midway between two centres: their mean, horizontally and vertically.
    EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(2.0, 3.5)), 0.5f * (T(1, 3) + T(2, 3)));
    EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(1.5, 5.0)), 0.5f * (T(1, 4) + T(1, 5)));
    // Midway between four centres: their mean.
    EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(3.0, 2.0)), 0.25f * (T(2, 1) + T(3, 1) + T(2, 2) + T(3, 2)));
    // A quarter of the way from one centre to the next: 0.75 / 0.25, then per axis.
    EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(1.75, 6.5)), 0.75f * T(1, 6) + 0.25f * T(2, 6));
    EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(0.5, 4.75)), 0.75f * T(0, 4) + 0.25f * T(0, 5));
    EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(1.75, 4.75)),
                    0.75f * (0.75f * T(1, 4) + 0.25f * T(2, 4)) + 0.25f * (0.75f * T(1, 5) + 0.25f * T(2, 5)));
    calls += 7;
    // At the border, half a texel out: Clamp repeats the edge texel, Repeat blends with the
    // opposite edge.
    for (const AddressMode mode : {AddressMode::Clamp, AddressMode::Repeat}) {
      const bool clamp = mode == AddressMode::Clamp;
      EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(0.0, 2.5), mode), clamp ? T(0, 2) : 0.5f * (T(kViewW - 1, 2) + T(0, 2)));
      EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(kViewW, 2.5), mode), clamp ? T(kViewW - 1, 2) : 0.5f * (T(kViewW - 1, 2) + T(0, 2)));
      EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(1.5, 0.0), mode), clamp ? T(1, 0) : 0.5f * (T(1, kViewH - 1) + T(1, 0)));
      EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(0.0, 0.0), mode),
                      clamp ? T(0, 0) : 0.25f * (T(kViewW - 1, kViewH - 1) + T(0, kViewH - 1) + T(kViewW - 1, 0) + T(0, 0)));
      // A quarter past the last centre: Repeat weights the first column 0.25 across the wrap.
      EXPECT_FLOAT_EQ(view.SampleBilinear(lane, ViewUv(kViewW - 0.25, 2.5), mode),
                      clamp ? T(kViewW - 1, 2) : 0.75f * T(kViewW - 1, 2) + 0.25f * T(0, 2));
      calls += 5;
    }
  });
  // One fetch instruction per call, reading the four-texel footprint.
  EXPECT_EQ(traffic.fetches, static_cast<std::uint64_t>(calls));
  EXPECT_EQ(traffic.bytesRead, 4u * 2u * static_cast<std::uint64_t>(calls));
}

}  // namespace
}  // namespace sim
