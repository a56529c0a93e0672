#pragma once
// Texel formats: what a store into a texture keeps and what a shader reads back, by the data
// conversion rules of the D3D11.3 functional spec §3.1.5-§3.2.3 ("D3D11 §" below). A texture
// created with a Format stores every value already converted, as the float (or uint) a view in
// that format reads: an 8-bit channel holds code / 255, whatever the view. The view's format
// decides how a store encodes and how a load decodes, so one RGBA8 texture can be written or
// read through a UNORM view in one dispatch and an sRGB view in another (D3D's typeless
// resources, aa-facts §1.9: SMAA reads the same colour both ways).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <type_traits>
#include <vector>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "raster/limits.h"

namespace sim {

enum class Format : std::uint8_t {
  R8Unorm,
  RG8Unorm,
  RGBA8Unorm,
  RGBA8Srgb,       // RGB sRGB-encoded, alpha linear UNORM
  R11G11B10Float,  // unsigned floats: 6-bit mantissa R and G, 5-bit B, 5-bit exponents
  RG16Float,
  RGBA16Float,
  R32Float,
  R32Uint,
};

int BytesPerTexel(Format format);
int Channels(Format format);
std::string_view FormatName(Format format);
// Formats whose bilinear filter runs on the 8-bit codes in fixed point (see FixedPointCoord).
// sRGB is not one: it is decoded, then filtered in float, as llvmpipe does (its 8-bit path
// excludes sRGB: u_format.c util_format_fits_8unorm).
inline bool IsUnorm8(Format format) {
  return format == Format::R8Unorm || format == Format::RG8Unorm || format == Format::RGBA8Unorm;
}
// 8 bits per channel, UNORM or sRGB: every texel value is finite.
inline bool IsEightBitPerChannel(Format format) { return IsUnorm8(format) || format == Format::RGBA8Srgb; }
// Whether a view of `view` format may read a resource created as `resource` (the typeless
// family: RGBA8Unorm and RGBA8Srgb share their bytes).
bool ViewCompatible(Format resource, Format view);

// Scalar conversions (D3D11 §3.2.3.5-§3.2.3.8 and §3.2.2). The 8-bit UNORM pair is inline:
// every 8-bit fetch and store of every kernel goes through it.

// D3D11 §3.2.3.6 (NaN -> 0, clamp to [0, 1], scale by 2^8 - 1, round; 0.6 ULP tolerance) as
// llvmpipe does it, the implementation the reference shaders' outputs come from (aa-facts §1.9):
// the float32 product 255 x rounded to nearest, ties to even. Measured against Mesa 22.3.6
// llvmpipe render-target stores of every (k + 0.5) / 255 (docs/smaa.md "Against the reference"):
// floor(255 x + 0.5) in exact arithmetic differs on 127 of those 255 ties.
[[gnu::always_inline]] inline std::uint8_t FloatToUnorm8(float value) {
  // Adding and removing 2^23 rounds a float in [0, 2^23) to an integer in the current rounding
  // mode (to nearest, ties to even): std::nearbyint's result without its library call, which
  // every 8-bit store and sRGB read would otherwise pay (SimFormats tests it against nearbyint).
  constexpr float kRoundingBias = 8388608.0f;
  // Written as two selects so they compile to maxss/minss: NaN fails the first comparison and
  // becomes 0, with no branch on the hot path of every 8-bit fetch and store.
  float clamped = value > 0.0f ? value : 0.0f;
  clamped = clamped < 1.0f ? clamped : 1.0f;
  return static_cast<std::uint8_t>((clamped * 255.0f + kRoundingBias) - kRoundingBias);
}
// D3D11 §3.2.3.5 (the code over 2^8 - 1) as llvmpipe computes it: k times float32(1 / 255),
// which differs from the correctly rounded k / 255 by one ulp on 126 codes (measured as above).
[[gnu::always_inline]] inline float Unorm8ToFloat(std::uint8_t code) { return static_cast<float>(code) * (1.0f / 255.0f); }
// ---- Whole 8-bit texels in registers ----
static_assert(std::endian::native == std::endian::little, "8-bit texels are kept as little-endian words");
// A texel's four 8-bit codes as one word, channel c in bits 8c..8c+7 (the byte order of an RGBA8
// texel in memory on a little-endian host). The SSE2 forms keep the channels in registers: a
// texel assembled in memory channel by channel and read back whole stalls on store forwarding.

// FloatToUnorm8 on the N channels of a texel at once (the codes past N are 0): the same clamp,
// product and rounding (cvtps2dq rounds in the current mode, as the bias does; maxps returns its
// second operand, 0, for a NaN).
template <glm::length_t N>
[[gnu::always_inline]] inline std::uint32_t Unorm8Word(const glm::vec<N, float>& value) {
#if defined(__SSE2__)
  __m128 channels;
  if constexpr (N == 4) {
    channels = _mm_setr_ps(value[0], value[1], value[2], value[3]);
  } else if constexpr (N == 3) {
    channels = _mm_setr_ps(value[0], value[1], value[2], 0.0f);
  } else if constexpr (N == 2) {
    channels = _mm_setr_ps(value[0], value[1], 0.0f, 0.0f);
  } else {
    channels = _mm_setr_ps(value[0], 0.0f, 0.0f, 0.0f);
  }
  const __m128 clamped = _mm_min_ps(_mm_max_ps(channels, _mm_setzero_ps()), _mm_set1_ps(1.0f));
  const __m128i codes = _mm_cvtps_epi32(_mm_mul_ps(clamped, _mm_set1_ps(255.0f)));
  const __m128i words = _mm_packs_epi32(codes, codes);  // 0..255 survive both saturating packs
  return static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_packus_epi16(words, words)));
