#pragma once
// Programmable sample positions (hw-facts §4). A pattern has 1, 2, 4, 8 or 16 samples and one
// set of offsets per pixel of a 2x2 quad (pixel order as in coverage_mask.h); screen pixel
// (x, y) uses quad pixel QuadPixelIndex(x, y). Offsets are signed 1/16-px steps from the pixel
// centre, -8..7 on each axis, +y down (DESIGN.md "Conventions").

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "raster/coverage_mask.h"
#include "raster/limits.h"

namespace raster {

struct SampleOffset {
  int x = 0;  // 1/16 px, kSampleOffsetMin..kSampleOffsetMax
  int y = 0;
  friend bool operator==(const SampleOffset&, const SampleOffset&) = default;
};

class SamplePattern {
 public:
  // Validates count (1, 2, 4, 8, 16) and every offset; throws RasterError naming the pattern,
  // the quad pixel and the sample on failure. `perPixel[p]` must hold exactly `count` offsets.
  static SamplePattern Create(std::string name, int count,
                              const std::array<std::vector<SampleOffset>, kQuadPixels>& perPixel);
  // Same offsets in all four quad pixels.
  static SamplePattern CreateUniform(std::string name, std::span<const SampleOffset> offsets);

  const std::string& Name() const { return name_; }
  int Count() const { return count_; }
  SampleOffset Offset(int quadPixel, int sample) const { return offsets_[quadPixel][sample]; }
  bool SameInAllPixels() const;

  // hw-facts §4.2 PA_SC_CENTROID_PRIORITY: the samples of the top-left pixel sorted by squared
  // distance to the pixel centre, earliest index first on ties.
  const std::array<std::uint8_t, kMaxCoverageSamples>& CentroidPriority() const {
    return centroidPriority_;
  }
  // hw-facts §4.2 PA_SC_AA_CONFIG.MAX_SAMPLE_DIST: largest |x| or |y| over the quad's samples.
  int MaxSampleDistance() const;

  friend bool operator==(const SamplePattern&, const SamplePattern&) = default;

 private:
  std::string name_;
  int count_ = 1;
  std::array<std::array<SampleOffset, kMaxCoverageSamples>, kQuadPixels> offsets_{};
  std::array<std::uint8_t, kMaxCoverageSamples> centroidPriority_{};
};

// Built-in patterns; `name` is one of BuiltinPatternNames() (for "halton", see below). Throws
// RasterError listing the legal names and counts when the name or count does not exist.
//   standard      D3D/Vulkan standard positions, hw-facts §4.1 (1, 2, 4, 8, 16)
//   eqaa          radeonsi's EQAA re-indexed order, hw-facts §4.3 (2, 4, 8, 16; 1 = centre)
//   centre        every sample at the pixel centre (D3D11 centre pattern, hw-facts §2.4)
//   rotated-grid  2x and 4x rotated grid (seed 001 "Sampling Patterns")
//   quincunx      2x: centre + shared top-left corner (seed 001; aa-facts §8)
//   flipquad      2x FLIPQUAD: edge samples mirrored per quad pixel (seed 001; aa-facts §8)
//   halton:K      1 sample, the K-th (K >= 0) Halton(2,3) jitter offset (seed 002; aa-facts §5)
SamplePattern MakeBuiltinPattern(std::string_view name, int samples);
std::vector<std::string> BuiltinPatternNames();

// The first `length` Halton(2,3) jitter offsets as 1-sample patterns, for temporal passes.
std::vector<SamplePattern> HaltonJitterSequence(int length);

// Custom patterns from JSON (format documented in docs/sample-patterns.md). `expectedSamples`
// must match the file's sample count. Errors name the file and, where it applies, the sample.
SamplePattern LoadPatternJson(const std::filesystem::path& path, int expectedSamples);
SamplePattern ParsePatternJson(std::string_view jsonText, int expectedSamples,
                               std::string_view sourceName);

// The JSON text ParsePatternJson reads back into an equal pattern: the "offsets" form when the
// pattern is the same in all quad pixels, else the "pixels" form; offsets in sixteenths.
std::string FormatPatternJson(const SamplePattern& pattern);

// `spec` is a built-in name or a path to a JSON file (it contains '/' or ends in ".json").
SamplePattern ResolvePattern(std::string_view spec, int samples);

}  // namespace raster
