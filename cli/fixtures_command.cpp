// `aasim fixtures` (see fixtures_command.h): the fixture set on disk, its manifest, and the
// verifier that re-derives every listed fixture and compares it byte for byte.

#include "cli/fixtures_command.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "cli/fixture_manifest.h"
#include "cli/image_io.h"
#include "cli/output_dir.h"
#include "cli/output_error.h"
#include "cli/text_io.h"
#include "fmask/fixtures.h"
#include "raster/json_input.h"

namespace cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Bytes = std::vector<std::uint8_t>;

constexpr const char* kManifestName = "manifest.json";
constexpr const char* kPreviewName = "preview.png";
constexpr int kPreviewScale = 8;               // preview pixels per fixture pixel
constexpr std::uint8_t kUnknownPreview = 255;  // UNKNOWN samples show white (palette has none)

struct NamedBytes {
  std::string_view name;
  std::span<const std::uint8_t> bytes;
};

std::array<NamedBytes, 5> BinaryFiles(const fmask::FixtureData& data) {
  return {{{"fmask.bin", data.fmask},
           {"colours.bin", data.colours},
           {"depth.bin", data.depth},
           {"decoded.bin", data.decoded},
           {"resolve.bin", data.resolve}}};
}

// --- Preview: box resolve on the left, every sample's decoded colour on the right. ---

struct Image {
  int width = 0, height = 0;
  Bytes rgb;
  void Fill(int x0, int y0, int w, int h, const std::array<std::uint8_t, 3>& colour) {
    for (int y = y0; y < y0 + h; ++y) {
      for (int x = x0; x < x0 + w; ++x) {
        std::copy(colour.begin(), colour.end(), rgb.begin() + 3 * (y * width + x));
      }
    }
  }
};

float ReadFloat(std::span<const std::uint8_t> bytes, std::size_t offset) {
  std::uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) bits |= std::uint32_t{bytes[offset + i]} << (8 * i);
  return std::bit_cast<float>(bits);
}

fmask::FmaskElement ReadElement(const fmask::FixtureData& data, int pixel) {
  const int elementBytes = data.layout.ElementBits() / 8;
  fmask::FmaskElement element = 0;
  for (int i = 0; i < elementBytes; ++i) {
    element |= fmask::FmaskElement{data.fmask[pixel * elementBytes + i]} << (8 * i);
  }
  return element;
}

// Sample cells per pixel: 2 -> 2x1, 4 -> 2x2, 8 -> 4x2, 16 -> 4x4.
int SampleColumns(int samples) { return samples <= 4 ? 2 : 4; }

// The right panel's cell grid of pixel (x, y): each sample's decoded colour, UNKNOWN white.
void DrawSamples(Image& image, const fmask::FixtureData& data, int x, int y) {
  const int samples = data.layout.CoverageSamples(), pixel = y * data.width + x;
  const int columns = SampleColumns(samples), rows = samples / columns;
  const int cellW = kPreviewScale / columns, cellH = kPreviewScale / rows;
  const fmask::FmaskElement element = ReadElement(data, pixel);
  for (int s = 0; s < samples; ++s) {
    std::array<std::uint8_t, 3> colour{kUnknownPreview, kUnknownPreview, kUnknownPreview};
    const bool unknown =
        data.layout.IsEqaa() && data.layout.Code(element, s) == data.layout.UnknownCode();
    for (int c = 0; c < 3 && !unknown; ++c) {
      colour[c] = EncodeSrgb8(data.decoded[4 * (pixel * samples + s) + c] / 255.0f);
    }
    image.Fill((data.width + x) * kPreviewScale + (s % columns) * cellW,
               y * kPreviewScale + (s / columns) * cellH, cellW, cellH, colour);
  }
}

Image PreviewImage(const fmask::FixtureData& data) {
  Image image{2 * data.width * kPreviewScale, data.height * kPreviewScale, {}};
  image.rgb.assign(static_cast<std::size_t>(image.width) * image.height * 3, 0);
  for (int y = 0; y < data.height; ++y) {
    for (int x = 0; x < data.width; ++x) {
      std::array<std::uint8_t, 3> resolved{};
      for (int c = 0; c < 3; ++c) {
        resolved[c] = EncodeSrgb8(ReadFloat(data.resolve, 16 * (y * data.width + x) + 4 * c));
      }
      image.Fill(x * kPreviewScale, y * kPreviewScale, kPreviewScale, kPreviewScale, resolved);
      DrawSamples(image, data, x, y);
    }
  }
  return image;
}

// --- Manifest ---

std::string Hex64(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(value));
  return text;
}

Json FileRecord(std::string_view name, std::span<const std::uint8_t> bytes) {
  return {{"name", name}, {"bytes", bytes.size()}, {"fnv1a64", Hex64(fmask::Fnv1a64(bytes))}};
}

