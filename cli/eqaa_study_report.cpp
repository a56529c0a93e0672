// The EQAA study's report section and JSON (see eqaa_study_report.h).

#include "cli/eqaa_study_report.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "cli/number_format.h"
#include "cli/report_json.h"
#include "study/eqaa_study.h"

namespace cli {
namespace {

using study::EqaaStudyRow;

// Seed 001, the timing table after the results ("Single Pass / Timing (ms)"; PS4, 1080p, seed
// 001's HRAA goals): 8xCRAA 0.25 ms, SMAA 0.9 ms.
constexpr double kSeedCraaMilliseconds = 0.25;
constexpr double kSeedSmaaMilliseconds = 0.9;

double PerPixel(std::uint64_t bytes, std::uint64_t pixels) {
  return pixels == 0 ? 0.0 : static_cast<double>(bytes) / static_cast<double>(pixels);
}

std::string Label(const EqaaStudyRow& row) { return row.mode + " " + row.policy + " " + row.resolve; }

std::vector<std::string> TableRow(const EqaaStudyRow& row) {
  const passes::QualityScores& q = row.quality;
  return {row.mode,
          row.policy,
          row.resolve,
          FormatFixed(q.psnr, 2),
          FormatFixed(q.ssim, 4),
          FormatFixed(q.flip, 4),
          FormatFixed(q.edgeFlip, 4),
          FormatFixed(PerPixel(row.written.fmaskWritten, row.pixels), 2),
          FormatFixed(PerPixel(row.written.colourWritten, row.pixels), 2),
          FormatFixed(PerPixel(row.fmaskBytesRead, row.pixels), 2),
          FormatFixed(PerPixel(row.fragmentBytesRead, row.pixels), 2),
          FormatFixed(PerPixel(row.tableBytesRead, row.pixels), 2),
          FormatFixed(PerPixel(row.unknown.eviction, row.pixels), 3),
          FormatFixed(PerPixel(row.unknown.untestable, row.pixels), 3),
          FormatFixed(PerPixel(row.unknown.initial, row.pixels), 3),
          std::to_string(row.evictions),
          std::to_string(row.resolveWaves),
          FormatPercent(row.resolveLanesActive, row.resolveLanesLaunched),
          FormatFixed(row.resolveMicroseconds, 1)};
}

// The run's SMAA cost: the `smaa` pass's cheaper strategy, every dispatch summed.
std::optional<double> SmaaMicroseconds(const study::Study& study) {
  std::optional<double> best;
  for (const study::StudyPass& pass : study.passes) {
    if (pass.name != "smaa") continue;
    for (const study::StudyPassRun& run : pass.runs) {
      double total = 0.0;
      for (std::size_t i = run.firstDispatch; i < run.endDispatch; ++i) {
        total += study.dispatches[i].report.time.totalMicroseconds;
      }
      best = best ? std::min(*best, total) : total;
    }
  }
  return best;
}

std::optional<EqaaStudyRow> CraaLut8(const std::vector<EqaaStudyRow>& rows, const study::Study& study) {
  for (const EqaaStudyRow& row : rows) {
    if (row.mode == "8S/8Z/1F" && row.resolve == "craa-lut" &&
        (study.frames.empty() || row.policy == study.frames.front().policy)) {
      return row;
    }
  }
  return std::nullopt;
}

struct SeedComparison {
  std::optional<double> craaMs, smaaMs;  // aasim's estimates scaled to 1080p
  double scale = 1.0;                    // 1080p pixels / the run's pixels
};

SeedComparison CompareWithSeed(const study::Study& study, const std::vector<EqaaStudyRow>& rows) {
  SeedComparison comparison;
  if (rows.empty()) return comparison;
  comparison.scale = kSeedTimingPixels / static_cast<double>(rows.front().pixels);
  if (const std::optional<EqaaStudyRow> craa = CraaLut8(rows, study)) {
    comparison.craaMs = craa->resolveMicroseconds / 1000.0 * comparison.scale;
  }
  if (const std::optional<double> smaa = SmaaMicroseconds(study)) comparison.smaaMs = *smaa / 1000.0 * comparison.scale;
  return comparison;
}

std::string Milliseconds(const std::optional<double>& value) {
  return value ? FormatFixed(*value, 3) : "not run";
}

ReportTable SeedTable(const study::Study& study, const SeedComparison& comparison) {
  return {"Seed 001's PS4 timings at 1080p beside aasim's estimates on '" + study.gpu.name + "'" +
              (comparison.scale != 1.0 ? " (scaled by pixel count from this run's size)" : ""),
          {"technique", "seed 001, ms", "aasim estimate, ms"},
          {{"8x CRAA (craa-lut on 8S/8Z/1F)", FormatFixed(kSeedCraaMilliseconds, 2), Milliseconds(comparison.craaMs)},
           {"SMAA 1x (smaa, cheaper strategy, all dispatches)", FormatFixed(kSeedSmaaMilliseconds, 2),
            Milliseconds(comparison.smaaMs)}}};
}

BarChart QualityChart(const std::vector<EqaaStudyRow>& rows) {
  BarChart chart{"FLIP error per mode and resolve (lower is better)", "FLIP", {}, {"all pixels", "edge pixels"},
                 {{}, {}}, false};
  for (const EqaaStudyRow& row : rows) {
    chart.categories.push_back(Label(row));
    chart.values[0].push_back(std::isfinite(row.quality.flip) ? row.quality.flip : 0.0);
    chart.values[1].push_back(std::isfinite(row.quality.edgeFlip) ? row.quality.edgeFlip : 0.0);
  }
  return chart;
}

BarChart BytesChart(const std::vector<EqaaStudyRow>& rows) {
  BarChart chart{"Bytes per pixel: the colour block's writes (model) and the resolve's reads", "B/px", {},
                 {"FMASK written", "colour written", "FMASK read", "fragments read", "LUT read"},
                 {{}, {}, {}, {}, {}}, true};
  for (const EqaaStudyRow& row : rows) {
    chart.categories.push_back(Label(row));
    const std::uint64_t values[] = {row.written.fmaskWritten, row.written.colourWritten, row.fmaskBytesRead,
                                    row.fragmentBytesRead, row.tableBytesRead};
    for (std::size_t i = 0; i < std::size(values); ++i) chart.values[i].push_back(PerPixel(values[i], row.pixels));
  }
  return chart;
}

}  // namespace

ReportSection EqaaStudySection(const study::Study& study) {
  const std::vector<EqaaStudyRow> rows = study::EqaaStudyRows(study);
  ReportSection section{"EQAA study: modes and resolves", {}, {}, {}, {}};
  section.paragraphs = {
      "Every mode's surface under every resolve that reads it, all run as dispatches on the machine: box (the "
      "frame's own: known samples averaged, UNKNOWN dropped), fetch (every sample fetched, UNKNOWN reading fragment "
      "0), craa-simple and craa-lut (seed 001's coverage reconstruction of 1F surfaces from the neighbours' "
      "fragments; docs/craa.md). Quality against the ground truth; bytes per pixel the colour block wrote while "
      "drawing (a model from its counters: an FMASK read-modify-write per pixel update, 4 bytes per accepted "
      "fragment) and the resolve read (counted by its views); UNKNOWN samples per pixel at the end of the frame by "
      "cause; fragment evictions; the resolve's waves, active lanes and estimated time.",
      "Times are estimates of the timing model (docs/timing-model.md), not measurements."};
  ReportTable table{"Modes and resolves",
                    {"mode", "policy", "resolve", "PSNR", "SSIM", "FLIP", "edge FLIP", "CB FMASK B/px",
                     "CB colour B/px", "FMASK read B/px", "fragments read B/px", "LUT read B/px", "UNKNOWN evicted/px",
                     "UNKNOWN untestable/px", "UNKNOWN initial/px", "evictions", "resolve waves", "active %",
                     "estimated µs"},
                    {}};
  for (const EqaaStudyRow& row : rows) table.rows.push_back(TableRow(row));
  section.tables.push_back(std::move(table));
  section.tables.push_back(SeedTable(study, CompareWithSeed(study, rows)));
  if (!rows.empty()) {
    section.charts.push_back(QualityChart(rows));
    section.charts.push_back(BytesChart(rows));
  }
  return section;
}

nlohmann::ordered_json EqaaStudyJson(const study::Study& study) {
  const std::vector<EqaaStudyRow> rows = study::EqaaStudyRows(study);
  nlohmann::ordered_json entries = nlohmann::ordered_json::array();
  for (const EqaaStudyRow& row : rows) {
    entries.push_back({{"mode", row.mode},
                       {"policy", row.policy},
                       {"resolve", row.resolve},
                       {"quality", QualityJson(row.quality)},
                       {"pixels", row.pixels},
                       {"colour_block_bytes_model",
                        {{"fmask_read", row.written.fmaskRead},
                         {"fmask_written", row.written.fmaskWritten},
                         {"colour_written", row.written.colourWritten}}},
                       {"resolve_bytes_read",
                        {{"fmask", row.fmaskBytesRead}, {"fragments", row.fragmentBytesRead}, {"tables", row.tableBytesRead}}},
                       {"unknown_samples",
                        {{"eviction", row.unknown.eviction}, {"untestable", row.unknown.untestable}, {"initial", row.unknown.initial}}},
                       {"evictions", row.evictions},
                       {"resolve_waves", row.resolveWaves},
                       {"resolve_lanes_active", row.resolveLanesActive},
                       {"resolve_lanes_launched", row.resolveLanesLaunched},
                       {"resolve_estimated_us", row.resolveMicroseconds}});
  }
  const SeedComparison seed = CompareWithSeed(study, rows);
  return {{"rows", entries},
          {"seed_001_ps4_1080p_ms", {{"craa_8x", kSeedCraaMilliseconds}, {"smaa", kSeedSmaaMilliseconds}}},
          {"estimated_1080p_ms",
           {{"craa_lut_8s8z1f", seed.craaMs ? Number(*seed.craaMs) : nlohmann::ordered_json(nullptr)},
            {"smaa", seed.smaaMs ? Number(*seed.smaaMs) : nlohmann::ordered_json(nullptr)}}}};
}

}  // namespace cli
