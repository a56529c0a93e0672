// Sample patterns: validation and centroid priority (hw-facts §4.2), the built-in tables, and
// custom patterns read from JSON (docs/sample-patterns.md).

#include "raster/sample_pattern.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "raster/json_input.h"

#include "raster/raster_error.h"

namespace raster {
namespace {

using Offsets = std::vector<SampleOffset>;
using PerPixel = std::array<Offsets, kQuadPixels>;
using Table = std::span<const SampleOffset>;

// hw-facts §1.1 / §4.2: the hardware has 1x, 2x, 4x, 8x and 16x sample patterns.
constexpr std::array<int, 5> kLegalCounts = {1, 2, 4, 8, 16};

std::string JoinCounts(std::span<const int> counts) {
  std::string text;
  for (const int count : counts) text += (text.empty() ? "" : ", ") + std::to_string(count);
  return text;
}

std::string GridRule() {
  return "x and y must be integers in " + std::to_string(kSampleOffsetMin) + ".." +
         std::to_string(kSampleOffsetMax) + " (1/16 px)";
}

bool OnGrid(int v) { return v >= kSampleOffsetMin && v <= kSampleOffsetMax; }

void ValidatePixel(const std::string& name, int count, int pixel, const Offsets& offsets) {
  const std::string where = "pattern '" + name + "': quad pixel " + std::to_string(pixel);
  if (std::ssize(offsets) != count) {
    throw RasterError(where + " has " + std::to_string(offsets.size()) + " offsets, expected " +
                      std::to_string(count));
  }
  for (int s = 0; s < count; ++s) {
    const SampleOffset o = offsets[s];
    if (!OnGrid(o.x) || !OnGrid(o.y)) {
      throw RasterError(where + " sample " + std::to_string(s) + " offset (" + std::to_string(o.x) +
                        ", " + std::to_string(o.y) + ") is off the sample grid: " + GridRule());
    }
  }
}

// ---- Built-in tables ------------------------------------------------------------------------

// reference/hw-facts.md §4.1 (Vulkan standard sample locations = D3D10.1/11 standard pattern).
constexpr SampleOffset kStandard1[] = {{0, 0}};
constexpr SampleOffset kStandard2[] = {{4, 4}, {-4, -4}};
constexpr SampleOffset kStandard4[] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
constexpr SampleOffset kStandard8[] = {{1, -3}, {-1, 3},  {5, 1}, {-3, -5},
                                       {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
constexpr SampleOffset kStandard16[] = {{1, 1},  {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5},
                                        {5, 3},  {3, -5},  {-2, 6}, {0, -7}, {-4, -6}, {-6, 4},
                                        {-8, 0}, {7, -4},  {6, 7},  {-7, -8}};
constexpr std::array<Table, 5> kStandardTables = {kStandard1, kStandard2, kStandard4, kStandard8,
                                                  kStandard16};

// reference/hw-facts.md §4.3 (radeonsi EQAA order, SI-MSAA); the 16x table keeps radeonsi's
// -7 where the standard pattern has -8 (hw-facts §4.2, PA_SU_PRIM_FILTER_CNTL). §4.3 has no 1x
// table: 1x EQAA is the single centre sample, as in §4.1.
constexpr SampleOffset kEqaa2[] = {{-4, -4}, {4, 4}};
constexpr SampleOffset kEqaa4[] = {{-2, -6}, {2, 6}, {-6, 2}, {6, -2}};
constexpr SampleOffset kEqaa8[] = {{-3, -5}, {5, 1}, {-1, 3}, {7, -7},
                                   {-7, -1}, {3, 7}, {-5, 5}, {1, -3}};
constexpr SampleOffset kEqaa16[] = {{-5, -2}, {5, 3},  {-2, 6},  {3, -5}, {-4, -6}, {1, 1},
                                    {-6, 4},  {7, -4}, {-1, -3}, {6, 7},  {-3, 2},  {0, -7},
                                    {-7, -7}, {2, 5},  {-7, 0},  {4, -1}};
constexpr std::array<Table, 5> kEqaaTables = {kStandard1, kEqaa2, kEqaa4, kEqaa8, kEqaa16};

// Seed 001 "Sampling Patterns: 2x Rotated Grid" (2 unique rows and columns). The standard 2x
// pattern (hw-facts §4.1) is already a rotated grid on the other diagonal; this is its mirror, so
// the two can be compared.
constexpr SampleOffset kRotatedGrid2[] = {{-4, 4}, {4, -4}};
// Seed 001 "Sampling Patterns: 4x Rotated Grid" (RGSS): the 2x2 grid rotated by atan(1/2), 4
// unique rows and columns, listed clockwise from the top. Same positions as standard 4x
// (hw-facts §4.1), different order.
constexpr SampleOffset kRotatedGrid4[] = {{-2, -6}, {6, -2}, {2, 6}, {-6, 2}};

// Seed 001 "Sampling Patterns: 2x Quincunx", aa-facts §8: the centre plus the pixel's top-left
// corner, which the four pixels around that corner all see at resolve time.
constexpr SampleOffset kQuincunx2[] = {{0, 0}, {-8, -8}};

// FLIPQUAD (seed 001 "2x FLIPQUAD", aa-facts §8). In a unit pixel the four points are (0, 1/3),
// (2/3, 0), (1, 2/3), (1/3, 1); a pixel renders only its left-edge and top-edge points and
// borrows the other two from its right and bottom neighbours. Mirroring x -> 1 - x in alternate
// pixels (checkerboard) puts the right neighbour's left point at this pixel's right point; the
// set's half-turn symmetry makes that mirror also put the lower neighbour's top point at this
// pixel's bottom point. 1/3 and 2/3 snap to 5/16 and 11/16, offsets -3 and +3 from the centre
// (derivation in docs/sample-patterns.md).
constexpr SampleOffset kFlipQuadEven[] = {{-8, -3}, {3, -8}};
constexpr SampleOffset kFlipQuadOdd[] = {{-8, 3}, {-3, -8}};

Offsets ToOffsets(Table table) { return Offsets(table.begin(), table.end()); }

PerPixel Uniform(Table table) {
  PerPixel perPixel;
  perPixel.fill(ToOffsets(table));
  return perPixel;
}

int CountIndex(int samples) { return std::countr_zero(static_cast<unsigned>(samples)); }

PerPixel StandardOffsets(int samples) { return Uniform(kStandardTables[CountIndex(samples)]); }
PerPixel EqaaOffsets(int samples) { return Uniform(kEqaaTables[CountIndex(samples)]); }

PerPixel CentreOffsets(int samples) {
  PerPixel perPixel;
  perPixel.fill(Offsets(static_cast<std::size_t>(samples)));
  return perPixel;
}

PerPixel RotatedGridOffsets(int samples) {
  return Uniform(samples == 2 ? Table(kRotatedGrid2) : Table(kRotatedGrid4));
}

PerPixel QuincunxOffsets(int) { return Uniform(kQuincunx2); }

PerPixel FlipQuadOffsets(int) {
  PerPixel perPixel;
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 2; ++x) {
      perPixel[QuadPixelIndex(x, y)] = ToOffsets((x ^ y) == 0 ? kFlipQuadEven : kFlipQuadOdd);
    }
  }
  return perPixel;
}

struct Builtin {
  std::string_view name;
  std::span<const int> counts;
  PerPixel (*offsets)(int samples);  // called only with one of `counts`
};

constexpr std::array<int, 2> kRotatedGridCounts = {2, 4};
constexpr std::array<int, 1> kTwoOnly = {2};
constexpr std::array<Builtin, 6> kBuiltins = {{
    {"standard", kLegalCounts, StandardOffsets},
    {"eqaa", kLegalCounts, EqaaOffsets},
    {"centre", kLegalCounts, CentreOffsets},
    {"rotated-grid", kRotatedGridCounts, RotatedGridOffsets},
    {"quincunx", kTwoOnly, QuincunxOffsets},
    {"flipquad", kTwoOnly, FlipQuadOffsets},
}};

constexpr std::string_view kHaltonPrefix = "halton:";

std::string BuiltinCatalogue() {
  std::string text = "built-in patterns (sample counts):";
  for (const Builtin& builtin : kBuiltins) {
    text += " " + std::string(builtin.name) + " (" + JoinCounts(builtin.counts) + "),";
  }
  return text + " halton:K (1; K >= 0)";
}

// ---- Halton jitter (aa-facts §5) ------------------------------------------------------------

// floor(16 * h) for the radical inverse h of `index` in `base`, computed exactly in integers so
// the grid cell never depends on floating-point rounding. index <= 2^31 keeps base^digits at most
// 2^32 (base 2) or 3^20 (base 3), so 16 * numerator fits in 64 bits.
int RadicalInverseSixteenths(std::uint64_t index, std::uint64_t base) {
  std::uint64_t numerator = 0;
  std::uint64_t denominator = 1;
  for (; index > 0; index /= base) {
    numerator = numerator * base + index % base;
    denominator *= base;
  }
  return static_cast<int>(numerator * 16 / denominator);
}

// The K-th jitter point uses Halton index K + 1, as UE4 and INSIDE do (aa-facts §5.2): index 0
// would be the corner (0, 0) of every base.
SamplePattern HaltonPattern(int k) {
  const std::uint64_t index = static_cast<std::uint64_t>(k) + 1;
  const SampleOffset offset{RadicalInverseSixteenths(index, 2) + kSampleOffsetMin,
                            RadicalInverseSixteenths(index, 3) + kSampleOffsetMin};
  return SamplePattern::CreateUniform(std::string(kHaltonPrefix) + std::to_string(k),
                                      std::span(&offset, 1));
}

SamplePattern MakeHalton(std::string_view name, int samples) {
  const std::string_view digits = name.substr(kHaltonPrefix.size());
  int k = -1;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), k);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || k < 0) {
    throw RasterError("sample pattern '" + std::string(name) +
                      "': K must be a decimal integer >= 0; " + BuiltinCatalogue());
  }
  if (samples != 1) {
    throw RasterError("sample pattern '" + std::string(name) + "' has no " +
                      std::to_string(samples) + "-sample version; " + BuiltinCatalogue());
  }
  return HaltonPattern(k);
}

