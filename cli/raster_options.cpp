// Option registry and cross-option checks of `aasim raster` (see raster_options.h).

#include "cli/raster_options.h"

#include <algorithm>
#include <charconv>
#include <iterator>
#include <stdexcept>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/common_options.h"
#include "raster/limits.h"
#include "raster/rasterizer.h"

namespace cli {
namespace {

struct NamedCullMode {
  std::string_view name;
  raster::CullMode mode;
};
constexpr NamedCullMode kCullModes[] = {
    {"back", raster::CullMode::Back},
    {"front", raster::CullMode::Front},
    {"none", raster::CullMode::None},
};

struct NamedCompareFunc {
  std::string_view name;
  raster::CompareFunc func;
};
constexpr NamedCompareFunc kDepthFuncs[] = {
    {"less", raster::CompareFunc::Less},       {"lequal", raster::CompareFunc::LessEqual},
    {"greater", raster::CompareFunc::Greater}, {"gequal", raster::CompareFunc::GreaterEqual},
    {"equal", raster::CompareFunc::Equal},     {"notequal", raster::CompareFunc::NotEqual},
    {"always", raster::CompareFunc::Always},   {"never", raster::CompareFunc::Never},
};

struct NamedInitialState {
  std::string_view name;
  fmask::InitialState state;
};
constexpr NamedInitialState kFmaskInits[] = {
    {"cleared", fmask::InitialState::Cleared},
    {"expanded", fmask::InitialState::Expanded},
    {"unknown", fmask::InitialState::Unknown},
};

void AddSurfaceOptions(CLI::App& command, RasterCommandOptions& options) {
  command.add_option("--samples", options.samples, "Coverage samples per pixel S")
      ->check(SampleCountCheck())
      ->capture_default_str();
  command
      .add_option("--depth-samples", options.depthSamples,
                  "Anchored depth samples per pixel Z, at most S [default: min(S, 8)]")
      ->check(DepthSampleCountCheck());
  AddPatternOption(command, options.pattern);
  command
      .add_option("--max-zplanes", options.maxZPlanes,
                  "Z planes an 8x8 tile holds before it decompresses (0 = no plane compression)")
      ->check(CLI::Range(0, raster::kMaxZPlanesPerTile))
      ->capture_default_str();
}

void AddStateOptions(CLI::App& command, RasterCommandOptions& options) {
  command.add_option("--cull", options.cull, "Face culling (counter-clockwise = front)")
      ->check(CLI::IsMember(Names(kCullModes)))
      ->capture_default_str();
  command
      .add_option("--depth-func", options.depthFunc,
                  "Depth test: a sample passes when its depth FUNC the stored depth")
      ->check(CLI::IsMember(Names(kDepthFuncs)))
      ->capture_default_str();
  command.add_flag("--no-hiz", options.noHiZ, "Disable hi-Z tile rejection");
}

void AddRunOptions(CLI::App& command, RasterCommandOptions& options) {
  AddThreadsOption(command, options.threads);
  command
      .add_option("--out", options.out,
                  "Output directory for coverage.png, primitives.png, depth.exr, counters.json "
                  "and, with --fragments, eqaa.exr, resolve.png, fmask.png, trace.txt, "
                  "trace.json (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
}

// The colour block's options mean nothing without it, so each one needs --fragments.
void AddEqaaOptions(CLI::App& command, RasterCommandOptions& options) {
  CLI::Option* fragments =
      command
          .add_option("--fragments", options.fragments,
                      "Colour fragments per pixel F: also render into an EQAA surface "
                      "(S/Z/F must be a legal EQAA mode) and write its outputs [default: off]")
          ->check(FragmentCountCheck());
  command
      .add_option("--policy", options.policy,
                  "Fragment arbitration policy when all F slots are taken (docs/eqaa.md)")
      ->check(CLI::IsMember(fmask::PolicyNames()))
      ->needs(fragments)
      ->capture_default_str();
  command.add_option("--fmask-init", options.fmaskInit, "FMASK contents before the first draw")
      ->check(CLI::IsMember(Names(kFmaskInits)))
      ->needs(fragments)
      ->capture_default_str();
  command
      .add_option("--trace", options.trace,
                  "Record every colour-block update of pixel X,Y in trace.txt and trace.json "
                  "(repeatable)")
      ->type_name("X,Y")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->needs(fragments);
}

std::string SizeOptions(const RasterCommandOptions& options) {
  std::string text = "--width " + std::to_string(options.width) + " --height " +
                     std::to_string(options.height) + " --samples " +
                     std::to_string(options.samples) + " --depth-samples " +
                     std::to_string(options.depthSamples);
  if (options.fragments > 0) text += " --fragments " + std::to_string(options.fragments);
  return text;
}

void CheckMemory(const RasterCommandOptions& options) {
  const std::uint64_t bytes = EstimateRasterBytes(options.width, options.height, options.samples,
                                                  options.depthSamples, options.fragments);
  if (bytes > kMaxRunBytes) {
    throw CLI::ValidationError(
        SizeOptions(options) + ": needs about " + FormatGiB(bytes) + " GiB (" +
        (options.fragments > 0 ? "depth and EQAA surfaces" : "depth surface") +
        ", quads and images), over the " + FormatGiB(kMaxRunBytes) + " GiB limit");
  }
}

// OpenEXR's scan-line writer (ImfOutputFile.cpp, ImfZipCompressor.cpp, ImfZip.cpp) fills one ZIP
// chunk of 16 rows of every channel, and the compressor holds an output buffer of 1.01 times that
// plus a scratch copy: about 3 x 16 rows, 49 to cover the 1 % and the fixed slack. Per image
// column, for `channels` 32-bit channels.
std::uint64_t ExrWriterBytesPerRow(int channels) {
  constexpr std::uint64_t kRowsHeld = 49;
  return kRowsHeld * std::uint64_t(channels) * 4u;
}

// All of `text` as a decimal integer.
bool ParseWholeInt(std::string_view text, int& value) {
  const char* end = text.data() + text.size();
  const auto [parsedEnd, error] = std::from_chars(text.data(), end, value);
  return error == std::errc() && parsedEnd == end;
}

// "X,Y" with both integers inside the viewport.
fmask::TracedPixel ParseTracedPixel(const std::string& text, int width, int height) {
  fmask::TracedPixel pixel;
  const std::string_view view(text);
  const std::size_t comma = view.find(',');
  if (comma == std::string_view::npos || !ParseWholeInt(view.substr(0, comma), pixel.x) ||
      !ParseWholeInt(view.substr(comma + 1), pixel.y)) {
    throw CLI::ValidationError("--trace " + text + ": expected X,Y (integer pixel coordinates)");
  }
  if (pixel.x < 0 || pixel.x >= width || pixel.y < 0 || pixel.y >= height) {
    throw CLI::ValidationError("--trace " + text + ": outside the " + std::to_string(width) + "x" +
                               std::to_string(height) + " viewport");
  }
  return pixel;
}

void ResolveEqaaOptions(RasterCommandOptions& options) {
  CheckEqaaMode(options.Eqaa());
  // MSAA layouts (F == S) have no UNKNOWN code to start from.
  if (FmaskInitByName(options.fmaskInit) == fmask::InitialState::Unknown &&
      !fmask::FmaskLayout::For(options.samples, options.fragments).IsEqaa()) {
    throw CLI::ValidationError("--fmask-init unknown needs F < S: " +
                               fmask::EqaaName(options.Eqaa()) + " has no UNKNOWN code");
  }
  options.traced.clear();
  for (const std::string& text : options.trace) {
    options.traced.push_back(ParseTracedPixel(text, options.width, options.height));
  }
}

}  // namespace

CLI::App* AddRasterCommand(CLI::App& app, RasterCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "raster",
      "Rasterize a scene into an EQAA depth surface (and, with --fragments, its colour "
      "fragments and FMASK); write images and counters");
  // Scripts append overrides to a base command line, so a repeated option means its last value.
  command->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  AddViewportOptions(*command, options.scene, options.width, options.height);
  AddSurfaceOptions(*command, options);
  AddStateOptions(*command, options);
  AddRunOptions(*command, options);
  AddEqaaOptions(*command, options);
  return command;
}

std::uint64_t EstimateRasterBytes(int width, int height, int samples, int depthSamples,
                                  int fragments) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  const std::uint64_t ownership = sizeof(float) + sizeof(std::uint32_t) + 1u;
  const std::uint64_t images = 4u * (depthSamples + 2u) + 4u;  // EXR channels, two PNGs
  std::uint64_t perPixel =
      SurfaceBytesPerPixel(samples, depthSamples, fragments) + ownership + images;
  // depth.exr: Z anchors, Z and coverage; samples.exr: 2S UINT channels in strips.
  std::uint64_t rows = ExrWriterBytesPerRow(depthSamples + 2) +
                       ExrWriterBytesPerRow(2 * samples) +
                       std::uint64_t(raster::kBinSize) * 2u * samples * sizeof(std::uint32_t);
  // eqaa.exr: RGBA, S codes, fragments, unknown; resolve.png and fmask.png are RGB.
  if (fragments > 0) {
    perPixel += 4u * (samples + 6u) + 6u;
    rows += ExrWriterBytesPerRow(samples + 6);
  }
  return pixels * perPixel + std::uint64_t(width) * rows;
}

