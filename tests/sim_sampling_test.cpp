// Texture sampling through formatted views: the 8-bit fixed-point bilinear filter against an
// integer reference written from llvmpipe's rule (aa-facts §1.9), gather order, texel offsets,
// one RGBA8 texture through a UNORM and an sRGB view, traffic per sample, determinism.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <tbb/global_control.h>

#include "sim/dispatch.h"
#include "sim/formats.h"
#include "sim_test_util.h"

namespace sim {
namespace {

using sim::testing::SmallKernel;

// Runs `body` once on one compute lane with `texture` bound for reading; returns its traffic.
template <typename T>
ResourceTraffic OnOneLane(const Texture2D<T>& texture,
                          const std::function<void(const TextureView<T>&, const ComputeLane&)>& body) {
  Machine machine(GpuConfigByName("ps4-class"));
  Dispatch d("test/sample", SmallKernel());
  const TextureView<T> view = d.Read(texture);
  const DispatchReport& r = machine.Compute(d, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}},
                                            [&](ComputeLane& lane) { body(view, lane); });
  return r.resources.at(0);
}

// ---- An independent integer reference of the fixed-point filter ----
// s = round-half-even(float32(u * 256 * size)) - 128; texel = floor(s / 256); weight = the rest.
struct ReferenceCoord {
  long texel;
  int weight;
};
ReferenceCoord ReferenceCoordOf(float u, int size) {
  // The double product is exact (24 x 22 bits); rounding it to float is the float32 multiply.
  const auto product = static_cast<double>(static_cast<float>(static_cast<double>(u) * (256.0 * size)));
  long s = static_cast<long>(std::floor(product));
  const double fraction = product - std::floor(product);
  if (fraction > 0.5 || (fraction == 0.5 && s % 2 != 0)) ++s;
  s -= 128;
  const auto texel = static_cast<long>(std::floor(static_cast<double>(s) / 256.0));
  return {texel, static_cast<int>(s - texel * 256)};
}
int ReferenceLerp(int w, int a, int b) {
  return a + static_cast<int>(std::floor((w * (b - a) + 128) / 256.0));
}
int Wrap(long i, int size, AddressMode mode) {
  if (mode == AddressMode::Clamp) return static_cast<int>(std::clamp<long>(i, 0, size - 1));
  return static_cast<int>(((i % size) + size) % size);
}

// codes[c][y * w + x]: the 8-bit code of channel c.
using Codes = std::vector<std::vector<int>>;
int ReferenceBilinear(const Codes& codes, int c, int w, int h, glm::vec2 uv, glm::ivec2 offset, AddressMode mode) {
  const ReferenceCoord rx = ReferenceCoordOf(uv.x, w), ry = ReferenceCoordOf(uv.y, h);
  const int x0 = Wrap(rx.texel + offset.x, w, mode), x1 = Wrap(rx.texel + offset.x + 1, w, mode);
  const int y0 = Wrap(ry.texel + offset.y, h, mode), y1 = Wrap(ry.texel + offset.y + 1, h, mode);
  const auto at = [&](int x, int y) { return codes[static_cast<std::size_t>(c)][static_cast<std::size_t>(y * w + x)]; };
  const int top = ReferenceLerp(rx.weight, at(x0, y0), at(x1, y0));
  const int bottom = ReferenceLerp(rx.weight, at(x0, y1), at(x1, y1));
  return ReferenceLerp(ry.weight, top, bottom);
}

template <typename T>
Texture2D<T> RandomCodes(Format format, int w, int h, std::uint32_t seed, Codes& codes) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> code(0, 255);
  Texture2D<T> texture("random", w, h, format);
  codes.assign(static_cast<std::size_t>(kTexelComponents<T>), std::vector<int>(static_cast<std::size_t>(w * h)));
  const std::span<std::uint8_t> kept = texture.Codes();  // an 8-bit texture keeps its codes
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < kTexelComponents<T>; ++c) {
        const int k = c < Channels(format) ? code(rng) : (c == 3 ? 255 : 0);
        codes[static_cast<std::size_t>(c)][static_cast<std::size_t>(y * w + x)] = k;
        if (c < Channels(format)) {
          kept[static_cast<std::size_t>((y * w + x) * Channels(format) + c)] = static_cast<std::uint8_t>(k);
        }
      }
    }
  }
  return texture;
}

