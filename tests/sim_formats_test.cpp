// Texel formats: every store conversion against references written from the D3D11.3 functional
// spec's rules (§3.1.5-§3.2.3), exhaustively where the domain is small: every 8-bit code and
// every midpoint between codes, every float16 / float11 / float10 bit pattern; byte counts per
// format; formatted textures through views.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <glm/vec4.hpp>

#include "sim/dispatch.h"
#include "sim/formats.h"
#include "sim_test_util.h"

namespace sim {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The largest float below t and the smallest float at or above t.
float FloatBelow(long double t) {
  float f = static_cast<float>(t);
  if (static_cast<long double>(f) >= t) f = std::nextafter(f, -kInf);
  return f;
}
float FloatAtOrAbove(long double t) {
  float f = static_cast<float>(t);
  if (static_cast<long double>(f) < t) f = std::nextafter(f, kInf);
  return f;
}

// The exact sRGB curves of D3D11 §3.2.3.7 / §3.2.3.8 in long double.
long double SrgbToLinear(long double c) {
  return c <= 0.04045L ? c / 12.92L : std::pow((c + 0.055L) / 1.055L, 2.4L);
}

TEST(SimFormats, BytesAndChannelsPerFormat) {
  struct Expected {
    Format format;
    int bytes, channels;
  };
  const Expected all[] = {{Format::R8Unorm, 1, 1},        {Format::RG8Unorm, 2, 2},  {Format::RGBA8Unorm, 4, 4},
                          {Format::RGBA8Srgb, 4, 4},      {Format::R11G11B10Float, 4, 3},
                          {Format::RG16Float, 4, 2},      {Format::RGBA16Float, 8, 4},
                          {Format::R32Float, 4, 1},       {Format::R32Uint, 4, 1}};
  for (const Expected& e : all) {
    EXPECT_EQ(BytesPerTexel(e.format), e.bytes) << FormatName(e.format);
    EXPECT_EQ(Channels(e.format), e.channels) << FormatName(e.format);
    if (e.format == Format::R32Uint) {
      EXPECT_EQ(Texture2D<std::uint32_t>("t", 7, 3, e.format).ModelledBytes(), 21u * 4);
    } else {
      const Texture2D<glm::vec4> texture("t", 7, 3, e.format);
      EXPECT_EQ(texture.TexelBytes(), e.bytes);
      EXPECT_EQ(texture.ModelledBytes(), 21u * static_cast<std::size_t>(e.bytes)) << FormatName(e.format);
    }
  }
}

TEST(SimFormats, TexelTypesMustHoldEveryChannel) {
  EXPECT_THROW(Texture2D<float>("t", 2, 2, Format::RGBA8Unorm), std::invalid_argument);
  EXPECT_THROW(Texture2D<glm::vec2>("t", 2, 2, Format::R11G11B10Float), std::invalid_argument);
  EXPECT_THROW(Texture2D<glm::vec4>("t", 2, 2, Format::R32Uint), std::invalid_argument);
  EXPECT_THROW(Texture2D<std::uint32_t>("t", 2, 2, Format::R32Float), std::invalid_argument);
  EXPECT_NO_THROW(Texture2D<glm::vec3>("t", 2, 2, Format::R11G11B10Float));
  EXPECT_NO_THROW(Texture2D<glm::vec4>("t", 2, 2, Format::R8Unorm));
}

// llvmpipe's UNORM8 conversions (sim/formats.h): a read is k * float32(1/255); a store rounds the
// float32 product 255 x to nearest with ties to even. Every code maps back to itself; away from
// ties a store is the nearest code; at a tie the even code wins (42.5 / 255 stores 42, as
// llvmpipe was measured to: docs/smaa.md).
// The store's rounding, inlined, against the library's nearbyint: every float within 4096 ulps of
// every midpoint and every code, and every 97th float of [0, 1].
TEST(SimFormats, Unorm8StoresRoundAsNearbyintDoes) {
  const auto reference = [](float value) {
    return static_cast<int>(std::nearbyint(std::clamp(value, 0.0f, 1.0f) * 255.0f));
  };
  for (int k = 0; k <= 510; ++k) {
    float value = static_cast<float>(k / 510.0L);
    for (int step = 0; step < 4096; ++step) value = std::nextafter(value, 0.0f);
    for (int step = 0; step < 8192 && value <= 1.0f; ++step) {
      ASSERT_EQ(static_cast<int>(FloatToUnorm8(value)), reference(value)) << value;
      value = std::nextafter(value, 2.0f);
    }
  }
  for (std::uint32_t bits = 0; bits <= 0x3F800000u; bits += 97) {
    float value = 0.0f;
    std::memcpy(&value, &bits, sizeof value);
    ASSERT_EQ(static_cast<int>(FloatToUnorm8(value)), reference(value)) << value;
  }
}

TEST(SimFormats, Unorm8StoresRoundToTheNearestCodeAtEveryCodeAndMidpoint) {
  const float reciprocal = 1.0f / 255.0f;
  for (int k = 0; k <= 255; ++k) {
    const auto code = static_cast<std::uint8_t>(k);
    EXPECT_EQ(FloatToUnorm8(Unorm8ToFloat(code)), code);
    EXPECT_EQ(Unorm8ToFloat(code), static_cast<float>(k) * reciprocal) << k;
    if (k == 255) continue;
    const long double midpoint = (k + 0.5L) / 255.0L;
    // Well below and above the midpoint the nearest code, whatever the rounding of the product.
    EXPECT_EQ(static_cast<int>(FloatToUnorm8(static_cast<float>(midpoint - 1e-4L))), k);
    EXPECT_EQ(static_cast<int>(FloatToUnorm8(static_cast<float>(midpoint + 1e-4L))), k + 1);
    // At the float nearest the midpoint: the product is the tie or a float next to it.
    const float nearest = static_cast<float>(midpoint);
    const long double product = static_cast<long double>(static_cast<float>(nearest * 255.0f));
    const int expected = product < k + 0.5L ? k : product > k + 0.5L ? k + 1 : (k % 2 == 0 ? k : k + 1);
    EXPECT_EQ(static_cast<int>(FloatToUnorm8(nearest)), expected) << k;
  }
  EXPECT_EQ(FloatToUnorm8(static_cast<float>(42.5 / 255)), 42);
  EXPECT_EQ(FloatToUnorm8(static_cast<float>(43.5 / 255)), 44);
  EXPECT_EQ(FloatToUnorm8(0.5f), 128);
  EXPECT_EQ(FloatToUnorm8(kNaN), 0);
  EXPECT_EQ(FloatToUnorm8(-kInf), 0);
  EXPECT_EQ(FloatToUnorm8(-0.0f), 0);
  EXPECT_EQ(FloatToUnorm8(-1e-30f), 0);
  EXPECT_EQ(FloatToUnorm8(kInf), 255);
  EXPECT_EQ(FloatToUnorm8(1.5f), 255);
}

// D3D11 §3.2.3.7 / §3.2.3.8: decode is the exact curve rounded to float once; encode rounds to
// the nearest code in sRGB space, so the linear threshold between codes k and k + 1 is the
// decoded midpoint (k + 0.5) / 255.
TEST(SimFormats, SrgbStoresRoundToTheNearestCodeAtEveryCodeAndMidpoint) {
  for (int k = 0; k <= 255; ++k) {
    const auto code = static_cast<std::uint8_t>(k);
    EXPECT_EQ(Srgb8ToFloat(code), static_cast<float>(SrgbToLinear(k / 255.0L))) << k;
    EXPECT_EQ(FloatToSrgb8(Srgb8ToFloat(code)), code);
    if (k == 255) continue;
    const long double threshold = SrgbToLinear((k + 0.5L) / 255.0L);
    EXPECT_EQ(static_cast<int>(FloatToSrgb8(FloatBelow(threshold))), k);
    EXPECT_EQ(static_cast<int>(FloatToSrgb8(FloatAtOrAbove(threshold))), k + 1);
  }
  EXPECT_EQ(Srgb8ToFloat(0), 0.0f);
  EXPECT_EQ(Srgb8ToFloat(255), 1.0f);
  EXPECT_EQ(FloatToSrgb8(kNaN), 0);
  EXPECT_EQ(FloatToSrgb8(-0.25f), 0);
  EXPECT_EQ(FloatToSrgb8(kInf), 255);
  // The texture keeps the code as code / 255; alpha stays linear.
  EXPECT_EQ(QuantizeChannel(Format::RGBA8Srgb, 0, 0.5f), Unorm8ToFloat(188));
  EXPECT_EQ(QuantizeChannel(Format::RGBA8Srgb, 3, 0.5f), Unorm8ToFloat(128));
  EXPECT_EQ(DecodeChannel(Format::RGBA8Srgb, 1, Unorm8ToFloat(188)), Srgb8ToFloat(188));
  EXPECT_EQ(DecodeChannel(Format::RGBA8Srgb, 3, Unorm8ToFloat(188)), Unorm8ToFloat(188));
}

// ---- Small floats: 5-bit exponent (bias 15), `fraction` bits, optional sign (D3D11 §3.1.5-6) ----

long double SmallValue(std::uint32_t bits, int fraction) {
  const std::uint32_t e = (bits >> fraction) & 31u, f = bits & ((1u << fraction) - 1);
  return e == 0 ? std::ldexp(static_cast<long double>(f), -14 - fraction)
                : std::ldexp(static_cast<long double>((1u << fraction) + f), static_cast<int>(e) - 15 - fraction);
}

// Round toward zero by search: the largest finite pattern not above |v| (D3D11 §3.2.2).
std::uint32_t ReferenceRoundTowardZero(long double magnitude, int fraction) {
  std::uint32_t lo = 0, hi = (31u << fraction) - 1;  // largest finite
  while (lo < hi) {
    const std::uint32_t mid = (lo + hi + 1) / 2;
    if (SmallValue(mid, fraction) <= magnitude) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return lo;
}

std::vector<float> RandomFloats(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> exponent(-30.0f, 20.0f);
  std::uniform_int_distribution<int> sign(0, 1);
  std::vector<float> values;
  for (int i = 0; i < 200000; ++i) {
    const float magnitude = std::exp2(exponent(rng));
    values.push_back(sign(rng) != 0 ? -magnitude : magnitude);
  }
  return values;
}

TEST(SimFormats, HalfStoresRoundTowardZeroAndSaturateToTheLargestFinite) {
  // Every pattern decodes to its value and encodes back to itself.
  for (std::uint32_t bits = 0; bits < 0x10000u; ++bits) {
    const auto half = static_cast<std::uint16_t>(bits);
    const float value = HalfToFloat(half);
    if (((bits >> 10) & 31u) == 31u) {
      EXPECT_EQ(std::isnan(value), (bits & 0x3ffu) != 0) << bits;
      EXPECT_EQ(FloatToHalf(value) & 0x7c00u, 0x7c00u);
      continue;
    }
    const long double magnitude = SmallValue(bits & 0x7fffu, 10);
    EXPECT_EQ(value, static_cast<float>((bits & 0x8000u) != 0 ? -magnitude : magnitude)) << bits;
    EXPECT_EQ(FloatToHalf(value), half) << bits;
  }
  for (const float v : RandomFloats(16)) {
    const std::uint32_t sign = v < 0 ? 0x8000u : 0u;
    ASSERT_EQ(FloatToHalf(v), sign | ReferenceRoundTowardZero(std::fabs(static_cast<long double>(v)), 10)) << v;
  }
  EXPECT_EQ(FloatToHalf(1.0f), 0x3c00u);
  EXPECT_EQ(FloatToHalf(1.0f + 0x1.8p-11f), 0x3c00u);  // 0.75 ulp: toward zero, not to nearest
  EXPECT_EQ(FloatToHalf(65504.0f), 0x7bffu);           // the largest finite
  EXPECT_EQ(FloatToHalf(65520.0f), 0x7bffu);           // nearest-even would overflow to infinity
  EXPECT_EQ(FloatToHalf(1e10f), 0x7bffu);
  EXPECT_EQ(FloatToHalf(-std::numeric_limits<float>::max()), 0xfbffu);
  EXPECT_EQ(FloatToHalf(kInf), 0x7c00u);
  EXPECT_EQ(FloatToHalf(-kInf), 0xfc00u);
  EXPECT_TRUE(std::isnan(HalfToFloat(FloatToHalf(kNaN))));
  EXPECT_EQ(FloatToHalf(0x1p-14f), 0x0400u);             // smallest normal
  EXPECT_EQ(FloatToHalf(0x1p-14f - 0x1p-24f), 0x03ffu);  // largest denormal
  EXPECT_EQ(FloatToHalf(0x1p-24f), 0x0001u);             // smallest denormal
  EXPECT_EQ(FloatToHalf(0x1.8p-24f), 0x0001u);
  EXPECT_EQ(FloatToHalf(0x1p-25f), 0x0000u);
  EXPECT_EQ(FloatToHalf(-0x1p-24f), 0x8001u);
  EXPECT_EQ(FloatToHalf(-0.0f), 0x8000u);
  EXPECT_EQ(FloatToHalf(1e-40f), 0x0000u);  // a float32 denormal
}

TEST(SimFormats, Float11And10StoresRoundTowardZeroAndClampNegativesToZero) {
  struct Small {
    int fraction;
    std::uint16_t (*encode)(float);
    float (*decode)(std::uint16_t);
  };
  for (const Small& s : {Small{6, FloatToFloat11, Float11ToFloat}, Small{5, FloatToFloat10, Float10ToFloat}}) {
    const std::uint32_t infinity = 31u << s.fraction, largest = infinity - 1;
    for (std::uint32_t bits = 0; bits < (32u << s.fraction); ++bits) {
      const float value = s.decode(static_cast<std::uint16_t>(bits));
      if (bits >= infinity) {
        EXPECT_EQ(std::isnan(value), bits != infinity) << bits;
        continue;
      }
      EXPECT_EQ(value, static_cast<float>(SmallValue(bits, s.fraction))) << bits;
      EXPECT_EQ(s.encode(value), bits) << bits;
    }
    for (const float v : RandomFloats(static_cast<std::uint32_t>(s.fraction))) {
      ASSERT_EQ(s.encode(v), v < 0 ? 0u : ReferenceRoundTowardZero(static_cast<long double>(v), s.fraction)) << v;
    }
    EXPECT_EQ(s.decode(static_cast<std::uint16_t>(largest)), s.fraction == 6 ? 65024.0f : 64512.0f);
    EXPECT_EQ(s.encode(1e9f), largest);
    EXPECT_EQ(s.encode(kInf), infinity);
    EXPECT_EQ(s.encode(-kInf), 0u);
    EXPECT_EQ(s.encode(-1.0f), 0u);
    EXPECT_EQ(s.encode(-0.0f), 0u);
    EXPECT_TRUE(std::isnan(s.decode(s.encode(kNaN))));
    EXPECT_TRUE(std::isnan(s.decode(s.encode(-kNaN))));
    EXPECT_EQ(s.encode(std::ldexp(1.0f, -14 - s.fraction)), 1u);  // smallest denormal
    EXPECT_EQ(s.encode(std::ldexp(1.0f, -15 - s.fraction)), 0u);
  }
  // R and G are float11, B float10: 1 + 2^-6 survives in R, not in B; alpha reads 1.
  const glm::vec4 stored = Quantize(Format::R11G11B10Float, glm::vec4(1.015625f, 1.015625f, 1.015625f, 0.25f));
  EXPECT_EQ(stored, glm::vec4(1.015625f, 1.015625f, 1.0f, 1.0f));
}

// QuantizeHalf's inline cut against the conversion it stands for, on every float32 whose top 19
// bits (sign, exponent and float16's fraction) take each value, with the 13 bits the cut drops
// all clear, all set, and one pattern between: every half, every boundary of the normal range,
// the denormals, overflow, infinities and NaNs.
TEST(SimFormats, TheInlineHalfStoreIsTheConversion) {
  for (std::uint32_t top = 0; top < (1u << 19); ++top) {
    for (const std::uint32_t low : {0u, 0x1FFFu, 0x0A5Au, 0x1000u}) {
      const float value = std::bit_cast<float>(top << 13 | low);
      const float expected = HalfToFloat(FloatToHalf(value));
      const float actual = QuantizeHalf(value);
      if (std::isnan(expected)) {
        ASSERT_TRUE(std::isnan(actual)) << std::hex << (top << 13 | low);
        continue;
      }
      ASSERT_EQ(std::bit_cast<std::uint32_t>(actual), std::bit_cast<std::uint32_t>(expected))
          << std::hex << (top << 13 | low);
    }
  }
  EXPECT_EQ(Quantize(Format::RGBA16Float, glm::vec4(1.0f + 0x1p-11f, -65504.0f, 1e6f, 0x1p-20f)),
            glm::vec4(1.0f, -65504.0f, 65504.0f, 0x1p-20f));
}

// The same for R11G11B10's inline cuts: every float32 pattern of the kept top bits (sign,
// exponent and 6 or 5 fraction bits) with the dropped bits clear, set, and between.
TEST(SimFormats, TheInlineFloat11And10StoresAreTheConversions) {
  struct Small {
    int fraction;
    float (*inlined)(float);
    float (*converted)(float);
  };
  const Small smalls[] = {{6, QuantizeFloat11, [](float v) { return Float11ToFloat(FloatToFloat11(v)); }},
                          {5, QuantizeFloat10, [](float v) { return Float10ToFloat(FloatToFloat10(v)); }}};
  for (const Small& s : smalls) {
    const int dropped = 23 - s.fraction;
    const std::uint32_t ones = (1u << dropped) - 1;
    for (std::uint32_t top = 0; top < (1u << (32 - dropped)); ++top) {
      for (const std::uint32_t low : {0u, ones, ones / 3, 1u << (dropped - 1)}) {
        const std::uint32_t bits = top << dropped | low;
        const float expected = s.converted(std::bit_cast<float>(bits));
        const float actual = s.inlined(std::bit_cast<float>(bits));
        if (std::isnan(expected)) {
          ASSERT_TRUE(std::isnan(actual)) << std::hex << bits;
          continue;
        }
        ASSERT_EQ(std::bit_cast<std::uint32_t>(actual), std::bit_cast<std::uint32_t>(expected)) << std::hex << bits;
      }
    }
  }
  EXPECT_EQ(Quantize(Format::R11G11B10Float, glm::vec4(1.0f + 0x1p-7f, -2.0f, 1.0f + 0x1p-6f, 0.5f)),
            glm::vec4(1.0f, 0.0f, 1.0f, 1.0f));
}

// Channels a format lacks read as D3D's defaults; float32 and uint32 keep their values.
TEST(SimFormats, MissingChannelsReadAsDefaults) {
  EXPECT_EQ(Quantize(Format::R8Unorm, glm::vec4(0.5f, 0.7f, 0.2f, 0.3f)), glm::vec4(Unorm8ToFloat(128), 0, 0, 1));
  EXPECT_EQ(Quantize(Format::RG16Float, glm::vec4(0.1f, -2.0f, 5.0f, 0.0f)),
            glm::vec4(HalfToFloat(FloatToHalf(0.1f)), -2.0f, 0, 1));
  EXPECT_EQ(Quantize(Format::R32Float, glm::vec2(0.1f, 0.2f)), glm::vec2(0.1f, 0.0f));
  EXPECT_EQ(Quantize(Format::R32Float, 1e-40f), 1e-40f);
  EXPECT_EQ(Quantize(Format::R32Uint, 0xdeadbeefu), 0xdeadbeefu);
}

using sim::testing::SmallKernel;

// Stores through views quantise in the view's format; a texture without a format keeps the float
// unchanged, as before formats existed.
TEST(SimFormats, ViewStoresQuantiseOnlyFormattedTextures) {
  Machine machine(GpuConfigByName("ps4-class"));
  Texture2D<glm::vec4> rgba8("rgba8", 4, 1, Format::RGBA8Unorm);
  Texture2D<glm::vec4> half("half", 4, 1, Format::RGBA16Float, glm::vec4(0.1f));
  Texture2D<float> plain("plain", 4, 1, 2);
  EXPECT_EQ(half.At(3, 0), glm::vec4(HalfToFloat(FloatToHalf(0.1f))));  // the fill value is quantised too
  Dispatch d("test/store", SmallKernel());
  const RwTextureView<glm::vec4> a = d.ReadWrite(rgba8), b = d.ReadWrite(half);
  const RwTextureView<float> c = d.ReadWrite(plain);
  const glm::vec4 value(0.3f, 2.0f, -1.0f, 0.123456f);
  machine.Compute(d, {.threads = {4, 1, 1}, .groupSize = {4, 1, 1}}, [&](ComputeLane& lane) {
    a.Store(lane, lane.threadId.x, 0, value);
    b.Store(lane, lane.threadId.x, 0, value);
    c.Store(lane, lane.threadId.x, 0, value.w);
  });
  // 0.3f * 255 rounds to the float32 tie 76.5, which goes to the even code (llvmpipe's rule).
  EXPECT_EQ(rgba8.Get(2, 0), glm::vec4(Unorm8ToFloat(76), 1.0f, 0.0f, Unorm8ToFloat(31)));
  EXPECT_EQ(half.At(2, 0), glm::vec4(HalfToFloat(FloatToHalf(0.3f)), 2.0f, -1.0f, HalfToFloat(FloatToHalf(0.123456f))));
  EXPECT_NE(half.At(2, 0).x, 0.3f);
  EXPECT_EQ(plain.At(2, 0), 0.123456f);
  EXPECT_EQ(plain.ModelledBytes(), 4u * 2);
}

}  // namespace
}  // namespace sim