void ResolveRasterOptions(RasterCommandOptions& options) {
  if (options.depthSamples == 0) {
    options.depthSamples = std::min(options.samples, raster::kMaxDepthSamples);
  }
  if (options.depthSamples > options.samples) {
    throw CLI::ValidationError("--depth-samples " + std::to_string(options.depthSamples) +
                               " exceeds --samples " + std::to_string(options.samples) +
                               ": need S >= Z");
  }
  if (options.fragments > 0) ResolveEqaaOptions(options);
  CheckMemory(options);
}

raster::CullMode CullModeByName(std::string_view name) {
  const auto* found = std::find_if(std::begin(kCullModes), std::end(kCullModes),
                                   [&](const NamedCullMode& entry) { return entry.name == name; });
  if (found == std::end(kCullModes)) throw std::invalid_argument("unknown cull mode");
  return found->mode;
}

raster::CompareFunc DepthFuncByName(std::string_view name) {
  const auto* found =
      std::find_if(std::begin(kDepthFuncs), std::end(kDepthFuncs),
                   [&](const NamedCompareFunc& entry) { return entry.name == name; });
  if (found == std::end(kDepthFuncs)) throw std::invalid_argument("unknown depth function");
  return found->func;
}

fmask::InitialState FmaskInitByName(std::string_view name) {
  const auto* found =
      std::find_if(std::begin(kFmaskInits), std::end(kFmaskInits),
                   [&](const NamedInitialState& entry) { return entry.name == name; });
  if (found == std::end(kFmaskInits)) throw std::invalid_argument("unknown FMASK initial state");
  return found->state;
}

}  // namespace cli