#else
  std::uint32_t word = 0;
  for (glm::length_t c = 0; c < N; ++c) word |= std::uint32_t{FloatToUnorm8(value[c])} << (8 * c);
  return word;
#endif
}
template <glm::length_t N>
[[gnu::always_inline]] inline glm::ivec4 Unorm8Codes(const glm::vec<N, float>& value) {
  const std::uint32_t word = Unorm8Word(value);
  return {static_cast<int>(word & 0xFFu), static_cast<int>(word >> 8 & 0xFFu), static_cast<int>(word >> 16 & 0xFFu),
          static_cast<int>(word >> 24)};
}
// Unorm8ToFloat on the four codes of a word.
[[gnu::always_inline]] inline glm::vec4 Unorm8WordToFloats(std::uint32_t word) {
#if defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128();
  const __m128i bytes = _mm_cvtsi32_si128(static_cast<int>(word));
  const __m128i ints = _mm_unpacklo_epi16(_mm_unpacklo_epi8(bytes, zero), zero);
  const __m128 floats = _mm_mul_ps(_mm_cvtepi32_ps(ints), _mm_set1_ps(1.0f / 255.0f));
  // Lane by lane with shuffles: a memcpy into glm::vec4 went through the stack as two 8-byte
  // loads of a 16-byte store on every fetch (docs/PERFORMANCE.md, "Stop 28").
  return {_mm_cvtss_f32(floats), _mm_cvtss_f32(_mm_shuffle_ps(floats, floats, 1)),
          _mm_cvtss_f32(_mm_shuffle_ps(floats, floats, 2)), _mm_cvtss_f32(_mm_shuffle_ps(floats, floats, 3))};
#else
  return {Unorm8ToFloat(word & 0xFFu), Unorm8ToFloat(word >> 8 & 0xFFu), Unorm8ToFloat(word >> 16 & 0xFFu),
          Unorm8ToFloat(word >> 24)};
#endif
}
// The codes of an 8-bit texel with `channels` channels as a word, the channels it lacks read as
// D3D's defaults (0, and alpha 1: code 255).
[[gnu::always_inline]] inline std::uint32_t CodesWord(const std::uint8_t* codes, int channels) {
  switch (channels) {
    case 4: {
      std::uint32_t word;
      std::memcpy(&word, codes, 4);
      return word;
    }
    case 2: {
      std::uint16_t pair;
      std::memcpy(&pair, codes, 2);
      return 0xFF000000u | pair;
    }
    default: return 0xFF000000u | codes[0];
  }
}
namespace detail {
// The sRGB conversion tables, built once (formats.cpp) from the double-precision curve. Inline
// accessors: every sRGB fetch decodes up to 16 channels and every colour store encodes 3, so
// a call per channel would cost more than the lookup.
inline constexpr int kSrgbBucketShift = 15;
struct SrgbTables {
  std::array<float, 256> decode{};      // code -> the nearest float to the exact curve
  // [k - 1]: the smallest float in [0, 1] encoding to k or more; [255] = 2, above every input.
  std::array<float, 256> thresholds{};
  // Floats in [0, 1] grouped by their top bits (2^15 ulps per bucket): the code of each bucket's
  // smallest float. No bucket holds two thresholds (BuildSrgbTables checks it: the narrowest gap
  // between two thresholds is about 10^5 ulps), so a float's code is its bucket's, plus one if
  // it reaches the next threshold.
  std::vector<std::uint8_t> buckets;
};
SrgbTables BuildSrgbTables();
[[gnu::always_inline]] inline const SrgbTables& Srgb() {
  static const SrgbTables tables = BuildSrgbTables();
  return tables;
}
}  // namespace detail

