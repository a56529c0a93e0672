#pragma once
// `aasim run`, the main job (and `aasim` with no arguments): the study of cli/study.h written as
// the output set of cli/study_report.h, all-or-nothing, with a summary on stdout that ends with
// the path of report.html.

#include <ostream>

#include "cli/run_options.h"

namespace cli {

// `options` must have passed ResolveRunOptions. Input problems (scene, pattern, GPU
// configuration) throw one-line errors naming the input before the output directory is created;
// output problems throw before any file is moved into place. If a post pass's strategies give
// different images (a bug in passes/), the outputs are written and the summary printed first,
// then std::runtime_error is thrown.
void RunRunCommand(const RunCommandOptions& options, std::ostream& summary, std::ostream& log);

}  // namespace cli