Json PatternJson(const raster::SamplePattern& pattern) {
  Json pixels = Json::array();
  for (int p = 0; p < raster::kQuadPixels; ++p) {
    Json offsets = Json::array();
    for (int s = 0; s < pattern.Count(); ++s) {
      offsets.push_back({pattern.Offset(p, s).x, pattern.Offset(p, s).y});
    }
    pixels.push_back(std::move(offsets));
  }
  return {{"name", pattern.Name()}, {"offsets_sixteenths", std::move(pixels)}};
}

Json FmaskJson(const fmask::FmaskLayout& layout) {
  return {{"format", layout.FormatName()},
          {"bits_per_sample", layout.BitsPerSample()},
          {"element_bits", layout.ElementBits()},
          {"element_bytes", layout.ElementBits() / 8},
          {"unknown_code", layout.IsEqaa() ? Json(layout.UnknownCode()) : Json(nullptr)}};
}

Json PolicyJson(const fmask::ArbitrationPolicy& policy) {
  using fmask::ArbitrationScope, fmask::CountBasis, fmask::DiscardOrder, fmask::TieBreak;
  return {
      {"name", policy.name},
      {"discard_order", policy.order == DiscardOrder::EvictThenDiscard ? "evict-then-discard"
                                                                       : "discard-then-evict"},
      {"tie_break",
       policy.tieBreak == TieBreak::KeepLowerIndex ? "keep-lower-index" : "keep-higher-index"},
      {"count_basis",
       policy.countBasis == CountBasis::AfterIncoming ? "after-incoming" : "before-incoming"},
      {"zplane_rescue", policy.zPlaneRescue},
      {"scope", policy.scope == ArbitrationScope::Pixel ? "pixel" : "quad"},
  };
}

Json TrianglesJson(const fmask::FixtureCase& fixtureCase) {
  Json triangles = Json::array();
  for (const fmask::FixtureTriangle& triangle : fixtureCase.triangles) {
    Json vertices = Json::array();
    for (const fmask::FixtureVertex& v : triangle.vertices) vertices.push_back({v.x, v.y, v.z});
    triangles.push_back({{"vertices", std::move(vertices)}, {"colour", triangle.colour}});
  }
  return triangles;
}

// Everything about a fixture except its file records; all of it is re-derivable.
Json FixtureJson(const fmask::FixtureData& data) {
  const fmask::FixtureCase& fixtureCase = fmask::CanonicalCase(data.spec.caseName);
  return {
      {"name", fmask::FixtureName(data.spec)},
      {"case", fixtureCase.name},
      {"exercises", fixtureCase.exercises},
      {"samples", data.spec.config.coverageSamples},
      {"depth_samples", data.spec.config.depthSamples},
      {"fragments", data.spec.config.fragments},
      {"width", data.width},
      {"height", data.height},
      {"pattern", PatternJson(data.pattern)},
      {"fmask", FmaskJson(data.layout)},
      {"policy", PolicyJson(fmask::PolicyByName(data.spec.policy))},
      {"raster",
       {{"initial_state", "cleared"},
        {"clear_colour", fmask::kFixtureClearColour},
        {"clear_depth", fmask::kFixtureClearDepth},
        {"depth_func", "less"},
        {"cull", "none"},
        {"max_zplanes", fmask::kFixtureMaxZPlanes},
        {"hiz", fmask::FixtureDrawState().depth.hiZEnable}}},
      {"triangles", TrianglesJson(fixtureCase)},
  };
}

// --- Files ---

std::optional<Bytes> ReadBytes(const fs::path& path) {
  // Only regular files: a FIFO put in a fixture's place would block the verifier forever.
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return std::nullopt;
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;
  return Bytes(std::istreambuf_iterator<char>(file), {});
}

OutputDir OpenOutputDir(const std::string& out) {
  try {
    return OutputDir(out);
  } catch (const OutputError& error) {
    throw OutputError("--out " + std::string(error.what()));
  }
}

std::uint64_t StageFixture(OutputDir& dir, const fmask::FixtureData& data, Json& entry) {
  const std::string name = fmask::FixtureName(data.spec);
  Json files = Json::array();
  std::uint64_t total = 0;
  for (const NamedBytes& file : BinaryFiles(data)) {
    WriteBytes(dir.Stage(name + "/" + std::string(file.name)), file.bytes);
    files.push_back(FileRecord(file.name, file.bytes));
    total += file.bytes.size();
  }
  const Image preview = PreviewImage(data);
  const fs::path previewPath = dir.Stage(name + "/" + kPreviewName);
  WritePng(previewPath, preview.width, preview.height, 3, preview.rgb);
  const std::optional<Bytes> png = ReadBytes(previewPath);
  if (!png) throw OutputError(previewPath.string() + ": cannot read back");
  files.push_back(FileRecord(kPreviewName, *png));
  entry["files"] = std::move(files);
  return total + png->size();
}