// D3D11 §3.2.3.8, exact: the encoded value the double-precision curve gives, found in a table of
// the 255 decision thresholds (the curve evaluated per store would dominate a full-screen pass).
// EncodeSrgb8 takes the tables from its caller, so the three channels of a texel fetch them once.
[[gnu::always_inline]] inline std::uint8_t EncodeSrgb8(const detail::SrgbTables& tables, float linear) {
  if (!(linear > 0.0f)) return 0;  // NaN, zero and negatives
  if (linear >= 1.0f) return 255;
  const int code = tables.buckets[std::bit_cast<std::uint32_t>(linear) >> detail::kSrgbBucketShift];
  return static_cast<std::uint8_t>(code + (linear >= tables.thresholds[static_cast<std::size_t>(code)] ? 1 : 0));
}
[[gnu::always_inline]] inline std::uint8_t FloatToSrgb8(float linear) { return EncodeSrgb8(detail::Srgb(), linear); }
// The same conversion evaluating the curve in double, the definition the table is built from.
std::uint8_t FloatToSrgb8ByCurve(float linear);
inline float Srgb8ToFloat(std::uint8_t code) { return detail::Srgb().decode[code]; }
std::uint16_t FloatToHalf(float value);
float HalfToFloat(std::uint16_t bits);
// What a float16 store keeps of a float32, read back: HalfToFloat(FloatToHalf(value)). In the
// half's normal range ([2^-14, 2^16) in magnitude, float32 exponents 113..142) the store's round
// toward zero is float32's fraction cut to float16's 10 bits, done inline here; zeros, denormals,
// overflow, infinities and NaN take the conversion itself. Every RGBA16F and RG16F store (the
// temporal passes' histories and velocities) comes through here.
[[gnu::always_inline]] inline float QuantizeHalf(float value) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
  const std::uint32_t exponent = bits >> 23 & 0xFFu;
  if (exponent - 113u <= 142u - 113u) return std::bit_cast<float>(bits & 0xFFFFE000u);
  return HalfToFloat(FloatToHalf(value));
}
std::uint16_t FloatToFloat11(float value);
float Float11ToFloat(std::uint16_t bits);
std::uint16_t FloatToFloat10(float value);
float Float10ToFloat(std::uint16_t bits);
// The same for R11G11B10's unsigned small floats (float16's exponent, 6 or 5 fraction bits):
// positive normals are cut inline; negatives (stored as 0), zeros, denormals, overflow,
// infinities and NaN take the conversion. MiniEngine FXAA's colour target stores through here.
[[gnu::always_inline]] inline float QuantizeFloat11(float value) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
  if ((bits >> 23) - 113u <= 142u - 113u) return std::bit_cast<float>(bits & 0xFFFE0000u);  // sign clear
  return Float11ToFloat(FloatToFloat11(value));
}
[[gnu::always_inline]] inline float QuantizeFloat10(float value) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
  if ((bits >> 23) - 113u <= 142u - 113u) return std::bit_cast<float>(bits & 0xFFFC0000u);
  return Float10ToFloat(FloatToFloat10(value));
}

// One channel of a texel in the host representation: what a store of `value` into channel
// `channel` of `format` keeps, and what a view of `format` reads from what was kept. Channels
// past the format's read as D3D's defaults (0, and 1 for alpha; D3D11.3 spec §19.1.3.3).
float QuantizeChannel(Format format, int channel, float value);
float DecodeChannel(Format format, int channel, float stored);