namespace sim {
namespace {

// The threshold table gives what the curve gives, on a stride through every float in [0, 1]
// and on every float within 512 ulps of each threshold.
TEST(SimFormats, TheSrgbEncodeTableAgreesWithTheCurve) {
  const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);
  for (std::uint32_t bits = 0; bits <= one; bits += 997) {
    const float value = std::bit_cast<float>(bits);
    ASSERT_EQ(FloatToSrgb8(value), FloatToSrgb8ByCurve(value)) << value;
  }
  // Where a coarse walk sees the code change, check every float around the change.
  std::uint8_t previous = 0;
  for (std::uint32_t coarse = 0; coarse <= one; coarse += 1u << 12) {
    const std::uint8_t code = FloatToSrgb8ByCurve(std::bit_cast<float>(coarse));
    if (code != previous) {
      for (std::uint32_t bits = coarse > 8192 ? coarse - 8192 : 0; bits <= std::min(one, coarse + 512); ++bits) {
        const float value = std::bit_cast<float>(bits);
        ASSERT_EQ(FloatToSrgb8(value), FloatToSrgb8ByCurve(value)) << value;
      }
    }
    previous = code;
  }
  for (const float outside : {-1.0f, -0.0f, 1.0f, 1.5f, std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
    EXPECT_EQ(FloatToSrgb8(outside), FloatToSrgb8ByCurve(outside)) << outside;
  }
}

}  // namespace
}  // namespace sim