template <typename T>
void ExpectFixedPointMatchesReference(Format format, int w, int h, std::uint32_t seed) {
  Codes codes;
  const Texture2D<T> texture = RandomCodes<T>(format, w, h, seed, codes);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coordinate(-0.6f, 1.6f);
  std::uniform_int_distribution<int> offset(kMinTexelOffset, kMaxTexelOffset);
  OnOneLane<T>(texture, [&](const TextureView<T>& view, const ComputeLane& lane) {
    for (int i = 0; i < 20000; ++i) {
      // Every fourth coordinate on the 1/512-texel grid, where rounding ties happen.
      glm::vec2 uv(coordinate(rng), coordinate(rng));
      if (i % 4 == 0) uv = glm::round(uv * glm::vec2(512 * w, 512 * h)) / glm::vec2(512 * w, 512 * h);
      const glm::ivec2 o = i % 2 == 0 ? glm::ivec2(0) : glm::ivec2(offset(rng), offset(rng));
      const AddressMode mode = i % 3 == 0 ? AddressMode::Repeat : AddressMode::Clamp;
      const T sample = view.SampleBilinear(lane, uv, mode, o);
      for (int c = 0; c < kTexelComponents<T>; ++c) {
        const int expected = ReferenceBilinear(codes, c, w, h, uv, o, mode);
        ASSERT_EQ(TexelComponent(sample, c), static_cast<float>(expected) * (1.0f / 255.0f))
            << FormatName(format) << " uv " << uv.x << "," << uv.y << " offset " << o.x << "," << o.y << " channel " << c;
      }
    }
  });
}

TEST(SimSampling, FixedPointBilinearMatchesAnIntegerReference) {
  ExpectFixedPointMatchesReference<glm::vec4>(Format::RGBA8Unorm, 7, 5, 1);
  ExpectFixedPointMatchesReference<glm::vec2>(Format::RG8Unorm, 16, 8, 2);
  ExpectFixedPointMatchesReference<float>(Format::R8Unorm, 13, 3, 3);
  ExpectFixedPointMatchesReference<glm::vec4>(Format::R8Unorm, 5, 9, 4);  // g, b read 0 and alpha 1
}

// D3D leaves a NaN coordinate undefined; aasim reads it as coordinate 0, the same texel and
// weight on every host (lrint's result for NaN is unspecified).
TEST(SimSampling, ANanCoordinateFiltersAsCoordinateZero) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const int size : {1, 7, 1920}) {
    const FixedPointCoord atNan = ToFixedPointCoord(nan, size), atZero = ToFixedPointCoord(0.0f, size);
    EXPECT_EQ(atNan.texel, atZero.texel) << size;
    EXPECT_EQ(atNan.weight, atZero.weight) << size;
  }
  EXPECT_EQ(ToFixedPointCoord(0.0f, 7).texel, -1);
  EXPECT_EQ(ToFixedPointCoord(0.0f, 7).weight, 128);
}

