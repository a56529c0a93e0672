// Options shared by the subcommands (see common_options.h).

#include "cli/common_options.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <oneapi/tbb/info.h>

#include "raster/limits.h"
#include "raster/rasterizer.h"
#include "raster/sample_pattern.h"
#include "scenes/scene.h"

namespace cli {

std::string JoinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) joined += (joined.empty() ? "" : ", ") + name;
  return joined;
}

std::string FormatGiB(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f", static_cast<double>(bytes) / double(1u << 30));
  return text;
}

void AddViewportOptions(CLI::App& command, std::string& scene, int& width, int& height) {
  scene = "builtin:" + std::string(scenes::kDefaultSceneName);
  command
      .add_option("--scene", scene,
                  "Scene: a glTF 2.0 file (.gltf/.glb) or builtin:NAME with NAME one of " +
                      JoinNames(scenes::BuiltinSceneNames()))
      ->type_name("FILE|builtin:NAME")
      ->capture_default_str();
  command.add_option("--width", width, "Viewport width in pixels")
      ->check(CLI::Range(1, raster::kMaxDimension))
      ->capture_default_str();
  command.add_option("--height", height, "Viewport height in pixels")
      ->check(CLI::Range(1, raster::kMaxDimension))
      ->capture_default_str();
}

void AddPatternOption(CLI::App& command, std::string& pattern) {
  command
      .add_option("--pattern", pattern,
                  "Sample pattern: a JSON file (a path with '/' or ending in .json; format in "
                  "docs/sample-patterns.md) or a built-in: " +
                      JoinNames(raster::BuiltinPatternNames()))
      ->type_name("NAME|FILE")
      ->capture_default_str();
}

void AddFramesPerSecondOption(CLI::App& command, double& framesPerSecond) {
  command
      .add_option("--fps", framesPerSecond,
                  "Frame rate of the sequence: frame-rate-aware passes blend with alpha = exp(-dt / tau), dt = 1 / fps")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
}

void AddThreadsOption(CLI::App& command, int& threads) {
  threads = tbb::info::default_concurrency();
  command.add_option("--threads", threads, "Worker threads [default: all cores]")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
}

CLI::Validator SampleCountCheck() { return CLI::IsMember({1, 2, 4, 8, 16}); }
CLI::Validator DepthSampleCountCheck() { return CLI::IsMember({1, 2, 4, 8}); }
CLI::Validator FragmentCountCheck() { return CLI::IsMember({1, 2, 4, 8}); }

void CheckEqaaMode(const fmask::EqaaConfig& eqaa) {
  try {
    fmask::ValidateEqaaConfig(eqaa);
  } catch (const std::invalid_argument& error) {
    throw CLI::ValidationError(error.what());
  }
}

std::uint64_t SurfaceBytesPerPixel(int samples, int depthSamples, int fragments) {
  const std::uint64_t surface = samples + 4u * depthSamples + 1u;
  const std::uint64_t quads = sizeof(raster::QuadFragment) / raster::kQuadPixels;
  std::uint64_t perPixel = surface + quads;
  if (fragments > 0) {
    perPixel += sizeof(fmask::FmaskElement) +
                std::uint64_t(fragments) * sizeof(fmask::FragmentSlot) +
                std::uint64_t(samples) * sizeof(fmask::UnknownCause);
  }
  return perPixel;
}

namespace {

// "0064" -> "64", "-007" -> "-7"; an error for anything that is not a decimal integer.
std::string DecimalInteger(std::string text) {
  const std::size_t signLength = text.starts_with('+') || text.starts_with('-') ? 1 : 0;
  const bool decimal = text.size() > signLength &&
                       std::all_of(text.begin() + static_cast<std::ptrdiff_t>(signLength), text.end(),
                                   [](char c) { return c >= '0' && c <= '9'; });
  if (!decimal) throw CLI::ValidationError("'" + text + "' is not a decimal integer");
  const std::size_t firstNonZero = text.find_first_not_of('0', signLength);
  text.erase(signLength, (firstNonZero == std::string::npos ? text.size() - 1 : firstNonZero) - signLength);
  return text;
}

}  // namespace

void RequireDecimalIntegers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    // The type name carries the validators' descriptions after the type ("INT:INT in [1 - 16]").
    const std::string type = option->get_type_name();
    if (type.starts_with("INT") || type.starts_with("UINT")) {
      option->transform(CLI::Validator(
          [](std::string& text) {
            text = DecimalInteger(text);
            return std::string();
          },
          "", "decimal"));
    }
  }
  for (CLI::App* command : app.get_subcommands({})) RequireDecimalIntegers(*command);
}

}  // namespace cli