// One fixture per line: small, and still greppable and diffable.
std::string ManifestText(const Json& fixtures) {
  std::string text = "{\"schema\": " + Json(kFixturesSchema).dump() +
                     ", \"version\": " + std::to_string(kFixturesVersion) +
                     ", \"checksum\": \"fnv1a64\", \"fixtures\": [\n";
  for (std::size_t i = 0; i < fixtures.size(); ++i) {
    text += fixtures[i].dump() + (i + 1 < fixtures.size() ? ",\n" : "\n");
  }
  return text + "]}\n";
}

void WriteFixtureSet(const std::string& out, std::ostream& summary) {
  const auto start = std::chrono::steady_clock::now();
  OutputDir dir = OpenOutputDir(out);
  Json fixtures = Json::array();
  std::uint64_t totalBytes = 0;
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    const fmask::FixtureData data = fmask::DeriveFixture(spec);
    Json entry = FixtureJson(data);
    totalBytes += StageFixture(dir, data, entry);
    fixtures.push_back(std::move(entry));
  }
  const std::size_t count = fixtures.size();
  // Staged last, so it is renamed into place after every file it lists.
  const std::string manifestText = ManifestText(fixtures);
  WriteBytes(dir.Stage(kManifestName),
             {reinterpret_cast<const std::uint8_t*>(manifestText.data()), manifestText.size()});
  dir.Commit(kManifestName);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char timing[32];
  std::snprintf(timing, sizeof(timing), "%.2f", seconds);
  summary << "wrote " << count << " fixtures (" << totalBytes << " bytes) to "
          << dir.Path().string() << " in " << timing << " s\n";
}

// --- Verification ---

[[noreturn]] void Fail(const std::string& fixture, const std::string& problem) {
  throw std::runtime_error("fixture " + fixture + ": " + problem);
}

Json ReadManifest(const fs::path& dir) {
  const fs::path path = dir / kManifestName;
  try {
    return ParseFixtureManifest(raster::ReadJsonFile(path), path.string());
  } catch (const raster::JsonTextError& error) {
    throw std::runtime_error(path.string() + ": " + error.what() + " (not a fixture set?)");
  }
}


template <typename T>
T Field(const Json& object, const char* key, const std::string& fixture) {
  if (!object.is_object() || !object.contains(key)) {
    Fail(fixture, std::string("manifest has no '") + key + "'");
  }
  try {
    return object[key].get<T>();
  } catch (const Json::exception&) {
    Fail(fixture, std::string("manifest field '") + key + "' has the wrong type");
  }
}

fmask::FixtureSpec SpecOf(const Json& entry, const std::string& fixture) {
  return {{Field<int>(entry, "samples", fixture), Field<int>(entry, "depth_samples", fixture),
           Field<int>(entry, "fragments", fixture)},
          Field<std::string>(Field<Json>(entry, "pattern", fixture), "name", fixture),
          Field<std::string>(entry, "case", fixture),
          Field<std::string>(Field<Json>(entry, "policy", fixture), "name", fixture)};
}

// A record is exactly {name, bytes, fnv1a64}: a checksum under another name would otherwise be
// ignored and the file go unchecked.
void CheckRecordKeys(const Json& record, const std::string& fixture) {
  if (!record.is_object()) Fail(fixture, "a 'files' record is not an object");
  for (const auto& item : record.items()) {
    if (item.key() != "name" && item.key() != "bytes" && item.key() != "fnv1a64") {
      Fail(fixture, "a 'files' record has the unknown key " + raster::JsonExcerpt(Json(item.key())));
    }
  }
}

void CheckRecord(const Json& files, std::string_view name, std::span<const std::uint8_t> actual,
                 const std::string& fixture) {
  const std::string file(name);
  for (const Json& record : files) {
    CheckRecordKeys(record, fixture);
    if (record.value("name", Json()) != file) continue;
    if (record.value("bytes", Json()) != actual.size()) {
      Fail(fixture, file + " has " + std::to_string(actual.size()) + " bytes, the manifest says " +
                        raster::JsonExcerpt(record.value("bytes", Json())));
    }
    if (record.value("fnv1a64", Json()) != Hex64(fmask::Fnv1a64(actual))) {
      Fail(fixture, file + " checksum " + Hex64(fmask::Fnv1a64(actual)) +
                        " does not match the manifest's " + raster::JsonExcerpt(record.value("fnv1a64", Json())));
    }
    return;
  }
  Fail(fixture, "the manifest has no record of " + file);
}

