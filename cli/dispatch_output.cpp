// Per-dispatch reports as JSON, CSV, a table and heat maps (see dispatch_output.h).

#include "cli/dispatch_output.h"

#include "cli/number_format.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <vector>

#include <glm/vec3.hpp>

#include "cli/counters_json.h"
#include "cli/image_io.h"
#include "cli/text_io.h"

namespace cli {
namespace {

// The names below are this file's only copy of the report fields outside sim/: JSON, CSV and
// the table are generated from these tables.

struct KernelField {
  const char* name;
  int sim::KernelInfo::*member;
};
constexpr KernelField kKernelFields[] = {
    {"vgprs", &sim::KernelInfo::vgprs},
    {"sgprs", &sim::KernelInfo::sgprs},
    {"lds_bytes_per_group", &sim::KernelInfo::ldsBytesPerGroup},
};
// Named so: it is the kernel author's estimate, not a count.
constexpr const char* kValuEstimate = "valu_instructions_per_wave_estimate";

struct TrafficField {
  const char* name;
  std::uint64_t sim::ResourceTraffic::*member;
};
// What lanes asked for; the CSV sums these over a dispatch's resources.
constexpr TrafficField kRequestFields[] = {
    {"bytes_read", &sim::ResourceTraffic::bytesRead},
    {"bytes_written", &sim::ResourceTraffic::bytesWritten},
    {"fetches", &sim::ResourceTraffic::fetches},
    {"atomics", &sim::ResourceTraffic::atomics},
    {"stores_dropped_oob", &sim::ResourceTraffic::storesDroppedOob},
};
// Distinct 64-byte lines behind the requests.
constexpr TrafficField kLineFields[] = {
    {"lines_read", &sim::ResourceTraffic::linesRead},
    {"lines_written", &sim::ResourceTraffic::linesWritten},
};
constexpr const char* kDramBytes = "dram_bytes";

struct OccupancyField {
  const char* name;
  int sim::Occupancy::*member;
};
constexpr OccupancyField kOccupancyFields[] = {
    {"waves_per_simd", &sim::Occupancy::wavesPerSimd},
    {"max_waves_per_simd", &sim::Occupancy::maxWavesPerSimd},
    {"by_vgpr", &sim::Occupancy::byVgpr},
    {"by_sgpr", &sim::Occupancy::bySgpr},
    {"by_lds", &sim::Occupancy::byLds},
    {"by_groups", &sim::Occupancy::byGroups},
    {"waves_per_group", &sim::Occupancy::wavesPerGroup},
    {"vgprs_allocated", &sim::Occupancy::vgprsAllocated},
    {"sgprs_allocated", &sim::Occupancy::sgprsAllocated},
    {"lds_bytes_allocated", &sim::Occupancy::ldsBytesAllocated},
};
constexpr const char* kLimiter = "limiter";
// The CSV keeps one occupancy number per dispatch: RGP's "A" of "A/B".
constexpr const OccupancyField& kOccupancyHeadline = kOccupancyFields[0];

struct TimeField {
  const char* name;
  double sim::TimeEstimate::*member;
};
constexpr TimeField kTimeFields[] = {
    {"alu", &sim::TimeEstimate::aluMicroseconds},
    {"memory", &sim::TimeEstimate::memoryMicroseconds},
    {"launch", &sim::TimeEstimate::launchMicroseconds},
    {"raster", &sim::TimeEstimate::rasterMicroseconds},
    {"overhead", &sim::TimeEstimate::overheadMicroseconds},
    {"total", &sim::TimeEstimate::totalMicroseconds},
    {"total_valu_halved", &sim::TimeEstimate::totalValuHalvedMicroseconds},
    {"total_valu_doubled", &sim::TimeEstimate::totalValuDoubledMicroseconds},
};
constexpr const char* kBound = "bound";

bool AnyFrame(std::span<const study::DispatchRecord> records) {
  return std::any_of(records.begin(), records.end(), [](const study::DispatchRecord& r) { return !r.frame.empty(); });
}

bool AnySweepPoint(std::span<const study::DispatchRecord> records) {
  return std::any_of(records.begin(), records.end(), [](const study::DispatchRecord& r) { return !r.sweepPoint.empty(); });
}

nlohmann::ordered_json Vector3(const glm::ivec3& v) { return {v.x, v.y, v.z}; }

// Every key of a GPU file (sim/gpu_config.h's tables), so the block can be saved and read back
// with --gpu.
nlohmann::ordered_json GpuJson(const sim::GpuConfig& gpu) {
  nlohmann::ordered_json json = {{"name", gpu.name}, {"source", gpu.source}};
  for (const sim::GpuDoubleKey& key : sim::kGpuDoubleKeys) json[key.key] = gpu.*key.member;
  for (const sim::GpuIntKey& key : sim::kGpuIntKeys) json[key.key] = gpu.*key.member;
  return json;
}

nlohmann::ordered_json KernelJson(const sim::KernelInfo& kernel) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  for (const KernelField& field : kKernelFields) json[field.name] = kernel.*field.member;
  json[kValuEstimate] = kernel.valuInstructionsPerWave;
  json["valu_estimate_source"] = kernel.source;
  return json;
}

nlohmann::ordered_json LaneCountersJson(const sim::LaneCounters& lanes) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  for (const sim::LaneCounterField& field : sim::kLaneCounterFields) {
    json[field.name] = lanes.*field.member;
  }
  return json;
}