// ---- JSON custom patterns (docs/sample-patterns.md) ------------------------------------------

enum class Units { kSixteenths, kPixels };

constexpr std::array<std::string_view, 5> kJsonKeys = {"name", "samples", "units", "offsets",
                                                       "pixels"};

std::string KeyList() {
  std::string keys;
  for (const std::string_view key : kJsonKeys) {
    keys += (keys.empty() ? "" : ", ") + std::string(key);
  }
  return keys;
}

class PatternFileParser {
 public:
  PatternFileParser(std::string_view source, int expectedSamples)
      : source_(source), expectedSamples_(expectedSamples) {}

  SamplePattern Parse(std::string_view jsonText) const {
    const nlohmann::json root = ParseText(jsonText);
    CheckKeys(root);
    const std::string name = Name(root);
    const int count = SampleCount(root);
    const Units units = ParseUnits(root);
    const bool uniform = root.contains("offsets");
    if (uniform == root.contains("pixels")) {
      Fail(uniform ? "has both \"offsets\" and \"pixels\"; use one"
                   : "has neither \"offsets\" nor \"pixels\"");
    }
    PerPixel perPixel;
    if (uniform) {
      perPixel.fill(ParseList(root.at("offsets"), count, units, std::nullopt));
    } else {
      perPixel = ParsePixels(root.at("pixels"), count, units);
    }
    try {
      return SamplePattern::Create(name, count, perPixel);
    } catch (const RasterError& e) {
      throw RasterError(Subject() + ": " + e.what());
    }
  }