// The float filter and gather4 against a direct reference: the footprint from floor(u w - 0.5)
// with each of its texels addressed alone, the lerps x then y. Coordinates cover the edges and
// beyond, with offsets and both modes, on sizes down to one texel, where the footprint's two
// columns (or rows) are the same texel.
TEST(SimSampling, FloatFilterAndGatherAddressEveryTexelOfTheFootprint) {
  for (const glm::ivec2 size : {glm::ivec2(1, 1), glm::ivec2(1, 5), glm::ivec2(2, 3), glm::ivec2(7, 5)}) {
    Texture2D<float> texture("random", size.x, size.y, Format::R32Float);
    std::mt19937 rng(static_cast<std::uint32_t>(size.x * 31 + size.y));
    std::uniform_real_distribution<float> value(-4.0f, 4.0f), coordinate(-1.3f, 2.3f);
    std::uniform_int_distribution<int> offset(kMinTexelOffset, kMaxTexelOffset);
    for (int y = 0; y < size.y; ++y) {
      for (int x = 0; x < size.x; ++x) texture.Set(x, y, value(rng));
    }
    OnOneLane<float>(texture, [&](const TextureView<float>& view, const ComputeLane& lane) {
      for (int i = 0; i < 5000; ++i) {
        const glm::vec2 uv(coordinate(rng), coordinate(rng));
        const glm::ivec2 o = i % 2 == 0 ? glm::ivec2(0) : glm::ivec2(offset(rng), offset(rng));
        const AddressMode mode = i % 3 == 0 ? AddressMode::Repeat : AddressMode::Clamp;
        const glm::vec2 texel = uv * glm::vec2(size) - 0.5f;
        const glm::vec2 base = glm::floor(texel), f = texel - base;
        const int x0 = static_cast<int>(base.x) + o.x, y0 = static_cast<int>(base.y) + o.y;
        const auto at = [&](int x, int y) { return texture.Get(Wrap(x, size.x, mode), Wrap(y, size.y, mode)); };
        const float top = at(x0, y0) * (1.0f - f.x) + at(x0 + 1, y0) * f.x;
        const float bottom = at(x0, y0 + 1) * (1.0f - f.x) + at(x0 + 1, y0 + 1) * f.x;
        ASSERT_EQ(view.SampleBilinearFloat(lane, uv, mode, o), top * (1.0f - f.y) + bottom * f.y)
            << size.x << "x" << size.y << " uv " << uv.x << "," << uv.y << " offset " << o.x << "," << o.y;
        const glm::vec4 gathered(at(x0, y0 + 1), at(x0 + 1, y0 + 1), at(x0 + 1, y0), at(x0, y0));
        ASSERT_EQ(view.Gather(lane, uv, 0, o, mode), gathered)
            << size.x << "x" << size.y << " uv " << uv.x << "," << uv.y << " offset " << o.x << "," << o.y;
      }
    });
  }
}

// The fetch converts both coordinates in one vector; each lane must be the scalar conversion,
// at the clamp limits, on rounding ties, for NaN, infinities, signed zeros and denormals, and on
// random bit patterns.
TEST(SimSampling, BothCoordinatesConvertAsEachAlone) {
  const float limit = kFixedPointProductLimit;
  std::vector<float> values = {0.0f, -0.0f, 0.5f, 1.0f, -1.0f, 1e-45f, -1e-45f, 1e30f, -1e30f,
                               limit, -limit, std::nextafter(limit, 0.0f), std::nextafter(-limit, 0.0f),
                               std::nextafter(limit, 2 * limit), std::nextafter(-limit, -2 * limit),
                               std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN()};
  for (int k = -1024; k <= 1024; ++k) values.push_back(static_cast<float>(k) / 512.0f);  // ties at 1/512
  std::mt19937 rng(11);
  for (int i = 0; i < 200000; ++i) values.push_back(std::bit_cast<float>(static_cast<std::uint32_t>(rng())));
  std::uniform_int_distribution<std::size_t> pick(0, values.size() - 1);
  for (const int size : {1, 7, 1920, 16384}) {
    const float scale = static_cast<float>(size * 256);
    for (std::size_t i = 0; i < values.size(); ++i) {
      const glm::vec2 uv(values[i], values[pick(rng)]);
      const FixedPointCoords both = ToFixedPointCoordsScaled(uv, glm::vec2(scale, 3.0f * scale));
      const FixedPointCoord x = ToFixedPointCoordScaled(uv.x, scale), y = ToFixedPointCoordScaled(uv.y, 3.0f * scale);
      ASSERT_EQ(both.x.texel, x.texel) << uv.x << " size " << size;
      ASSERT_EQ(both.x.weight, x.weight) << uv.x << " size " << size;
      ASSERT_EQ(both.y.texel, y.texel) << uv.y << " size " << size;
      ASSERT_EQ(both.y.weight, y.weight) << uv.y << " size " << size;
    }
  }
}

