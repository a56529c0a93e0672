// `aasim smaa-tables` (see smaa_tables_command.h).

#include "cli/smaa_tables_command.h"

#include <cstdint>
#include <cstdio>
#include <span>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/image_io.h"
#include "cli/output_dir.h"
#include "cli/text_io.h"
#include "fmask/fixtures.h"
#include "passes/smaa/area_tex.h"
#include "passes/smaa/search_tex.h"

namespace cli {
namespace {

using Json = nlohmann::ordered_json;
using passes::smaa::kAreaTexHeight, passes::smaa::kAreaTexWidth, passes::smaa::kSearchTexHeight,
    passes::smaa::kSearchTexWidth;

constexpr const char* kManifestName = "smaa_tables.json";
constexpr const char* kAreaPng = "smaa_area_tex.png";
constexpr const char* kAreaRaw = "smaa_area_tex.rg8";
constexpr const char* kSearchPng = "smaa_search_tex.png";
constexpr const char* kSearchRaw = "smaa_search_tex.r8";

// RG8 -> RGB8 with blue 0: PNG has no two-channel colour type (grey + alpha would hide G).
std::vector<std::uint8_t> RgToRgb(std::span<const std::uint8_t> rg) {
  std::vector<std::uint8_t> rgb;
  rgb.reserve(rg.size() / 2 * 3);
  for (std::size_t i = 0; i + 1 < rg.size(); i += 2) rgb.insert(rgb.end(), {rg[i], rg[i + 1], 0});
  return rgb;
}

std::string Hex64(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(value));
  return text;
}

Json TableRecord(std::string_view raw, std::string_view png, std::string_view format, int width, int height,
                 std::span<const std::uint8_t> bytes) {
  return {{"raw", raw},     {"png", png},           {"format", format},
          {"width", width}, {"height", height},     {"bytes", bytes.size()},
          {"fnv1a64", Hex64(fmask::Fnv1a64(bytes))}};
}

}  // namespace

CLI::App* AddSmaaTablesCommand(CLI::App& app, SmaaTablesCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "smaa-tables",
      "Write SMAA's AreaTex and SearchTex as this build generates them: PNG previews and raw RG8 / R8 bytes, "
      "row-major from the top row (docs/smaa-tables.md)");
  command->add_option("--out", options.out, "Output directory (created if missing)")->required()->type_name("DIR");
  return command;
}

void RunSmaaTablesCommand(const SmaaTablesCommandOptions& options, std::ostream& summary) {
  const std::span<const std::uint8_t> area = passes::smaa::AreaTexBytes();
  const std::span<const std::uint8_t> search = passes::smaa::SearchTexBytes();
  OutputDir dir = OpenOutOption(options.out);
  WritePng(dir.Stage(kAreaPng), kAreaTexWidth, kAreaTexHeight, 3, RgToRgb(area));
  WriteBytes(dir.Stage(kAreaRaw), area);
  WritePng(dir.Stage(kSearchPng), kSearchTexWidth, kSearchTexHeight, 1, search);
  WriteBytes(dir.Stage(kSearchRaw), search);
  const Json manifest = {
      {"schema", kSmaaTablesSchema},
      {"version", kSmaaTablesVersion},
      {"tables",
       {{"area", TableRecord(kAreaRaw, kAreaPng, "RG8", kAreaTexWidth, kAreaTexHeight, area)},
        {"search", TableRecord(kSearchRaw, kSearchPng, "R8", kSearchTexWidth, kSearchTexHeight, search)}}},
  };
  // Staged last, so it is renamed into place after every file it lists.
  WriteJson(dir.Stage(kManifestName), manifest);
  dir.Commit(kManifestName);
  summary << "wrote SMAA AreaTex " << kAreaTexWidth << "x" << kAreaTexHeight << " RG8 and SearchTex "
          << kSearchTexWidth << "x" << kSearchTexHeight << " R8 to " << dir.Path().string() << "\n";
}

}  // namespace cli