 private:
  std::string Subject() const { return "pattern file '" + source_ + "'"; }
  // "pattern file 'f.json' <problem>", for problems of the file as a whole.
  [[noreturn]] void Fail(const std::string& problem) const {
    throw RasterError(Subject() + " " + problem);
  }
  // "pattern file 'f.json': <where> <problem>", for problems of one sample.
  [[noreturn]] void FailAt(const std::string& where, const std::string& problem) const {
    throw RasterError(Subject() + ": " + where + " " + problem);
  }

  nlohmann::json ParseText(std::string_view jsonText) const {
    nlohmann::json root;
    try {
      root = ParseJsonText(jsonText, /*allowComments=*/false);
    } catch (const JsonTextError& e) {
      Fail(e.what());
    }
    if (!root.is_object()) Fail("must hold one JSON object, found " + JsonExcerpt(root));
    return root;
  }

  void CheckKeys(const nlohmann::json& root) const {
    for (const auto& item : root.items()) {
      if (std::ranges::find(kJsonKeys, item.key()) == kJsonKeys.end()) {
        Fail("has unknown key \"" + item.key() + "\"; the keys are " + KeyList());
      }
    }
  }

  const nlohmann::json& Required(const nlohmann::json& root, const char* key) const {
    if (!root.contains(key)) Fail(std::string("has no \"") + key + "\" key");
    return root.at(key);
  }

  std::string Name(const nlohmann::json& root) const {
    const nlohmann::json& name = Required(root, "name");
    if (!name.is_string() || name.get_ref<const std::string&>().empty()) {
      Fail("needs \"name\" to be a non-empty string, found " + JsonExcerpt(name));
    }
    return name.get<std::string>();
  }

  int SampleCount(const nlohmann::json& root) const {
    const nlohmann::json& samples = Required(root, "samples");
    if (!samples.is_number_integer()) {
      Fail("needs \"samples\" to be an integer, found " + JsonExcerpt(samples));
    }
    if (samples.get<std::int64_t>() != expectedSamples_) {
      Fail("defines " + JsonExcerpt(samples) + " samples but --samples is " +
           std::to_string(expectedSamples_));
    }
    return expectedSamples_;
  }