// ---- Texel types a formatted texture can hold: float, glm float vectors, std::uint32_t ----

template <typename T>
inline constexpr int kTexelComponents = 1;
template <glm::length_t N, typename S, glm::qualifier Q>
inline constexpr int kTexelComponents<glm::vec<N, S, Q>> = N;

template <typename T>
struct TexelScalarOf {
  using type = T;
};
template <glm::length_t N, typename S, glm::qualifier Q>
struct TexelScalarOf<glm::vec<N, S, Q>> {
  using type = S;
};
template <typename T>
using TexelScalar = typename TexelScalarOf<T>::type;

template <typename T>
concept FloatTexel = std::is_same_v<TexelScalar<T>, float> && kTexelComponents<T> <= 4;
template <typename T>
concept FormattableTexel = FloatTexel<T> || std::is_same_v<T, std::uint32_t>;

template <typename T>
auto& TexelComponent(T& texel, int c) {
  if constexpr (kTexelComponents<T> == 1 && std::is_arithmetic_v<T>) {
    return texel;
  } else {
    return texel[static_cast<glm::length_t>(c)];
  }
}
template <typename T>
TexelScalar<T> TexelComponent(const T& texel, int c) {
  if constexpr (kTexelComponents<T> == 1 && std::is_arithmetic_v<T>) {
    return texel;
  } else {
    return texel[static_cast<glm::length_t>(c)];
  }
}

// A host texel of type T holds every channel of the format, and integer formats need an
// integer texel.
template <FormattableTexel T>
bool CanHold(Format format) {
  if (format == Format::R32Uint) return std::is_same_v<T, std::uint32_t>;
  return FloatTexel<T> && kTexelComponents<T> >= Channels(format);
}

// Whole texels: Quantize is what a store through a view of `format` leaves in the texture,
// Decode what a load through such a view returns for a stored texel.
template <FormattableTexel T>
[[gnu::always_inline]] inline T Quantize(Format format, T value) {
  if constexpr (FloatTexel<T>) {
    if constexpr (kTexelComponents<T> == 4) {
      if (format == Format::RGBA8Srgb) {  // every colour store of a pass: unrolled
        const detail::SrgbTables& tables = detail::Srgb();
        value[0] = Unorm8ToFloat(EncodeSrgb8(tables, value[0]));
        value[1] = Unorm8ToFloat(EncodeSrgb8(tables, value[1]));
        value[2] = Unorm8ToFloat(EncodeSrgb8(tables, value[2]));
        value[3] = Unorm8ToFloat(FloatToUnorm8(value[3]));
        return value;
      }
    }
    if constexpr (kTexelComponents<T> > 1) {
      constexpr bool kRgba = kTexelComponents<T> == 4, kRg = kTexelComponents<T> == 2;
      if ((kRgba && format == Format::RGBA8Unorm) || (kRg && format == Format::RG8Unorm)) {  // SMAA's edges, weights
        const glm::ivec4 codes = Unorm8Codes(value);
        for (glm::length_t c = 0; c < T::length(); ++c) value[c] = Unorm8ToFloat(static_cast<std::uint8_t>(codes[c]));
        return value;
      }
    }
    if (format == Format::R11G11B10Float) {
      for (int c = 0; c < kTexelComponents<T>; ++c) {
        const float channel = TexelComponent(value, c);
        TexelComponent(value, c) = c < 2 ? QuantizeFloat11(channel) : c == 2 ? QuantizeFloat10(channel) : 1.0f;
      }
      return value;
    }
    if (format == Format::RGBA16Float || format == Format::RG16Float) {
      const int channels = format == Format::RGBA16Float ? 4 : 2;
      for (int c = 0; c < kTexelComponents<T>; ++c) {
        const float stored = c == 3 ? 1.0f : 0.0f;  // QuantizeChannel's defaults past the format's channels
        TexelComponent(value, c) = c < channels ? QuantizeHalf(TexelComponent(value, c)) : stored;
      }
      return value;
    }
    for (int c = 0; c < kTexelComponents<T>; ++c) {
      TexelComponent(value, c) = QuantizeChannel(format, c, TexelComponent(value, c));
    }
  }
  return value;
}
template <FormattableTexel T>
[[gnu::always_inline]] inline T Decode(Format format, T stored) {
  if constexpr (FloatTexel<T>) {
    if (format != Format::RGBA8Srgb) return stored;  // only sRGB reads differ from what is kept
    // Alpha (and anything past it) is linear in every sRGB format. Unrolled: every texel of an
    // sRGB bilinear fetch comes through here.
    const float* const decode = detail::Srgb().decode.data();
    if constexpr (kTexelComponents<T> >= 3) {
      const glm::ivec4 codes = Unorm8Codes(stored);
      stored[0] = decode[codes[0]];
      stored[1] = decode[codes[1]];
      stored[2] = decode[codes[2]];
    } else {
      for (int c = 0; c < kTexelComponents<T>; ++c) {
        TexelComponent(stored, c) = decode[FloatToUnorm8(TexelComponent(stored, c))];
      }
    }
  }
  return stored;
}

