#pragma once
// The one coverage-mask type of aasim (style.md habit 9). A QuadCoverage holds the per-sample
// coverage of a 2x2 quad in 64 bits:
//
//   bit (pixel * 16 + sample)
//
// pixel 0 = X0Y0 (top-left), 1 = X1Y0, 2 = X0Y1, 3 = X1Y1 — the order of the hardware's
// PA_SC_AA_SAMPLE_LOCS_PIXEL_* registers (hw-facts §4.2); sample = the pattern's sample index.
// Bits of samples >= the pattern's count are always zero. Nobody outside this header shifts
// coverage bits by hand.

#include <bit>
#include <cstdint>

#include "raster/limits.h"

namespace raster {

using SampleMask = std::uint16_t;  // one pixel: bit s = sample s

constexpr SampleMask AllSamples(int sampleCount) {
  return static_cast<SampleMask>((1u << sampleCount) - 1u);
}

constexpr int QuadPixelIndex(int x, int y) { return (y & 1) * 2 + (x & 1); }

class QuadCoverage {
 public:
  constexpr QuadCoverage() = default;
  constexpr explicit QuadCoverage(std::uint64_t bits) : bits_(bits) {}

  constexpr std::uint64_t Bits() const { return bits_; }
  constexpr bool Empty() const { return bits_ == 0; }

  constexpr SampleMask Pixel(int pixel) const {
    return static_cast<SampleMask>(bits_ >> (pixel * kMaxCoverageSamples));
  }
  constexpr void SetPixel(int pixel, SampleMask mask) {
    const int shift = pixel * kMaxCoverageSamples;
    bits_ = (bits_ & ~(std::uint64_t{0xFFFF} << shift)) | (std::uint64_t{mask} << shift);
  }
  constexpr bool Sample(int pixel, int sample) const {
    return (bits_ >> (pixel * kMaxCoverageSamples + sample)) & 1u;
  }
  constexpr void SetSample(int pixel, int sample) {
    bits_ |= std::uint64_t{1} << (pixel * kMaxCoverageSamples + sample);
  }

  // Bit p set when pixel p has at least one covered sample ("live" pixel).
  constexpr std::uint8_t LivePixels() const {
    std::uint8_t live = 0;
    for (int p = 0; p < kQuadPixels; ++p) live |= static_cast<std::uint8_t>((Pixel(p) != 0) << p);
    return live;
  }
  constexpr int LivePixelCount() const { return std::popcount(LivePixels()); }
  constexpr int SampleCount() const { return std::popcount(bits_); }

  friend constexpr QuadCoverage operator&(QuadCoverage a, QuadCoverage b) {
    return QuadCoverage(a.bits_ & b.bits_);
  }
  friend constexpr QuadCoverage operator|(QuadCoverage a, QuadCoverage b) {
    return QuadCoverage(a.bits_ | b.bits_);
  }
  friend constexpr bool operator==(QuadCoverage, QuadCoverage) = default;

 private:
  std::uint64_t bits_ = 0;
};

}  // namespace raster
