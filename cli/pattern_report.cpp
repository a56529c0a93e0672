// The sample-pattern error table (see pattern_report.h).

#include "cli/pattern_report.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "cli/number_format.h"
#include "raster/pattern_error.h"

namespace cli {
namespace {

using raster::ReferenceFilter, raster::SampleOffset, raster::SamplePattern;

// Seed 001 "FLIPQUAD: In Practice" table (after Laine & Aila 2006), aa-facts §8.
constexpr const char* kSeedCentre = ">1.0";
constexpr const char* kSeedUniformGrid = "0.698";
constexpr const char* kSeedRotatedGrid = "0.439";
constexpr const char* kSeedQuincunx = "0.518";
constexpr const char* kSeedFlipQuad = "0.364";

// `aasim patterns optimise --samples N --out docs/patterns/optimised-N.json` with the defaults
// (seed 1, start standard, 20000 iterations, box reference); docs/sample-patterns.md.
const std::map<int, std::vector<SampleOffset>>& OptimisedOffsets() {
  static const std::map<int, std::vector<SampleOffset>> offsets = {
      {2, {{-3, 4}, {3, -4}}},
      {4, {{-3, -5}, {5, -3}, {-5, 3}, {3, 5}}},
      {8, {{3, -6}, {6, -2}, {-6, 2}, {-3, 6}, {5, 6}, {2, 2}, {-5, -6}, {-2, -2}}},
      {16, {{5, -6}, {1, 2}, {1, 6}, {-4, -6}, {-2, 4}, {1, -3}, {-5, 0}, {7, 3},
            {-7, 3}, {5, 6}, {4, 0}, {7, -3}, {-7, -4}, {-2, -2}, {1, -7}, {-5, 7}}},
  };
  return offsets;
}

// "1/8" for 0.125; weights of the footprints here are unit fractions.
std::string Fraction(double weight) {
  const double inverse = 1.0 / weight;
  if (std::fabs(inverse - std::round(inverse)) < 1e-9) return "1/" + FormatFixed(std::round(inverse), 0);
  return FormatFixed(weight, 4);
}

// "4 own, 1/4 each" or "5 (2 own, rest shared): 1/2 x1, 1/8 x4", for quad pixel 0.
std::string DescribeFootprint(const SamplePattern& pattern) {
  const raster::Footprint footprint = raster::ResolveFootprints(pattern)[0];
  const std::size_t count = footprint.samples.size();
  if (!raster::IsSharedSamplePattern(pattern)) {
    return count == 1 ? "1 own" : std::to_string(count) + " own, " + Fraction(footprint.samples[0].weight) + " each";
  }
  std::vector<std::pair<double, int>> weights;  // in first-seen order
  for (const raster::FootprintSample& sample : footprint.samples) {
    bool seen = false;
    for (auto& [weight, n] : weights) {
      if (std::fabs(weight - sample.weight) < 1e-12) ++n, seen = true;
    }
    if (!seen) weights.push_back({sample.weight, 1});
  }
  std::string text = std::to_string(count) + " (" + std::to_string(pattern.Count()) + " own, rest shared):";
  for (std::size_t i = 0; i < weights.size(); ++i) {
    text += (i == 0 ? " " : ", ") + Fraction(weights[i].first) + " x" + std::to_string(weights[i].second);
  }
  return text;
}

SamplePattern UniformGrid() {
  // The 2x2 grid at the quarter points, +-1/4 px: 4/16 on the sample grid.
  const std::vector<SampleOffset> offsets = {{-4, -4}, {4, -4}, {-4, 4}, {4, 4}};
  return SamplePattern::CreateUniform("2x2 uniform grid", offsets);
}

}  // namespace

PatternErrorRow PatternErrorRowOf(const SamplePattern& pattern, std::string name, std::string seedValue) {
  return {std::move(name),
          pattern.Count(),
          DescribeFootprint(pattern),
          raster::PatternError(pattern, ReferenceFilter::kBox),
          raster::PatternError(pattern, ReferenceFilter::kTent),
          std::move(seedValue)};
}

SamplePattern OptimisedPattern(int samples) {
  const auto found = OptimisedOffsets().find(samples);
  if (found == OptimisedOffsets().end()) {
    throw std::invalid_argument("no optimised pattern for " + std::to_string(samples) + " samples");
  }
  return SamplePattern::CreateUniform("optimised-" + std::to_string(samples), found->second);
}

std::vector<PatternErrorRow> PatternErrorRows() {
  using raster::MakeBuiltinPattern;
  std::vector<PatternErrorRow> rows = {
      PatternErrorRowOf(MakeBuiltinPattern("standard", 1), "1x centre", kSeedCentre),
      PatternErrorRowOf(UniformGrid(), "2x2 uniform grid", kSeedUniformGrid),
      PatternErrorRowOf(MakeBuiltinPattern("rotated-grid", 4), "2x2 rotated grid (RGSS)", kSeedRotatedGrid),
      PatternErrorRowOf(MakeBuiltinPattern("quincunx", 2), "quincunx", kSeedQuincunx),
      PatternErrorRowOf(MakeBuiltinPattern("flipquad", 2), "FLIPQUAD", kSeedFlipQuad),
  };
  for (const char* family : {"standard", "eqaa"}) {
    for (const int samples : {2, 4, 8, 16}) {
      rows.push_back(PatternErrorRowOf(MakeBuiltinPattern(family, samples),
                                       std::string(family) + " " + std::to_string(samples) + "x"));
    }
  }
  for (const int samples : {2, 4, 8, 16}) {
    rows.push_back(PatternErrorRowOf(OptimisedPattern(samples), "optimised " + std::to_string(samples) + "x"));
  }
  return rows;
}

ReportSection PatternErrorSection() {
  ReportSection section{"Sample-pattern error", {}, {}, {}, {}};
  section.paragraphs.push_back(
      "E: a Laine–Aila-style weighted coverage error of straight edges over all orientations and offsets "
      "(lower is better; 1 = one centre sample on axis-aligned edges against the box reference). \"box\" compares "
      "the resolve's estimate with the pixel's area coverage, \"tent\" with the pixel widened by a 0.5-px-radius "
      "blur, which quincunx and FLIPQUAD resolves add (seed 001). Patterns that differ per quad pixel report the "
      "root mean square over the four pixels. The seed's values (Laine & Aila 2006) use a weighting and "
      "normalisation of their own: compare rankings, not values (docs/sample-patterns.md).");
  ReportTable table{"Pattern error", {"pattern", "samples", "resolve footprint", "E box", "E tent", "seed 001"}, {}};
  BarChart chart{"Sample-pattern error E (lower is better)", "E", {}, {"box reference", "tent reference"}, {{}, {}}, false};
  for (const PatternErrorRow& row : PatternErrorRows()) {
    table.rows.push_back({row.name, std::to_string(row.samples), row.footprint, FormatFixed(row.errorBox, 4),
                          FormatFixed(row.errorTent, 4), row.seedValue.empty() ? "-" : row.seedValue});
    chart.categories.push_back(row.name);
    chart.values[0].push_back(row.errorBox);
    chart.values[1].push_back(row.errorTent);
  }
  section.tables.push_back(std::move(table));
  section.charts.push_back(std::move(chart));
  return section;
}

nlohmann::ordered_json PatternErrorJson() {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const PatternErrorRow& row : PatternErrorRows()) {
    rows.push_back({{"pattern", row.name},
                    {"samples", row.samples},
                    {"footprint", row.footprint},
                    {"error_box", row.errorBox},
                    {"error_tent", row.errorTent},
                    {"seed", row.seedValue.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(row.seedValue)}});
  }
  return {{"metric", "weighted straight-edge coverage error E, docs/sample-patterns.md \"Pattern error\""},
          {"orientations", raster::kErrorOrientations},
          {"axis_emphasis", raster::kAxisEmphasis},
          {"patterns", rows}};
}

}  // namespace cli
