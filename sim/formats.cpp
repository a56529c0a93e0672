// Texel format conversions (see formats.h). Sections cited as "D3D11 §" are from the
// Direct3D 11.3 functional specification (microsoft/DirectX-Specs, d3d/archive).

#include "sim/formats.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "raster/limits.h"
#include "sim/colour.h"

namespace sim {

namespace {

struct FormatInfo {
  std::string_view name;
  int bytes;
  int channels;
};

FormatInfo Info(Format format) {
  switch (format) {
    case Format::R8Unorm: return {"R8Unorm", 1, 1};
    case Format::RG8Unorm: return {"RG8Unorm", 2, 2};
    case Format::RGBA8Unorm: return {"RGBA8Unorm", 4, 4};
    case Format::RGBA8Srgb: return {"RGBA8Srgb", 4, 4};
    case Format::R11G11B10Float: return {"R11G11B10Float", 4, 3};
    case Format::RG16Float: return {"RG16Float", 4, 2};
    case Format::RGBA16Float: return {"RGBA16Float", 8, 4};
    case Format::R32Float: return {"R32Float", 4, 1};
    case Format::R32Uint: return {"R32Uint", 4, 1};
  }
  return {"?", 1, 1};
}

// Small floats share float16's 5-bit exponent with bias 15 (D3D11 §3.1.5, §3.1.6); they differ
// in fraction bits and in having a sign bit.
constexpr int kSmallExponentBias = 15;
constexpr std::uint32_t kSmallExponentMax = 31;  // all ones: infinity or NaN

// float32 -> small float per D3D11 §3.2.2 (a conversion to a lower-range float format): round
// toward zero, so finite values too large become the largest finite value, never infinity;
// infinity stays infinity, NaN stays NaN; values below the smallest normal become denormals
// (or zero); the sign is kept where the format has one, and without one negative values clamp
// to zero (D3D11 §3.1.6).
std::uint32_t ToSmallFloat(float value, int fractionBits, bool hasSign) {
  const auto bits = std::bit_cast<std::uint32_t>(value);
  const std::uint32_t negative = bits >> 31;
  const std::uint32_t exponent = (bits >> 23) & 0xffu;
  const std::uint32_t fraction = bits & 0x7fffffu;
  const std::uint32_t infinity = kSmallExponentMax << fractionBits;
  if (exponent == 0xffu && fraction != 0) return infinity | (1u << (fractionBits - 1));  // quiet NaN
  if (negative && !hasSign) return 0;
  const std::uint32_t sign = hasSign ? negative << (5 + fractionBits) : 0u;
  if (exponent == 0xffu) return sign | infinity;
  const int biased = static_cast<int>(exponent) - 127 + kSmallExponentBias;
  // infinity - 1 is exponent 30 with every fraction bit set: the largest finite value.
  if (biased >= static_cast<int>(kSmallExponentMax)) return sign | (infinity - 1);
  if (biased >= 1) {
    return sign | (static_cast<std::uint32_t>(biased) << fractionBits) | (fraction >> (23 - fractionBits));
  }
  // A denormal counts units of 2^(-14 - fractionBits): the 24-bit significand shifted right by
  // (23 - fractionBits) + (1 - biased) >= 24 - fractionBits, truncating. float32 zeros and
  // denormals (below 2^-126) are far below the smallest small-float denormal.
  const int shift = 23 - fractionBits + (1 - biased);
  if (exponent == 0 || shift >= 32) return sign;
  return sign | (((1u << 23) | fraction) >> shift);
}

// Small float -> float32: exact, every small float is a float32 normal (D3D11 §3.2.2, lower to
// higher range).
float FromSmallFloat(std::uint32_t bits, int fractionBits, bool hasSign) {
  const bool negative = hasSign && ((bits >> (5 + fractionBits)) & 1u) != 0;
  const std::uint32_t exponent = (bits >> fractionBits) & kSmallExponentMax;
  const std::uint32_t fraction = bits & ((1u << fractionBits) - 1);
  float magnitude;
  if (exponent == kSmallExponentMax) {
    magnitude = fraction != 0 ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
  } else if (exponent == 0) {
    // fraction units of 2^(1 - bias - fractionBits), a float32 normal power of two: exact.
    magnitude = static_cast<float>(fraction) *
                std::bit_cast<float>(static_cast<std::uint32_t>(127 + 1 - kSmallExponentBias - fractionBits) << 23);
  } else {
    // The same exponent rebiased and the fraction widened: the float32 with this value, built
    // directly (ldexp's library call was a few percent of a temporal pass storing RGBA16F).
    magnitude = std::bit_cast<float>((exponent + 127 - kSmallExponentBias) << 23 | fraction << (23 - fractionBits));
  }
  return negative ? -magnitude : magnitude;
}

constexpr int kHalfFraction = 10, kFloat11Fraction = 6, kFloat10Fraction = 5;

}  // namespace

int BytesPerTexel(Format format) { return Info(format).bytes; }
int Channels(Format format) { return Info(format).channels; }
std::string_view FormatName(Format format) { return Info(format).name; }

bool ViewCompatible(Format resource, Format view) {
  const auto rgba8 = [](Format f) { return f == Format::RGBA8Unorm || f == Format::RGBA8Srgb; };
  return resource == view || (rgba8(resource) && rgba8(view));
}

// D3D11 §3.2.3.8: NaN -> 0, clamp, encode (linear below 0.0031308, else 1.055 c^(1/2.4) - 0.055)
// in double, then the UNORM quantisation.
std::uint8_t FloatToSrgb8ByCurve(float linear) {
  if (std::isnan(linear)) return 0;
  const double c = std::clamp(static_cast<double>(linear), 0.0, 1.0);
  const double encoded = SrgbEncodeCurve(c);
  return static_cast<std::uint8_t>(std::floor(encoded * 255.0 + 0.5));
}

namespace detail {

SrgbTables BuildSrgbTables() {
  SrgbTables tables;
  // The sRGB curve of D3D11 §3.2.3.7 evaluated in double and rounded to float once, for each
  // code: the nearest float to the exact curve (D3D11 §3.2.3.2 asks conversions to be exact).
  for (int k = 0; k < 256; ++k) {
    tables.decode[static_cast<std::size_t>(k)] = static_cast<float>(SrgbDecodeCurve(k / 255.0));
  }
  // thresholds[k - 1] = the smallest float in [0, 1] the curve encodes to k or more (the curve is
  // monotonic, so a bisection over float bit patterns finds it; non-negative floats order as
  // their bits do).
  for (int k = 1; k <= 255; ++k) {
    std::uint32_t low = 0, high = std::bit_cast<std::uint32_t>(1.0f);  // code(low) < k <= code(high)
    while (high - low > 1) {
      const std::uint32_t mid = low + (high - low) / 2;
      (FloatToSrgb8ByCurve(std::bit_cast<float>(mid)) >= k ? high : low) = mid;
    }
    tables.thresholds[static_cast<std::size_t>(k - 1)] = std::bit_cast<float>(high);
  }
  tables.thresholds[255] = 2.0f;
  // Each bucket's code is that of its smallest float.
  const std::uint32_t count = (std::bit_cast<std::uint32_t>(1.0f) >> kSrgbBucketShift) + 1;
  tables.buckets.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const float first = std::bit_cast<float>(i << kSrgbBucketShift);
    tables.buckets[i] = static_cast<std::uint8_t>(
        std::upper_bound(tables.thresholds.begin(), tables.thresholds.end() - 1, first) - tables.thresholds.begin());
  }
  for (std::size_t k = 1; k < 255; ++k) {
    if ((std::bit_cast<std::uint32_t>(tables.thresholds[k - 1]) >> kSrgbBucketShift) ==
        (std::bit_cast<std::uint32_t>(tables.thresholds[k]) >> kSrgbBucketShift)) {
      throw std::logic_error("sRGB encode table: two thresholds share a bucket; FloatToSrgb8 needs a finer one");
    }
  }
  return tables;
}

}  // namespace detail


