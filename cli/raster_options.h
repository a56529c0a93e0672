#pragma once
// The options of `aasim raster`: one registry (name, default, legal range, help) from which
// CLI11 builds --help and checks single values, plus the cross-option checks CLI11 cannot
// express. Every rule runs before any work; violations are CLI::ValidationError (exit 2).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "cli/cli11_fwd.h"
#include "fmask/eqaa_surface.h"
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
  // The colour block runs when fragments > 0 (--fragments); the rest only matter then.
  int fragments = 0;
  std::string policy = "hraa";
  std::string fmaskInit = "cleared";
  std::vector<std::string> trace;          // "X,Y" as given
  std::vector<fmask::TracedPixel> traced;  // parsed from `trace` by ResolveRasterOptions

  fmask::EqaaConfig Eqaa() const { return {samples, depthSamples, fragments}; }
};

// Registers the `raster` subcommand on `app`, bound to `options`.
CLI::App* AddRasterCommand(CLI::App& app, RasterCommandOptions& options);

// Fills defaults that depend on other options and checks the rules between options.
void ResolveRasterOptions(RasterCommandOptions& options);

// Bytes held at once: the depth surface (S plane indices, Z float anchors and a stencil byte
// per pixel), one layer of quads, the ownership buffers and the output images; with
// fragments > 0 also the EQAA surface (FMASK element, F slots, S causes) and its images. Plus,
// per image column, the EXR writers' buffers (OpenEXR's 16-row ZIP chunk and compressor, and
// samples.exr's 32-row strip of 2S channels), which dominate for wide, short images.
std::uint64_t EstimateRasterBytes(int width, int height, int samples, int depthSamples,
                                  int fragments);

raster::CullMode CullModeByName(std::string_view name);
raster::CompareFunc DepthFuncByName(std::string_view name);
fmask::InitialState FmaskInitByName(std::string_view name);

}  // namespace cli
