#pragma once
// `aasim frame`: scene -> sim::FramePipeline on a modelled GPU (raster, pixel waves, material
// kernel, EQAA colour, resolve) -> the demo edge-blend post pass under each chosen dispatch
// strategy. Writes the images, heat maps and per-dispatch reports (docs/cli.md) all-or-nothing
// and prints the dispatch table with estimated times.

#include <ostream>

#include "cli/frame_options.h"

namespace cli {

// `options` must have passed ResolveFrameOptions. Input problems (scene, pattern, GPU
// configuration) throw one-line errors naming the input before the output directory is
// created; output problems throw before any file is moved into place. When both strategies ran
// and their images differ (a bug in passes/: they run the same arithmetic in the same order),
// the outputs are written and the summary printed first, so the difference can be inspected,
// then std::runtime_error is thrown.
void RunFrameCommand(const FrameCommandOptions& options, std::ostream& summary);

}  // namespace cli