// With 8 fractional bits the weight is k/256, not a float: a quarter of the way from code 0 to
// code 255 reads code 64, where float weights give 63.75 / 255. Texel centres stay exact, and
// elsewhere the two filters differ by under 2 / 255 (aa-facts §1.9: up to 1.6 / 255).
TEST(SimSampling, FixedPointWeightsHaveEightBits) {
  Texture2D<float> ramp("ramp", 2, 1, Format::R8Unorm);
  ramp.Set(1, 0, 1.0f);
  OnOneLane<float>(ramp, [&](const TextureView<float>& view, const ComputeLane& lane) {
    EXPECT_EQ(view.SampleBilinear(lane, {0.375f, 0.5f}), 64.0f / 255.0f);
    EXPECT_EQ(view.SampleBilinearFloat(lane, {0.375f, 0.5f}), 0.25f);
  });
  Codes codes;
  const Texture2D<glm::vec4> texture = RandomCodes<glm::vec4>(Format::RGBA8Unorm, 9, 6, 7, codes);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(0.0f, 1.0f);
  OnOneLane<glm::vec4>(texture, [&](const TextureView<glm::vec4>& view, const ComputeLane& lane) {
    for (int y = 0; y < 6; ++y) {
      for (int x = 0; x < 9; ++x) {
        const glm::vec2 centre((static_cast<float>(x) + 0.5f) / 9.0f, (static_cast<float>(y) + 0.5f) / 6.0f);
        ASSERT_EQ(view.SampleBilinear(lane, centre), texture.Get(x, y));
      }
    }
    for (int i = 0; i < 5000; ++i) {
      const glm::vec2 uv(coordinate(rng), coordinate(rng));
      const glm::vec4 difference = glm::abs(view.SampleBilinear(lane, uv) - view.SampleBilinearFloat(lane, uv));
      ASSERT_LT(std::max(std::max(difference.x, difference.y), std::max(difference.z, difference.w)), 2.0f / 255.0f);
    }
  });
}

// gather4 (HLSL reference, gather4 (sm5 - asm)): counter-clockwise from the lower left,
// x = (u0, v1), y = (u1, v1), z = (u1, v0), w = (u0, v0), with v growing downwards.
TEST(SimSampling, GatherReturnsTheFootprintCounterClockwiseFromTheLowerLeft) {
  Texture2D<float> texture("distinct", 4, 4, Format::R32Float);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) texture.At(x, y) = static_cast<float>(x + 10 * y);
  }
  const ResourceTraffic traffic = OnOneLane<float>(texture, [&](const TextureView<float>& view, const ComputeLane& lane) {
    // Between texel centres (1, 1) and (2, 2).
    EXPECT_EQ(view.Gather(lane, {0.5f, 0.5f}), glm::vec4(21, 22, 12, 11));
    EXPECT_EQ(view.Gather(lane, {0.4f, 0.6f}), glm::vec4(21, 22, 12, 11));
    EXPECT_EQ(view.Gather(lane, {0.5f, 0.5f}, 0, {1, -1}), glm::vec4(12, 13, 3, 2));
    // Clamp at the left border: both columns are column 0.
    EXPECT_EQ(view.Gather(lane, {0.0f, 0.5f}), glm::vec4(20, 20, 10, 10));
    EXPECT_EQ(view.Gather(lane, {1.0f, 1.0f}), glm::vec4(33, 33, 33, 33));
    // Repeat wraps the footprint across the border.
    EXPECT_EQ(view.Gather(lane, {0.0f, 0.0f}, 0, {0, 0}, AddressMode::Repeat), glm::vec4(3, 0, 30, 33));
    // A channel the format lacks reads 0, alpha reads 1.
    EXPECT_EQ(view.Gather(lane, {0.5f, 0.5f}, 1), glm::vec4(0));
    EXPECT_EQ(view.Gather(lane, {0.5f, 0.5f}, 3), glm::vec4(1));
  });
  EXPECT_EQ(traffic.fetches, 8u);
  EXPECT_EQ(traffic.bytesRead, 8u * 4 * 4);

  Texture2D<glm::vec4> rgba("rgba", 2, 2, Format::RGBA8Unorm);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 2; ++x) {
      const float k = static_cast<float>(x + 2 * y);
      rgba.Set(x, y, glm::vec4(k, 10 + k, 20 + k, 30 + k) / 255.0f);
    }
  }
  OnOneLane<glm::vec4>(rgba, [&](const TextureView<glm::vec4>& view, const ComputeLane& lane) {
    for (int c = 0; c < 4; ++c) {
      const float base = 10.0f * static_cast<float>(c);
      const auto unorm = [](float code) { return Unorm8ToFloat(static_cast<std::uint8_t>(code)); };  // as a UNORM view reads
      EXPECT_EQ(view.Gather(lane, {0.5f, 0.5f}, c),
                glm::vec4(unorm(base + 2), unorm(base + 3), unorm(base + 1), unorm(base))) << c;
    }
    EXPECT_THROW(view.Gather(lane, {0.5f, 0.5f}, 4), KernelError);
  });
}