  Units ParseUnits(const nlohmann::json& root) const {
    if (!root.contains("units")) return Units::kSixteenths;
    const nlohmann::json& units = root.at("units");
    if (units == "sixteenths") return Units::kSixteenths;
    if (units == "pixels") return Units::kPixels;
    Fail("needs \"units\" to be \"sixteenths\" or \"pixels\", found " + JsonExcerpt(units));
  }

  PerPixel ParsePixels(const nlohmann::json& pixels, int count, Units units) const {
    if (!pixels.is_array() || pixels.size() != kQuadPixels) {
      Fail("needs \"pixels\" to be 4 lists, one per quad pixel, found " + JsonExcerpt(pixels));
    }
    PerPixel perPixel;
    for (int p = 0; p < kQuadPixels; ++p) perPixel[p] = ParseList(pixels[p], count, units, p);
    return perPixel;
  }

  // `pixel` is empty for the "offsets" form, which applies to every quad pixel.
  Offsets ParseList(const nlohmann::json& list, int count, Units units,
                    std::optional<int> pixel) const {
    const std::string owner = pixel ? " for quad pixel " + std::to_string(*pixel) : "";
    if (!list.is_array()) Fail("needs a list of [x, y] pairs" + owner + ", found " + JsonExcerpt(list));
    if (std::ssize(list) != count) {
      Fail("has " + std::to_string(list.size()) + " offsets" + owner + ", expected " +
           std::to_string(count));
    }
    Offsets offsets;
    for (int s = 0; s < count; ++s) offsets.push_back(ParsePair(list[s], units, pixel, s));
    return offsets;
  }

  SampleOffset ParsePair(const nlohmann::json& pair, Units units, std::optional<int> pixel,
                         int sample) const {
    const std::string where = (pixel ? "quad pixel " + std::to_string(*pixel) + " " : "") +
                              "sample " + std::to_string(sample);
    if (!pair.is_array() || pair.size() != 2 || !pair[0].is_number() || !pair[1].is_number()) {
      FailAt(where, "must be an [x, y] pair of numbers, found " + JsonExcerpt(pair));
    }
    const std::optional<int> x = ToSixteenths(pair[0].get<double>(), units);
    const std::optional<int> y = ToSixteenths(pair[1].get<double>(), units);
    if (!x || !y) {
      const std::string rule =
          units == Units::kPixels
              ? "x and y must be multiples of 1/16 in [0, 1) (px from the pixel's top-left corner)"
              : GridRule();
      FailAt(where, (units == Units::kPixels ? "position (" : "offset (") + JsonExcerpt(pair[0]) + ", " +
                        JsonExcerpt(pair[1]) + ") is off the sample grid: " + rule);
    }
    return {*x, *y};
  }

  // Pixel positions convert as floor((p - 0.5) * 16) (hw-facts §4.4), accepted only when exact:
  // a value between grid points would otherwise move silently. p * 16 is exact in binary
  // floating point, so it is an integer exactly when p is on the grid; the grid test comes
  // before the shift by -8, which would round a tiny off-grid p (5e-324) onto the grid.
  static std::optional<int> ToSixteenths(double value, Units units) {
    const double scaled = units == Units::kPixels ? value * 16.0 : value;
    if (!std::isfinite(scaled) || std::floor(scaled) != scaled) return std::nullopt;
    const double sixteenths = units == Units::kPixels ? scaled + kSampleOffsetMin : scaled;
    if (sixteenths < kSampleOffsetMin || sixteenths > kSampleOffsetMax) return std::nullopt;
    return static_cast<int>(sixteenths);
  }

  std::string source_;
  int expectedSamples_;
};

}  // namespace

// ---- SamplePattern --------------------------------------------------------------------------

SamplePattern SamplePattern::Create(
    std::string name, int count,
    const std::array<std::vector<SampleOffset>, kQuadPixels>& perPixel) {
  if (std::ranges::find(kLegalCounts, count) == kLegalCounts.end()) {
    throw RasterError("pattern '" + name + "': " + std::to_string(count) +
                      " samples; legal counts are " + JoinCounts(kLegalCounts));
  }
  for (int p = 0; p < kQuadPixels; ++p) ValidatePixel(name, count, p, perPixel[p]);

  SamplePattern pattern;
  pattern.name_ = std::move(name);
  pattern.count_ = count;
  for (int p = 0; p < kQuadPixels; ++p) {
    std::ranges::copy(perPixel[p], pattern.offsets_[p].begin());
  }
  // hw-facts §4.2: PAL and RADV sort the top-left pixel's samples by squared distance to the
  // centre, earlier index first on ties, and repeat the list as index & (N - 1).
  std::array<std::uint8_t, kMaxCoverageSamples> order{};
  std::iota(order.begin(), order.begin() + count, std::uint8_t{0});
  const auto distance = [&](std::uint8_t s) {
    const SampleOffset o = pattern.offsets_[0][s];
    return o.x * o.x + o.y * o.y;
  };
  std::ranges::stable_sort(order.begin(), order.begin() + count, {}, distance);
  for (int k = 0; k < kMaxCoverageSamples; ++k) {
    pattern.centroidPriority_[k] = order[k & (count - 1)];
  }
  return pattern;
}