nlohmann::ordered_json HistogramsJson(const sim::LaneCounters& lanes) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  sim::ForEachLaneHistogram(
      lanes, [&](const char* name, const auto& histogram) { json[name] = histogram; });
  return json;
}

// Whatever counters the pass declared (sim::Dispatch::Counter), by name.
nlohmann::ordered_json PassCountersJson(const std::vector<sim::PassCounter>& counters) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  for (const sim::PassCounter& counter : counters) json[counter.name] = counter.value;
  return json;
}

nlohmann::ordered_json ResourceJson(const sim::ResourceTraffic& traffic) {
  nlohmann::ordered_json json = {{"name", traffic.name}, {"access", sim::AccessName(traffic.access)}};
  for (const TrafficField& field : kRequestFields) json[field.name] = traffic.*field.member;
  for (const TrafficField& field : kLineFields) json[field.name] = traffic.*field.member;
  json[kDramBytes] = traffic.DramBytes();
  return json;
}

nlohmann::ordered_json OccupancyJson(const sim::Occupancy& occupancy) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  for (const OccupancyField& field : kOccupancyFields) json[field.name] = occupancy.*field.member;
  json[kLimiter] = sim::LimiterName(occupancy.limiter);
  return json;
}

nlohmann::ordered_json TimeJson(const sim::TimeEstimate& time) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  for (const TimeField& field : kTimeFields) json[field.name] = time.*field.member;
  json[kBound] = time.bound;
  return json;
}

nlohmann::ordered_json DispatchJson(const study::DispatchRecord& record) {
  const sim::DispatchReport& report = record.report;
  const std::string& strategy = record.strategy;
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  if (!record.frame.empty()) json["frame"] = record.frame;
  if (!record.sweepPoint.empty()) json["sweep_point"] = record.sweepPoint;
  json.update(nlohmann::ordered_json{
      {"name", report.name},
      {"kind", sim::DispatchKindName(report.kind)},
      {"strategy",
       strategy.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(strategy)},
      {"pass", record.pass.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(record.pass)},
      {"kernel", KernelJson(report.kernel)},
      {"group_size", Vector3(report.groupSize)},
      {"group_count", Vector3(report.groupCount)},
      {"counters", LaneCountersJson(report.lanes)},
      {"histograms", HistogramsJson(report.lanes)},
      {"pass_counters", PassCountersJson(report.passCounters)},
      {"resources", nlohmann::ordered_json::array()},
      {"occupancy", OccupancyJson(report.occupancy)},
      {"time_estimate_us", TimeJson(report.time)},
  });
  for (const sim::ResourceTraffic& traffic : report.resources) {
    json["resources"].push_back(ResourceJson(traffic));
  }
  if (report.raster) json["raster"] = CountersJson(*report.raster);
  if (report.fragments) json["fragments"] = FragmentCountersJson(*report.fragments);
  json["host_ms"] = report.hostMilliseconds;
  return json;
}

