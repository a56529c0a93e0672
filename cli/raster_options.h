#pragma once
// The options of `aasim raster`: one registry (name, default, legal range, help) from which
// CLI11 builds --help and checks single values, plus the cross-option checks CLI11 cannot
// express. Every rule runs before any work; violations are CLI::ValidationError (exit 2).

#include <cstdint>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "raster/depth_stencil.h"
#include "raster/setup.h"

namespace cli {

struct RasterCommandOptions {
  std::string scene;  // "builtin:NAME" or a glTF path; default set by AddRasterCommand
  int width = 1920;
  int height = 1080;
  int samples = 8;
  int depthSamples = 0;  // 0 until ResolveRasterOptions: min(samples, kMaxDepthSamples)
  std::string pattern = "standard";
  int maxZPlanes = 4;
  std::string cull = "back";
  std::string depthFunc = "less";
  bool noHiZ = false;
  int threads = 0;  // default set by AddRasterCommand: every core
  std::string out = "out/raster";
};

// Refuse runs whose buffers would exceed this (see EstimateRasterBytes).
inline constexpr std::uint64_t kMaxRasterBytes = std::uint64_t{4} << 30;

// Registers the `raster` subcommand on `app`, bound to `options`.
CLI::App* AddRasterCommand(CLI::App& app, RasterCommandOptions& options);

// Fills defaults that depend on other options and checks the rules between options.
void ResolveRasterOptions(RasterCommandOptions& options);

// Bytes held at once: the depth surface (S plane indices, Z float anchors and a stencil byte
// per pixel), one layer of quads, the ownership buffers and the output images.
std::uint64_t EstimateRasterBytes(int width, int height, int samples, int depthSamples);

raster::CullMode CullModeByName(std::string_view name);
raster::CompareFunc DepthFuncByName(std::string_view name);

}  // namespace cli