// Offsets move every kind of access by whole texels before addressing: a sample at a texel
// centre with offset o reads the texel o away (clamped at the border).
TEST(SimSampling, OffsetsMoveEveryAccessByWholeTexels) {
  constexpr int kSize = 16;
  Texture2D<float> codes("codes", kSize, kSize, Format::R8Unorm);
  Texture2D<float> floats("floats", kSize, kSize, Format::R32Float);
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      codes.Set(x, y, Unorm8ToFloat(static_cast<std::uint8_t>(x + kSize * y)));
      floats.At(x, y) = static_cast<float>(x + kSize * y);
    }
  }
  const glm::ivec2 at(9, 6);
  const glm::vec2 centre = (glm::vec2(at) + 0.5f) / static_cast<float>(kSize);
  for (const Texture2D<float>* texture : {&codes, &floats}) {
    OnOneLane<float>(*texture, [&](const TextureView<float>& view, const ComputeLane& lane) {
      for (int oy = kMinTexelOffset; oy <= kMaxTexelOffset; ++oy) {
        for (int ox = kMinTexelOffset; ox <= kMaxTexelOffset; ++ox) {
          const glm::ivec2 o(ox, oy);
          const glm::ivec2 clamped = glm::clamp(at + o, 0, kSize - 1);
          const float expected = texture->Get(clamped.x, clamped.y);
          EXPECT_EQ(view.SamplePoint(lane, centre, AddressMode::Clamp, o), expected) << ox << "," << oy;
          EXPECT_EQ(view.SampleBilinear(lane, centre, AddressMode::Clamp, o), expected) << ox << "," << oy;
          EXPECT_EQ(view.SampleBilinearFloat(lane, centre, AddressMode::Clamp, o), expected) << ox << "," << oy;
          // Load is not addressed: past the border it reads zero.
          const glm::ivec2 loaded = at + o;
          EXPECT_EQ(view.Load(lane, at.x, at.y, o), loaded == clamped ? expected : 0.0f) << ox << "," << oy;
        }
      }
      EXPECT_THROW(view.SampleBilinear(lane, centre, AddressMode::Clamp, {8, 0}), KernelError);
      EXPECT_THROW(view.SamplePoint(lane, centre, AddressMode::Clamp, {0, -9}), KernelError);
      EXPECT_THROW(view.Load(lane, 0, 0, {-9, 0}), KernelError);
      EXPECT_THROW(view.Gather(lane, centre, 0, {0, 8}), KernelError);
    });
  }
}

// One RGBA8 texture, three dispatches: an sRGB view stores linear colour (encoded), a UNORM view
// reads the codes, an sRGB view reads them decoded; sRGB views filter decoded values (llvmpipe
// never filters sRGB in 8-bit fixed point).
TEST(SimSampling, UnormAndSrgbViewsOfOneTextureShareItsBytes) {
  Machine machine(GpuConfigByName("ps4-class"));
  Texture2D<glm::vec4> colour("colour", 2, 1, Format::RGBA8Unorm);
  const glm::vec4 linear(0.5f, Srgb8ToFloat(128), 1.0f, 0.5f);
  Dispatch write("test/write-srgb", SmallKernel());
  const RwTextureView<glm::vec4> srgbOut = write.ReadWrite(colour).As(Format::RGBA8Srgb);
  machine.Compute(write, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}},
                  [&](ComputeLane& lane) { srgbOut.Store(lane, 1, 0, linear); });
  EXPECT_EQ(colour.Get(1, 0), glm::vec4(188, 128, 255, 128) / 255.0f);  // alpha is linear

  Dispatch unorm("test/read-unorm", SmallKernel());
  const TextureView<glm::vec4> codes = unorm.Read(colour);
  glm::vec4 loaded(0), filtered(0);
  machine.Compute(unorm, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}}, [&](ComputeLane& lane) {
    loaded = codes.Load(lane, 1, 0);
    filtered = codes.SampleBilinear(lane, {0.5f, 0.5f});
  });
  EXPECT_EQ(loaded, glm::vec4(188, 128, 255, 128) / 255.0f);
  EXPECT_EQ(filtered, glm::vec4(94, 64, 128, 64) / 255.0f);  // lerp(128, 0, k) in fixed point

  Dispatch srgb("test/read-srgb", SmallKernel());
  const TextureView<glm::vec4> decoded = srgb.Read(colour).As(Format::RGBA8Srgb);
  machine.Compute(srgb, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}}, [&](ComputeLane& lane) {
    loaded = decoded.Load(lane, 1, 0);
    filtered = decoded.SampleBilinear(lane, {0.5f, 0.5f});
  });
  EXPECT_EQ(loaded, glm::vec4(Srgb8ToFloat(188), Srgb8ToFloat(128), 1.0f, 128.0f / 255.0f));
  EXPECT_EQ(filtered, 0.5f * loaded);  // decoded, then filtered: texel 0 is black
  EXPECT_NE(filtered.x, Srgb8ToFloat(94));
  EXPECT_EQ(machine.Reports().back().resources.at(0).fetches, 2u);

  Texture2D<glm::vec4> plain("plain", 2, 1, 4);
  Texture2D<glm::vec2> rg("rg", 2, 1, Format::RG8Unorm);
  Dispatch bad("test/bad-view", SmallKernel());
  EXPECT_THROW(bad.Read(plain).As(Format::RGBA8Srgb), std::invalid_argument);
  EXPECT_THROW(bad.Read(colour).As(Format::RGBA16Float), std::invalid_argument);
  EXPECT_THROW(bad.ReadWrite(rg).As(Format::RGBA8Srgb), std::invalid_argument);
}