// Shortest text that reads back as the same double.
std::string FormatDouble(double value) {
  char text[32];
  const std::to_chars_result result = std::to_chars(text, text + sizeof(text), value);
  return std::string(text, result.ptr);
}

// CSV columns of pass counters: every name any dispatch declared, in first-seen order; a
// dispatch without one leaves its cell empty.
constexpr const char* kPassCounterColumnPrefix = "pass_counters/";

std::vector<std::string> PassCounterNames(std::span<const study::DispatchRecord> records) {
  std::vector<std::string> names;
  for (const study::DispatchRecord& record : records) {
    for (const sim::PassCounter& counter : record.report.passCounters) {
      if (std::find(names.begin(), names.end(), counter.name) == names.end()) names.push_back(counter.name);
    }
  }
  return names;
}

std::vector<std::string> CsvHeader(bool withFrame, std::span<const std::string> passCounters,
                                   bool withSweepPoint = false) {
  std::vector<std::string> header;
  if (withFrame) header.emplace_back("frame");
  if (withSweepPoint) header.emplace_back("sweep_point");
  header.insert(header.end(), {"name", "kind", "strategy"});
  for (const sim::LaneCounterField& field : sim::kLaneCounterFields) {
    header.emplace_back(field.name);
  }
  for (const TrafficField& field : kRequestFields) header.emplace_back(field.name);
  header.emplace_back(kDramBytes);
  header.push_back(std::string("occupancy_") + kOccupancyHeadline.name);
  header.push_back(std::string("occupancy_") + kLimiter);
  for (const TimeField& field : kTimeFields) {
    header.push_back(std::string("estimate_") + field.name + "_us");
  }
  header.push_back(std::string("estimate_") + kBound);
  for (const std::string& name : passCounters) header.push_back(kPassCounterColumnPrefix + name);
  return header;
}

std::vector<std::string> CsvRow(const sim::DispatchReport& report, std::string_view strategy,
                                std::optional<std::string_view> frame, std::span<const std::string> passCounters,
                                std::optional<std::string_view> sweepPoint = std::nullopt) {
  std::vector<std::string> row;
  if (frame) row.emplace_back(*frame);
  if (sweepPoint) row.emplace_back(*sweepPoint);
  row.insert(row.end(), {report.name, std::string(sim::DispatchKindName(report.kind)), std::string(strategy)});
  for (const sim::LaneCounterField& field : sim::kLaneCounterFields) {
    row.push_back(std::to_string(report.lanes.*field.member));
  }
  for (const TrafficField& field : kRequestFields) {
    std::uint64_t sum = 0;
    for (const sim::ResourceTraffic& traffic : report.resources) sum += traffic.*field.member;
    row.push_back(std::to_string(sum));
  }
  row.push_back(std::to_string(report.DramBytes()));
  row.push_back(std::to_string(report.occupancy.*kOccupancyHeadline.member));
  row.emplace_back(sim::LimiterName(report.occupancy.limiter));
  for (const TimeField& field : kTimeFields) row.push_back(FormatDouble(report.time.*field.member));
  row.emplace_back(report.time.bound);
  for (const std::string& name : passCounters) {
    const auto found = std::find_if(report.passCounters.begin(), report.passCounters.end(),
                                    [&](const sim::PassCounter& counter) { return counter.name == name; });
    row.push_back(found == report.passCounters.end() ? std::string() : std::to_string(found->value));
  }
  return row;
}

void AppendCsvLine(std::string& csv, const std::vector<std::string>& fields) {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) csv += ',';
    csv += CsvField(fields[i]);
  }
  csv += '\n';
}

// --- The summary table ---

// Columns are padded by what a terminal shows, so UTF-8 continuation bytes (the 'µ' of
// "µs") do not count.
std::size_t DisplayWidth(std::string_view text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0u) != 0x80u;
  }));
}

struct Column {
  const char* heading;
  bool numeric;  // right-aligned
};

constexpr Column kSummaryColumns[] = {
    {"dispatch", false},        {"kind", false},          {"waves", true},
    {"lanes launched", true},   {"active %", true},       {"helper %", true},
    {"dead (stencil) %", true}, {"dead (empty) %", true}, {"DRAM MB", true},
    {"occupancy", false},       {"est. µs", true},
};

