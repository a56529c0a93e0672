#pragma once
// `aasim raster`: scene -> clip space -> raster::Rasterize, then the output set (coverage.png,
// primitives.png, depth.exr, counters.json; formats in docs/cli.md) written all-or-nothing and
// a short summary.

#include <ostream>

#include "cli/raster_options.h"

namespace cli {

// `options` must have passed ResolveRasterOptions. Input and output problems (scene, pattern,
// --out) throw one-line errors naming the input; no output file is left behind then.
void RunRasterCommand(const RasterCommandOptions& options, std::ostream& summary);

}  // namespace cli