Bytes ReadFixtureFile(const fs::path& dir, const std::string& fixture, std::string_view name) {
  const fs::path path = dir / fixture / name;
  std::optional<Bytes> bytes = ReadBytes(path);
  if (!bytes) Fail(fixture, std::string(name) + " is missing (" + path.string() + ")");
  return std::move(*bytes);
}

void CompareBytes(std::span<const std::uint8_t> actual, std::span<const std::uint8_t> expected,
                  std::string_view name, const std::string& fixture) {
  const auto [a, e] = std::mismatch(actual.begin(), actual.end(), expected.begin(), expected.end());
  if (a == actual.end() && e == expected.end()) return;
  if (actual.size() != expected.size()) {
    Fail(fixture, std::string(name) + " has " + std::to_string(actual.size()) +
                      " bytes, re-derived data has " + std::to_string(expected.size()));
  }
  Fail(fixture, std::string(name) + " differs from re-derived data at byte " +
                    std::to_string(a - actual.begin()));
}

void ComparePreview(std::span<const std::uint8_t> png, const Image& expected,
                    const std::string& fixture) {
  int width = 0, height = 0, channels = 0;
  const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &width, &height, &channels,
                            3),
      stbi_image_free);
  if (!pixels) Fail(fixture, std::string(kPreviewName) + " cannot be decoded as PNG");
  if (width != expected.width || height != expected.height) {
    Fail(fixture, std::string(kPreviewName) + " is " + std::to_string(width) + "x" +
                      std::to_string(height) + ", re-derived image is " +
                      std::to_string(expected.width) + "x" + std::to_string(expected.height));
  }
  CompareBytes({pixels.get(), expected.rgb.size()}, expected.rgb, "preview.png pixel data",
               fixture);
}

void CompareFields(Json stored, Json expected, const std::string& fixture) {
  stored.erase("files");
  for (const auto& [key, value] : expected.items()) {
    if (!stored.contains(key) || stored[key] != value) {
      Fail(fixture, "manifest field '" + key + "' differs from re-derived value");
    }
  }
  for (const auto& item : stored.items()) {
    if (!expected.contains(item.key())) {
      Fail(fixture, "manifest field '" + item.key() + "' is unknown");
    }
  }
}

void VerifyFixture(const fs::path& dir, const Json& entry, std::size_t index) {
  const std::string fixture = Field<std::string>(entry, "name", "#" + std::to_string(index));
  const fmask::FixtureSpec spec = SpecOf(entry, fixture);
  const fmask::FixtureData data = [&] {
    try {
      return fmask::DeriveFixture(spec);
    } catch (const std::exception& error) {
      Fail(fixture, std::string("cannot re-derive: ") + error.what());
    }
  }();
  CompareFields(entry, FixtureJson(data), fixture);
  const Json files = Field<Json>(entry, "files", fixture);
  if (!files.is_array()) Fail(fixture, "manifest field 'files' is not a list");
  for (const NamedBytes& file : BinaryFiles(data)) {
    const Bytes actual = ReadFixtureFile(dir, fixture, file.name);
    CompareBytes(actual, file.bytes, file.name, fixture);
    CheckRecord(files, file.name, actual, fixture);
  }
  const Bytes png = ReadFixtureFile(dir, fixture, kPreviewName);
  CheckRecord(files, kPreviewName, png, fixture);
  ComparePreview(png, PreviewImage(data), fixture);
  if (files.size() != BinaryFiles(data).size() + 1)
    Fail(fixture, "the manifest lists unexpected files");
}

void VerifyFixtureSet(const fs::path& dir, std::ostream& summary) {
  const Json manifest = ReadManifest(dir);
  const Json& fixtures = manifest["fixtures"];
  for (std::size_t i = 0; i < fixtures.size(); ++i) VerifyFixture(dir, fixtures[i], i);
  summary << "verified " << fixtures.size() << " fixtures\n";
}

}  // namespace

CLI::App* AddFixturesCommand(CLI::App& app, FixturesCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "fixtures", "Write the canonical FMASK fixture set (docs/fixtures.md), or verify one");
  CLI::Option* out =
      command->add_option("--out", options.out, "Write the fixture set into DIR")->type_name("DIR");
  CLI::Option* verify =
      command->add_option("--verify", options.verify, "Re-derive the set in DIR and compare")
          ->type_name("DIR");
  out->excludes(verify);
  command->require_option(1);
  return command;
}

void RunFixturesCommand(const FixturesCommandOptions& options, std::ostream& summary) {
  if (options.verify.empty()) {
    WriteFixtureSet(options.out, summary);
  } else {
    VerifyFixtureSet(options.verify, summary);
  }
}

}  // namespace cli