std::vector<std::string> SummaryRow(const sim::DispatchReport& report, std::string_view strategy) {
  const sim::LaneCounters& lanes = report.lanes;
  std::string label = report.name;
  if (!strategy.empty()) {
    label += " [";
    label += strategy;
    label += ']';
  }
  return {label,
          std::string(sim::DispatchKindName(report.kind)),
          std::to_string(lanes.waves),
          std::to_string(lanes.lanesLaunched),
          FormatPercent(lanes.lanesActive, lanes.lanesLaunched),
          FormatPercent(lanes.lanesHelper, lanes.lanesLaunched),
          FormatPercent(lanes.lanesDeadStencil, lanes.lanesLaunched),
          FormatPercent(lanes.lanesDeadEmpty, lanes.lanesLaunched),
          FormatFixed(double(report.DramBytes()) / 1e6, 2),
          std::to_string(report.occupancy.wavesPerSimd) + "/" +
              std::to_string(report.occupancy.maxWavesPerSimd) + " (" +
              std::string(sim::LimiterName(report.occupancy.limiter)) + ")",
          FormatFixed(report.time.totalMicroseconds, 1)};
}

// Columns padded to their widest cell, two spaces apart, right-aligned where flagged.
void PrintAlignedTable(std::ostream& out, const std::vector<std::vector<std::string>>& rows,
                       const std::vector<bool>& rightAligned, std::string_view indent = "") {
  std::vector<std::size_t> widths(rightAligned.size(), 0);
  for (const std::vector<std::string>& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      widths[c] = std::max(widths[c], DisplayWidth(row[c]));
    }
  }
  for (const std::vector<std::string>& row : rows) {
    std::string line(indent);
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string padding(widths[c] - DisplayWidth(row[c]), ' ');
      if (c > 0) line += "  ";
      line += rightAligned[c] ? padding + row[c] : row[c] + padding;
    }
    line.erase(line.find_last_not_of(' ') + 1);
    out << line << '\n';
  }
}

// A studied dispatch the pass did not launch (nothing to do: MiniEngine FXAA on a screen one
// pixel high) compares as an empty one: no waves, no lanes, no bytes, no time.
const sim::DispatchReport& FindDispatch(std::span<const study::DispatchRecord> pass, std::string_view name) {
  static const sim::DispatchReport kNotLaunched{};
  const auto found = std::find_if(pass.begin(), pass.end(),
                                  [&](const study::DispatchRecord& r) { return r.report.name == name; });
  return found == pass.end() ? kNotLaunched : found->report;
}

// How far the estimate moves when the kernel author's VALU count is off by 2x either way.
std::string ValuRange(const sim::TimeEstimate& time) {
  return FormatFixed(time.totalValuHalvedMicroseconds, 1) + " .. " + FormatFixed(time.totalValuDoubledMicroseconds, 1);
}

double EstimatedMicroseconds(std::span<const study::DispatchRecord> pass) {
  double total = 0.0;
  for (const study::DispatchRecord& record : pass) total += record.report.time.totalMicroseconds;
  return total;
}

// --- Heat maps ---

constexpr int kHeatPreviewScale = 4;
using Rgb8 = std::array<std::uint8_t, 3>;
// sRGB-encoded, and lerped in encoded values so equal utilization steps look like equal steps.
constexpr Rgb8 kNoLanes{50, 50, 50};           // dark grey
constexpr Rgb8 kUtilizationZero{20, 24, 120};  // dark blue
constexpr Rgb8 kUtilizationOne{255, 230, 0};   // yellow

Rgb8 HeatColour(float utilization) {
  if (utilization < 0.0f) return kNoLanes;
  const float t = std::min(utilization, 1.0f);
  Rgb8 colour{};
  for (std::size_t c = 0; c < colour.size(); ++c) {
    const float zero = kUtilizationZero[c], one = kUtilizationOne[c];
    colour[c] = static_cast<std::uint8_t>(std::lround(zero + t * (one - zero)));
  }
  return colour;
}

}  // namespace