// ---- 8-bit texels kept as codes (sim/resources.h Texture2D) ----
// A texture of an 8-bit format keeps `channels` bytes per texel (its format's channels; views of
// the typeless family, RGBA8 UNORM and sRGB, have the same count). EncodeCodes writes what a
// store of `value` through a view of `view` format leaves, DecodeCodes returns what a load reads:
// code / 255 through a UNORM view, the sRGB curve for RGB through an sRGB view (alpha linear);
// channels past the format's read 0, and 1 for alpha (D3D11.3 spec §19.1.3.3). These are
// Quantize and Decode with the texel's codes kept instead of its floats: the same values.
template <FloatTexel T>
[[gnu::always_inline]] inline std::uint32_t EncodeWord(Format view, const T& value) {
  if constexpr (kTexelComponents<T> == 4) {
    if (view == Format::RGBA8Srgb) {
      const detail::SrgbTables& tables = detail::Srgb();
      return std::uint32_t{EncodeSrgb8(tables, value[0])} | std::uint32_t{EncodeSrgb8(tables, value[1])} << 8 |
             std::uint32_t{EncodeSrgb8(tables, value[2])} << 16 | std::uint32_t{FloatToUnorm8(value[3])} << 24;
    }
  }
  if constexpr (kTexelComponents<T> == 1) {
    return FloatToUnorm8(value);
  } else {
    return Unorm8Word(value);
  }
}
template <FloatTexel T>
[[gnu::always_inline]] inline void EncodeCodes(Format view, const T& value, std::uint8_t* codes, int channels) {
  const std::uint32_t word = EncodeWord(view, value);
  std::memcpy(codes, &word, static_cast<std::size_t>(channels));  // little-endian: channel 0 first
}
// The first components of a decoded RGBA texel.
template <FloatTexel T>
[[gnu::always_inline]] inline T TexelOf(const glm::vec4& rgba) {
  if constexpr (kTexelComponents<T> == 1) {
    return rgba.x;
  } else {
    return T(rgba);
  }
}
template <FloatTexel T>
[[gnu::always_inline]] inline T DecodeWord(std::uint32_t word, bool srgb) {
  if constexpr (kTexelComponents<T> == 4) {
    if (srgb) {  // only RGBA8 is sRGB
      const float* const decode = detail::Srgb().decode.data();
      return {decode[word & 0xFFu], decode[word >> 8 & 0xFFu], decode[word >> 16 & 0xFFu],
              Unorm8ToFloat(static_cast<std::uint8_t>(word >> 24))};
    }
  }
  return TexelOf<T>(Unorm8WordToFloats(word));
}
template <FloatTexel T>
[[gnu::always_inline]] inline T DecodeCodes(const std::uint8_t* codes, int channels, bool srgb) {
  return DecodeWord<T>(CodesWord(codes, channels), srgb);
}

