#pragma once
// The machine's per-dispatch reports as outputs: versioned JSON (aasim.dispatches), one CSV row
// per dispatch, the aligned summary table and per-tile lane-utilization heat maps (EXR + PNG).
// Every counter name comes from sim's and raster's field tables, so no output can drift from
// the counters; formats in docs/cli.md "aasim frame".

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/output_dir.h"
#include "sim/dispatch.h"
#include "study/dispatch_log.h"

namespace cli {

inline constexpr const char* kDispatchesSchema = "aasim.dispatches";
inline constexpr int kDispatchesVersion = 1;

// Dispatch records (study/dispatch_log.h) carry the frame, pass and strategy each dispatch ran
// under: the pass dispatches of two strategies share names, so every output carries the
// strategy; when records name their frame (a run that renders several), JSON gains a "frame" key
// and CSV a leading "frame" column.

// {"schema", "version", "gpu", "timing_model", "configuration", "dispatches": [...]};
// `configuration` is echoed as given (the run's resolved options).
nlohmann::ordered_json DispatchReportsJson(std::span<const study::DispatchRecord> records,
                                           const sim::GpuConfig& gpu,
                                           const nlohmann::ordered_json& configuration);

// Header row, then one row per dispatch; "\n" line ends.
std::string DispatchReportsCsv(std::span<const study::DispatchRecord> records);
// One CSV field: quoted, with inner quotes doubled, when it holds a comma, quote or line break.
std::string CsvField(std::string_view text);

// The table on stdout: lanes by kind, DRAM traffic, occupancy and the estimated time per
// dispatch, under a line naming the GPU configuration the estimates come from.
void PrintDispatchSummary(std::ostream& out, std::span<const study::DispatchRecord> records,
                          const sim::GpuConfig& gpu);

// The summary table's cells: a header row, then one row per dispatch ("name [strategy]").
std::vector<std::vector<std::string>> DispatchSummaryRows(std::span<const study::DispatchRecord> records);

// The comparison's cells (PrintDispatchComparison): a header row with the two labels, then one
// row per quantity. std::invalid_argument when a pass lacks `name`.
std::vector<std::vector<std::string>> DispatchComparisonRows(
    std::string_view name, std::string_view leftLabel, std::span<const study::DispatchRecord> leftPass,
    std::string_view rightLabel, std::span<const study::DispatchRecord> rightPass);

// One dispatch, `name`, run under two strategies, side by side: waves, active and launched
// lanes, utilisation %, DRAM bytes, estimated µs, and the estimated µs of each whole pass
// (every dispatch in `leftPass` / `rightPass`). std::invalid_argument when a pass lacks `name`.
void PrintDispatchComparison(std::ostream& out, std::string_view name, std::string_view leftLabel,
                             std::span<const study::DispatchRecord> leftPass,
                             std::string_view rightLabel,
                             std::span<const study::DispatchRecord> rightPass);

// Wall time of simulating every dispatch on this machine, as the summary's last lines state it.
void PrintHostTime(std::ostream& out, std::span<const study::DispatchRecord> records, int threads);

// The utilization preview: 4x4 pixels per 8x8 tile, dark blue (0) to yellow (1), dark grey where
// no lane was launched. Throws std::invalid_argument for an empty map.
struct HeatMapImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};
HeatMapImage HeatMapPreview(const sim::TileHeatMap& heat);

// One pixel per 8x8 tile. EXR channels active, helper, dead, launched (lane counts) and
// utilization (active / launched; 0 where launched is 0). The PNG shows utilization at 4x4
// pixels per tile. Throws OutputError naming the path; std::invalid_argument for an empty map.
void WriteHeatMap(const sim::TileHeatMap& heat, const std::filesystem::path& exr,
                  const std::filesystem::path& png);

// "<index>-<name>[-<strategy>]" with every character outside [A-Za-z0-9._-] replaced by '-':
// a file name per dispatch, unique through the index into dispatches.json ("0-frame-material").
std::string HeatMapStem(std::size_t index, std::string_view name, std::string_view strategy);

// The dispatch reports of a run as `aasim frame` writes them, staged in `dir`: a heat map per
// dispatch that has one (heat/STEM.exr and .png), dispatches.json with `configuration`, and
// dispatches.csv. Throws OutputError naming the file.
void WriteDispatchReports(OutputDir& dir, std::span<const study::DispatchRecord> records, const sim::GpuConfig& gpu,
                          const nlohmann::ordered_json& configuration);

}  // namespace cli
