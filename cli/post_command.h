#pragma once
// `aasim post`: a registered post pass on the user's own image instead of a rendered frame (a
// PNG or OpenEXR export of a render target, e.g. a RenderDoc capture), under each chosen dispatch
// strategy on the modelled GPU. Writes the first strategy's output image and layers, the dispatch
// reports as `aasim frame` writes them, and report.json (docs/cli.md), all-or-nothing, and prints
// the dispatch table and the strategy comparison.

#include <ostream>

#include "cli/post_options.h"

namespace cli {

// `options` must have passed ResolvePostOptions. Input problems (GPU configuration, image, depth
// file, an image too large for memory) throw one-line errors naming the input before the output
// directory is created, so a previous set in it stays as it was. When the strategies' outputs
// differ, everything is written and the summary printed first, then std::runtime_error is thrown,
// as `aasim frame` does.
void RunPostCommand(const PostCommandOptions& options, std::ostream& summary);

}  // namespace cli