// ---- Fixed-point bilinear filtering of 8-bit UNORM texels ----
// As llvmpipe's AoS sampler (lp_bld_sample_aos.c lp_build_sample_image_linear): the normalised
// coordinate times 256 * size, rounded to nearest (even) as one float32 product
// (lp_bld_arit.c lp_build_iround: cvtps2dq), minus 128 (half a texel); the first texel is
// that >> 8 (arithmetic), the weight its low 8 bits. D3D10+ asks for at least 8 bits of
// sub-texel precision (D3D11.3 spec §7.18.16.1; aa-facts §1.9).
struct FixedPointCoord {
  int texel;   // left (or top) texel of the footprint, before offsets and addressing
  int weight;  // 0..255, weight of the right (or bottom) texel in 1/256
};
// The product's clamp, 2^30: the rounded value stays inside int.
inline constexpr float kFixedPointProductLimit = 1073741824.0f;
// `scale` is the texture's size times 256 as a float (exact: size * 256 <= 2^22).
[[gnu::always_inline]] inline FixedPointCoord ToFixedPointCoordScaled(float normalised, float scale) {
  // NaN takes the coordinate 0 (a NaN coordinate is undefined in D3D).
  float scaled = normalised * scale;
  scaled = scaled == scaled ? scaled : 0.0f;
  scaled = scaled > -kFixedPointProductLimit ? scaled : -kFixedPointProductLimit;
  scaled = scaled < kFixedPointProductLimit ? scaled : kFixedPointProductLimit;
#if defined(__SSE__) || defined(__x86_64__)
  // cvtss2si: lrint's rounding (the current mode, to nearest even) without its library call.
  const int s = _mm_cvtss_si32(_mm_set_ss(scaled)) - 128;
#else
  const int s = static_cast<int>(std::lrint(scaled)) - 128;
#endif
  return {s >> 8, s & 255};
}
// Both coordinates of a bilinear fetch at once: the same product, NaN rule, clamp and
// round-to-nearest-even as ToFixedPointCoordScaled, lane by lane (SimSampling tests the two
// against each other). SSE's max(a, b) and min(a, b) are a > b ? a : b and a < b ? a : b, the
// selects above, so the clamp is the same even at the limits; one vector conversion replaces
// two scalar ones and their compare-and-branch pairs in every 8-bit bilinear fetch.
struct FixedPointCoords {
  FixedPointCoord x, y;
};
[[gnu::always_inline]] inline FixedPointCoords ToFixedPointCoordsScaled(glm::vec2 normalised, glm::vec2 scale) {
#if defined(__SSE2__)
  __m128 scaled = _mm_mul_ps(_mm_setr_ps(normalised.x, normalised.y, 0.0f, 0.0f), _mm_setr_ps(scale.x, scale.y, 0.0f, 0.0f));
  scaled = _mm_and_ps(scaled, _mm_cmpord_ps(scaled, scaled));
  scaled = _mm_min_ps(_mm_max_ps(scaled, _mm_set1_ps(-kFixedPointProductLimit)),
                      _mm_set1_ps(kFixedPointProductLimit));
  const __m128i s = _mm_sub_epi32(_mm_cvtps_epi32(scaled), _mm_set1_epi32(128));
  const __m128i texels = _mm_srai_epi32(s, 8), weights = _mm_and_si128(s, _mm_set1_epi32(255));
  return {{_mm_cvtsi128_si32(texels), _mm_cvtsi128_si32(weights)},
          {_mm_cvtsi128_si32(_mm_shuffle_epi32(texels, 1)), _mm_cvtsi128_si32(_mm_shuffle_epi32(weights, 1))}};
#else
  return {ToFixedPointCoordScaled(normalised.x, scale.x), ToFixedPointCoordScaled(normalised.y, scale.y)};
#endif
}
inline FixedPointCoord ToFixedPointCoord(float normalised, int size) {
  static_assert(raster::kMaxDimension * 256 < (1 << 24));
  return ToFixedPointCoordScaled(normalised, static_cast<float>(size * 256));
}

// lerp(w, a, b) = a + ((w * (b - a) + 128) >> 8) on 8-bit codes: llvmpipe's lp_build_lerp
// with prescaled weights on its SSSE3/AVX2 path (pmulhrsw of w and (b - a) << 7 rounds this
// way; without SSSE3 it truncates instead). The result lies between a and b.
constexpr int LerpUnorm8(int weight, int a, int b) { return a + ((weight * (b - a) + 128) >> 8); }
[[gnu::always_inline]] inline std::uint32_t LerpUnorm8Word(int weight, std::uint32_t a, std::uint32_t b) {
  std::uint32_t result = 0;
  for (int shift = 0; shift < 32; shift += 8) {
    const int lerped = LerpUnorm8(weight, static_cast<int>(a >> shift & 0xFFu), static_cast<int>(b >> shift & 0xFFu));
    result |= static_cast<std::uint32_t>(lerped) << shift;
  }
  return result;
}

}  // namespace sim
