#pragma once
// The CRAA LUT (seed 001 "8xCRAA LUT"): for a 1F xS surface, one entry per FMASK value holding
// how many of the pixel's S samples take the stored fragment of each of its four edge neighbours
// (up, bottom, left, right); the rest take the pixel's own fragment. The resolve reads
// FMASK -> entry -> blends (docs/craa.md "CRAA LUT"):
//
//   colour = (own * (S - U - B - L - R) + U * up + B * bottom + L * left + R * right) / S
//
// where each neighbour's colour is that pixel's stored fragment (fragment 0). The table comes
// from GenerateCraaLut, a least-squares fit of those weights to the exact coverage of synthetic
// configurations on the given sample pattern, and is kept as a JSON fixture (ParseCraaLut /
// FormatCraaLut).

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "raster/sample_pattern.h"

namespace passes::craa {

// One entry: sample counts, each 0..kMaxLutWeight, summing to at most the UNKNOWN samples of
// its FMASK (so at most S): only samples the FMASK marks UNKNOWN are given to a neighbour.
struct LutEntry {
  std::uint8_t up = 0;
  std::uint8_t bottom = 0;
  std::uint8_t left = 0;
  std::uint8_t right = 0;
  int Sum() const { return up + bottom + left + right; }
  friend bool operator==(const LutEntry&, const LutEntry&) = default;
};

// Seed 001 "8xCRAA LUT: In Practice": weights are 4 bits.
inline constexpr int kMaxLutWeight = 15;

// GPU layout of an entry, 16 bits: up | bottom << 4 | left << 8 | right << 12.
std::uint16_t PackLutEntry(const LutEntry& entry);
LutEntry UnpackLutEntry(std::uint16_t packed);

// Why an entry holds what it holds.
enum class LutEntrySource : std::uint8_t {
  kFitted,    // least-squares fit over the configurations that produce this FMASK
  kFallback,  // no configuration produced this FMASK: nearest-edge rule (docs/craa.md)
  kFixed,     // FMASK 0: no UNKNOWN sample, all own by definition
};

class CraaLut {
 public:
  // `entries` holds Tables() * 2^samples entries, table t (quad pixel t when there are 4) at
  // [t << samples, (t + 1) << samples). `sources` is empty or the same size. Throws
  // std::invalid_argument when the sizes, a weight or a sum is out of range.
  CraaLut(std::string patternName, int samples, std::vector<std::vector<raster::SampleOffset>> offsets,
          std::vector<LutEntry> entries, std::vector<LutEntrySource> sources = {});

  int Samples() const { return samples_; }
  // 1 when the pattern is the same in all quad pixels, else 4 (one per quad pixel, indexed by
  // raster::QuadPixelIndex).
  int Tables() const { return static_cast<int>(offsets_.size()); }
  int EntriesPerTable() const { return 1 << samples_; }
  const std::string& PatternName() const { return patternName_; }
  // The sample offsets (1/16 px) of table t's quad pixel that the table was made for.
  const std::vector<raster::SampleOffset>& Offsets(int table) const { return offsets_.at(table); }

  // `quadPixel` is 0..3 whatever Tables() is; `fmask` is the 1F FMASK element (bit i = sample i,
  // 1 = UNKNOWN), below 2^Samples().
  const LutEntry& Entry(int quadPixel, std::uint32_t fmask) const { return entries_.at(Index(quadPixel, fmask)); }
  std::uint16_t Packed(int quadPixel, std::uint32_t fmask) const { return PackLutEntry(Entry(quadPixel, fmask)); }
  // Source of an entry; kFitted for every entry of a table read from a fixture without sources.
  LutEntrySource Source(int quadPixel, std::uint32_t fmask) const;
  // All entries, table after table.
  const std::vector<LutEntry>& Entries() const { return entries_; }
  // What the table takes on the GPU: 2 bytes per entry (512 bytes for one 8S table, seed 001).
  std::size_t Bytes() const { return entries_.size() * sizeof(std::uint16_t); }

  friend bool operator==(const CraaLut&, const CraaLut&) = default;

 private:
  std::size_t Index(int quadPixel, std::uint32_t fmask) const;

  std::string patternName_;
  int samples_ = 1;
  std::vector<std::vector<raster::SampleOffset>> offsets_;
  std::vector<LutEntry> entries_;
  std::vector<LutEntrySource> sources_;
};

// The configuration distribution and fit options (docs/craa.md "Configurations"). Counts are base
// configurations; each is also used in its 8 mirror/rotation images and every draw order of its
// surfaces. Positions are in pixels, the centre pixel spanning [0, 1] x [0, 1].
struct LutGeneratorSettings {
  int edges = 192000;        // one straight edge crossing the centre pixel
  int corners = 192000;      // a wedge (two half-planes) over a background
  int junctions = 192000;    // three regions meeting at a point inside the centre pixel
  int slivers = 192000;      // a strip narrower than a pixel crossing the centre pixel
  int sliverEdges = 96000;   // a strip crossing a straight edge (three surfaces)
  int triangles = 96000;     // a triangle with vertices anywhere in the 3x3 neighbourhood
  double maxSliverWidth = 0.75;  // px; strip widths are uniform in (0, maxSliverWidth]
  double apexMargin = 0.25;      // px; corner apexes lie within the centre pixel grown by this
  std::uint64_t seed = 1;        // of the counter-based random numbers; any value
  // 0 = one per hardware thread (oneTBB's choice); the table does not depend on it.
  int threads = 0;
};

// The largest total count the generator accepts (keeps its 64-bit sums exact).
inline constexpr std::int64_t kMaxLutConfigurations = std::int64_t{1} << 21;

// `settings` with `total` configurations split over the families in the default proportions
// (2 : 2 : 2 : 2 : 1 : 1); the default total is 960000.
LutGeneratorSettings WithConfigurations(LutGeneratorSettings settings, std::int64_t total);

struct LutFitSummary {
  int fitted = 0;        // entries fitted from at least one configuration
  int fallbacks = 0;     // entries no configuration produced (nearest-edge rule)
  std::uint64_t evaluations = 0;  // configurations x 8 images x tables (each over all draw orders)
  // Mean over all evaluations of sum_k (predicted_k - area_k)^2, with the table and with every
  // entry all-own (weights 0).
  double meanError = 0.0;
  double meanErrorAllOwn = 0.0;
};

struct GeneratedCraaLut {
  CraaLut lut;
  LutFitSummary summary;
  // Per entry (as CraaLut::Entries()): the mean squared coverage error of its weights over the
  // configurations that produce its FMASK; 0 where none does.
  std::vector<double> entryError;
};

// Deterministic for given pattern and settings, whatever the thread count. Throws
// std::invalid_argument for a setting out of range (message names it).
GeneratedCraaLut GenerateCraaLutWithSummary(const raster::SamplePattern& pattern,
                                            const LutGeneratorSettings& settings = {});
CraaLut GenerateCraaLut(const raster::SamplePattern& pattern, const LutGeneratorSettings& settings = {});

// Errors of the fixture reader: one line naming the source and where in it.
class CraaLutError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The JSON fixture (docs/craa.md "File format"). Strict: unknown keys, wrong types, weights out
// of range, a wrong entry count or a weight sum above the entry's UNKNOWN samples are errors.
CraaLut ParseCraaLut(std::string_view text, std::string_view sourceName);
std::string FormatCraaLut(const CraaLut& lut);

inline constexpr const char* kCraaLutSchema = "aasim.craa.lut";
inline constexpr int kCraaLutVersion = 1;

}  // namespace passes::craa