nlohmann::ordered_json DispatchReportsJson(std::span<const study::DispatchRecord> records,
                                           const sim::GpuConfig& gpu,
                                           const nlohmann::ordered_json& configuration) {
  nlohmann::ordered_json json = {
      {"schema", kDispatchesSchema},
      {"version", kDispatchesVersion},
      {"gpu", GpuJson(gpu)},
      {"timing_model", "estimate: see docs/timing-model.md"},
      {"configuration", configuration},
      {"dispatches", nlohmann::ordered_json::array()},
  };
  for (const study::DispatchRecord& record : records) json["dispatches"].push_back(DispatchJson(record));
  return json;
}

std::string CsvField(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

std::string DispatchReportsCsv(std::span<const study::DispatchRecord> records) {
  const bool withFrame = AnyFrame(records), withSweepPoint = AnySweepPoint(records);
  const std::vector<std::string> passCounters = PassCounterNames(records);
  std::string csv;
  AppendCsvLine(csv, CsvHeader(withFrame, passCounters, withSweepPoint));
  for (const study::DispatchRecord& record : records) {
    const std::optional<std::string_view> frame =
        withFrame ? std::optional<std::string_view>(record.frame) : std::nullopt;
    const std::optional<std::string_view> sweepPoint =
        withSweepPoint ? std::optional<std::string_view>(record.sweepPoint) : std::nullopt;
    AppendCsvLine(csv, CsvRow(record.report, record.strategy, frame, passCounters, sweepPoint));
  }
  return csv;
}

std::vector<std::vector<std::string>> DispatchSummaryRows(std::span<const study::DispatchRecord> records) {
  std::vector<std::vector<std::string>> rows(1);
  for (const Column& column : kSummaryColumns) rows[0].emplace_back(column.heading);
  for (const study::DispatchRecord& record : records) rows.push_back(SummaryRow(record.report, record.strategy));
  return rows;
}

void PrintDispatchSummary(std::ostream& out, std::span<const study::DispatchRecord> records,
                          const sim::GpuConfig& gpu) {
  std::vector<bool> rightAligned;
  for (const Column& column : kSummaryColumns) rightAligned.push_back(column.numeric);
  out << "dispatches (est. µs: estimated from the GPU configuration '" << gpu.name
      << "', docs/timing-model.md; occupancy: theoretical waves per SIMD; lane shares: % of "
         "lanes launched)\n";
  PrintAlignedTable(out, DispatchSummaryRows(records), rightAligned);
}

std::vector<std::vector<std::string>> DispatchComparisonRows(
    std::string_view name, std::string_view leftLabel, std::span<const study::DispatchRecord> leftPass,
    std::string_view rightLabel, std::span<const study::DispatchRecord> rightPass) {
  const sim::DispatchReport& a = FindDispatch(leftPass, name);
  const sim::DispatchReport& b = FindDispatch(rightPass, name);
  return {
      {"", std::string(leftLabel), std::string(rightLabel)},
      {"waves", std::to_string(a.lanes.waves), std::to_string(b.lanes.waves)},
      {"active lanes", std::to_string(a.lanes.lanesActive), std::to_string(b.lanes.lanesActive)},
      {"launched lanes", std::to_string(a.lanes.lanesLaunched),
       std::to_string(b.lanes.lanesLaunched)},
      {"utilisation %", FormatPercent(a.lanes.lanesActive, a.lanes.lanesLaunched),
       FormatPercent(b.lanes.lanesActive, b.lanes.lanesLaunched)},
      {"DRAM bytes", std::to_string(a.DramBytes()), std::to_string(b.DramBytes())},
      {"estimated µs", FormatFixed(a.time.totalMicroseconds, 1),
       FormatFixed(b.time.totalMicroseconds, 1)},
      {"estimated µs, VALU count x0.5 .. x2", ValuRange(a.time), ValuRange(b.time)},
      {"estimated µs, whole pass", FormatFixed(EstimatedMicroseconds(leftPass), 1),
       FormatFixed(EstimatedMicroseconds(rightPass), 1)},
  };
}

void PrintDispatchComparison(std::ostream& out, std::string_view name, std::string_view leftLabel,
                             std::span<const study::DispatchRecord> leftPass,
                             std::string_view rightLabel,
                             std::span<const study::DispatchRecord> rightPass) {
  PrintAlignedTable(out, DispatchComparisonRows(name, leftLabel, leftPass, rightLabel, rightPass),
                    {false, true, true}, "  ");
}

HeatMapImage HeatMapPreview(const sim::TileHeatMap& heat) {
  if (heat.Empty()) throw std::invalid_argument("empty heat map");
  HeatMapImage image{heat.TilesX() * kHeatPreviewScale, heat.TilesY() * kHeatPreviewScale, {}};
  image.rgb.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
  for (int py = 0; py < image.height; ++py) {
    for (int px = 0; px < image.width; ++px) {
      const Rgb8 colour = HeatColour(heat.Utilization(px / kHeatPreviewScale, py / kHeatPreviewScale));
      const std::size_t at = (static_cast<std::size_t>(py) * static_cast<std::size_t>(image.width) +
                              static_cast<std::size_t>(px)) * 3;
      std::copy(colour.begin(), colour.end(), image.rgb.begin() + static_cast<std::ptrdiff_t>(at));
    }
  }
  return image;
}

void WriteHeatMap(const sim::TileHeatMap& heat, const std::filesystem::path& exr,
                  const std::filesystem::path& png) {
  if (heat.Empty()) throw std::invalid_argument(exr.string() + ": empty heat map");
  const int tilesX = heat.TilesX(), tilesY = heat.TilesY();
  const std::size_t tiles = static_cast<std::size_t>(tilesX) * static_cast<std::size_t>(tilesY);
  std::vector<float> active(tiles), helper(tiles), dead(tiles), launched(tiles), utilization(tiles);
  for (int ty = 0; ty < tilesY; ++ty) {
    for (int tx = 0; tx < tilesX; ++tx) {
      const std::size_t tile = static_cast<std::size_t>(ty) * static_cast<std::size_t>(tilesX) +
                               static_cast<std::size_t>(tx);
      active[tile] = static_cast<float>(heat.Active(tx, ty));
      helper[tile] = static_cast<float>(heat.Helper(tx, ty));
      dead[tile] = static_cast<float>(heat.Dead(tx, ty));
      launched[tile] = static_cast<float>(heat.Launched(tx, ty));
      utilization[tile] = std::max(heat.Utilization(tx, ty), 0.0f);
    }
  }
  const ExrChannel channels[] = {{"active", active},
                                 {"helper", helper},
                                 {"dead", dead},
                                 {"launched", launched},
                                 {"utilization", utilization}};
  WriteExr(exr, tilesX, tilesY, channels);
  const HeatMapImage preview = HeatMapPreview(heat);
  WritePng(png, preview.width, preview.height, 3, preview.rgb);
}

std::string HeatMapStem(std::size_t index, std::string_view name, std::string_view strategy) {
  // Appended piecewise: GCC 12 flags "-" + string with a false -Wrestrict.
  std::string stem = std::to_string(index);
  stem += '-';
  stem += name;
  if (!strategy.empty()) {
    stem += '-';
    stem += strategy;
  }
  for (char& c : stem) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == '_' || c == '-';
    if (!keep) c = '-';
  }
  return stem;
}

void PrintHostTime(std::ostream& out, std::span<const study::DispatchRecord> records, int threads) {
  double hostMs = 0.0;
  for (const study::DispatchRecord& record : records) hostMs += record.report.hostMilliseconds;
  out << "\nhost time  " << std::llround(hostMs) << " ms simulating the dispatches (" << threads
      << " threads; wall time of this program, not a GPU time)\n";
}

void WriteDispatchReports(OutputDir& dir, std::span<const study::DispatchRecord> records, const sim::GpuConfig& gpu,
                          const nlohmann::ordered_json& configuration) {
  for (std::size_t i = 0; i < records.size(); ++i) {
    const sim::DispatchReport& report = records[i].report;
    if (report.heat.Empty()) continue;
    const std::string stem = "heat/" + HeatMapStem(i, report.name, records[i].strategy);
    WriteHeatMap(report.heat, dir.Stage(stem + ".exr"), dir.Stage(stem + ".png"));
  }
  WriteJson(dir.Stage("dispatches.json"), DispatchReportsJson(records, gpu, configuration));
  WriteText(dir.Stage("dispatches.csv"), DispatchReportsCsv(records));
}

}  // namespace cli