SamplePattern SamplePattern::CreateUniform(std::string name,
                                           std::span<const SampleOffset> offsets) {
  std::array<std::vector<SampleOffset>, kQuadPixels> perPixel;
  perPixel.fill(ToOffsets(offsets));
  return Create(std::move(name), static_cast<int>(offsets.size()), perPixel);
}

bool SamplePattern::SameInAllPixels() const {
  return std::ranges::all_of(offsets_, [&](const auto& pixel) { return pixel == offsets_[0]; });
}

int SamplePattern::MaxSampleDistance() const {
  int distance = 0;
  for (const auto& pixel : offsets_) {
    for (int s = 0; s < count_; ++s) {
      distance = std::max({distance, std::abs(pixel[s].x), std::abs(pixel[s].y)});
    }
  }
  return distance;
}

// ---- Built-ins ------------------------------------------------------------------------------

SamplePattern MakeBuiltinPattern(std::string_view name, int samples) {
  if (name.starts_with(kHaltonPrefix)) return MakeHalton(name, samples);
  const auto builtin = std::ranges::find(kBuiltins, name, &Builtin::name);
  if (builtin == kBuiltins.end()) {
    throw RasterError("unknown sample pattern '" + std::string(name) + "'; " + BuiltinCatalogue());
  }
  if (std::ranges::find(builtin->counts, samples) == builtin->counts.end()) {
    throw RasterError("sample pattern '" + std::string(name) + "' has no " +
                      std::to_string(samples) + "-sample version; " + BuiltinCatalogue());
  }
  return SamplePattern::Create(std::string(name), samples, builtin->offsets(samples));
}

std::vector<std::string> BuiltinPatternNames() {
  std::vector<std::string> names;
  for (const Builtin& builtin : kBuiltins) names.emplace_back(builtin.name);
  names.push_back(std::string(kHaltonPrefix) + "K");
  return names;
}

std::vector<SamplePattern> HaltonJitterSequence(int length) {
  if (length < 0) {
    throw RasterError("Halton jitter sequence length " + std::to_string(length) + " is negative");
  }
  std::vector<SamplePattern> sequence;
  for (int k = 0; k < length; ++k) sequence.push_back(HaltonPattern(k));
  return sequence;
}

// ---- JSON -----------------------------------------------------------------------------------

SamplePattern ParsePatternJson(std::string_view jsonText, int expectedSamples,
                               std::string_view sourceName) {
  return PatternFileParser(sourceName, expectedSamples).Parse(jsonText);
}

SamplePattern LoadPatternJson(const std::filesystem::path& path, int expectedSamples) {
  std::string text;
  try {
    text = ReadJsonFile(path);
  } catch (const JsonTextError& e) {
    throw RasterError("pattern file '" + path.string() + "' " + e.what());
  }
  return ParsePatternJson(text, expectedSamples, path.string());
}

std::string FormatPatternJson(const SamplePattern& pattern) {
  const auto pixelJson = [&](int pixel) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (int s = 0; s < pattern.Count(); ++s) {
      const SampleOffset o = pattern.Offset(pixel, s);
      list.push_back({o.x, o.y});
    }
    return list;
  };
  // Ordered so the file reads in the documented key order: name, samples, offsets or pixels.
  nlohmann::ordered_json root = {{"name", pattern.Name()}, {"samples", pattern.Count()}};
  if (pattern.SameInAllPixels()) {
    root["offsets"] = pixelJson(0);
  } else {
    for (int p = 0; p < kQuadPixels; ++p) root["pixels"].push_back(pixelJson(p));
  }
  return root.dump();
}

SamplePattern ResolvePattern(std::string_view spec, int samples) {
  if (spec.find('/') != std::string_view::npos || spec.ends_with(".json")) {
    return LoadPatternJson(std::filesystem::path(spec), samples);
  }
  return MakeBuiltinPattern(spec, samples);
}

}  // namespace raster