// A sample is one fetch instruction; its bytes are its footprint (1 texel, or 4 for bilinear
// and gather) times the format's size.
TEST(SimSampling, EachSampleIsOneFetchOfItsFootprint) {
  Texture2D<float> r8("r8", 8, 8, Format::R8Unorm);
  Texture2D<glm::vec4> half("half", 8, 8, Format::RGBA16Float);
  const ResourceTraffic narrow = OnOneLane<float>(r8, [](const TextureView<float>& view, const ComputeLane& lane) {
    view.Load(lane, 1, 1);
    view.SamplePoint(lane, {0.3f, 0.3f});
    view.SampleBilinear(lane, {0.3f, 0.3f});
    view.Gather(lane, {0.3f, 0.3f});
  });
  EXPECT_EQ(narrow.fetches, 4u);
  EXPECT_EQ(narrow.bytesRead, (1u + 1 + 4 + 4) * 1);
  const ResourceTraffic wide = OnOneLane<glm::vec4>(half, [](const TextureView<glm::vec4>& view, const ComputeLane& lane) {
    view.Load(lane, 1, 1);
    view.SampleBilinear(lane, {0.3f, 0.3f});
    view.Gather(lane, {0.3f, 0.3f}, 2);
  });
  EXPECT_EQ(wide.fetches, 3u);
  EXPECT_EQ(wide.bytesRead, (1u + 4 + 4) * 8);
}

// Fixed-point filtering, gathers and quantising stores give bit-identical texels and counters
// with 1 and 2 host threads.
TEST(SimSampling, ResultsDoNotDependOnTheThreadCount) {
  Codes codes;
  const Texture2D<glm::vec4> input = RandomCodes<glm::vec4>(Format::RGBA8Unorm, 64, 64, 9, codes);
  const auto run = [&](int threads, std::vector<DispatchReport>& reports) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    Machine machine(GpuConfigByName("ps4-class"));
    Texture2D<glm::vec4> output("output", 64, 64, Format::RGBA8Unorm);
    Dispatch d("test/filter", SmallKernel());
    const TextureView<glm::vec4> in = d.Read(input);
    const RwTextureView<glm::vec4> out = d.ReadWrite(output).As(Format::RGBA8Srgb);
    machine.Compute(d, {.threads = {64, 64, 1}, .groupSize = {8, 8, 1}}, [&](ComputeLane& lane) {
      const glm::vec2 uv = (glm::vec2(lane.threadId) + glm::vec2(0.3f, 0.7f)) / 64.0f;
      const glm::vec4 gathered = in.Gather(lane, uv, lane.threadId.x % 4, {-1, 2});
      out.Store(lane, lane.threadId.x, lane.threadId.y, 0.5f * (in.SampleBilinear(lane, uv) + gathered));
    });
    reports = machine.Reports();
    return output;
  };
  std::vector<DispatchReport> one, two;
  const Texture2D<glm::vec4> a = run(1, one), b = run(2, two);
  testing::ExpectSameReports(one, two);
  EXPECT_TRUE(std::ranges::equal(a.Codes(), b.Codes()));
}

}  // namespace
}  // namespace sim
