#pragma once
// trace.json and trace.txt of `aasim raster --trace X,Y` (formats in docs/cli.md): one entry
// per colour-block update of a traced pixel, with every field of fmask::TraceEvent; FMASK both
// as the raw element (hex, the layout's element width) and decoded into per-sample codes.

#include <string>

#include <nlohmann/json.hpp>

#include "cli/raster_options.h"
#include "fmask/eqaa_surface.h"

namespace cli {

nlohmann::ordered_json TraceJson(const RasterCommandOptions& options,
                                 const fmask::EqaaSurface& surface);
std::string TraceText(const RasterCommandOptions& options, const fmask::EqaaSurface& surface);

}  // namespace cli