std::uint16_t FloatToHalf(float value) {
  return static_cast<std::uint16_t>(ToSmallFloat(value, kHalfFraction, true));
}
float HalfToFloat(std::uint16_t bits) { return FromSmallFloat(bits, kHalfFraction, true); }
std::uint16_t FloatToFloat11(float value) {
  return static_cast<std::uint16_t>(ToSmallFloat(value, kFloat11Fraction, false));
}
float Float11ToFloat(std::uint16_t bits) { return FromSmallFloat(bits, kFloat11Fraction, false); }
std::uint16_t FloatToFloat10(float value) {
  return static_cast<std::uint16_t>(ToSmallFloat(value, kFloat10Fraction, false));
}
float Float10ToFloat(std::uint16_t bits) { return FromSmallFloat(bits, kFloat10Fraction, false); }

float QuantizeChannel(Format format, int channel, float value) {
  if (channel >= Channels(format)) return channel == 3 ? 1.0f : 0.0f;
  switch (format) {
    case Format::R8Unorm:
    case Format::RG8Unorm:
    case Format::RGBA8Unorm: return Unorm8ToFloat(FloatToUnorm8(value));
    // The texture keeps the encoded code (as code / 255, what a UNORM view reads); alpha is
    // linear in every sRGB format.
    case Format::RGBA8Srgb: return Unorm8ToFloat(channel == 3 ? FloatToUnorm8(value) : FloatToSrgb8(value));
    case Format::R11G11B10Float: return channel == 2 ? QuantizeFloat10(value) : QuantizeFloat11(value);
    case Format::RG16Float:
    case Format::RGBA16Float: return QuantizeHalf(value);
    case Format::R32Float:
    case Format::R32Uint: return value;
  }
  return value;
}

float DecodeChannel(Format format, int channel, float stored) {
  if (format != Format::RGBA8Srgb || channel == 3) return stored;
  return Srgb8ToFloat(FloatToUnorm8(stored));
}


}  // namespace sim
