#pragma once
// The main job's outputs (`aasim run`, formats in docs/report.md): images (EXR with named layers,
// PNG previews) under images/, report.json (schema aasim.report), counters.csv (one row per
// dispatch), quality.csv (one row per scored image) and the self-contained report.html.

#include <nlohmann/json.hpp>

#include "cli/output_dir.h"
#include "cli/report_html.h"
#include "cli/run_options.h"
#include "cli/sequence_report.h"
#include "study/study.h"

namespace cli {

using study::Study;
using study::StudyFrame;

inline constexpr const char* kReportSchema = "aasim.report";
inline constexpr int kReportVersion = 1;

// The frame's own files, written while its pipeline still holds the surfaces:
// images/frames/<mode>/colour.png, frame.exr, eqaa.exr, fmask.png, error.exr, flip.png.
void StageFrameFiles(OutputDir& dir, const StudyFrame& frame, const sim::FramePipeline& pipeline);

// A pass's layers under every strategy: images/passes/<pass>/<strategy>/<layer>.png and .exr,
// written as the pass finishes (StudyObserver::passDone), before the study drops them.
void StagePassLayers(OutputDir& dir, const study::StudyPass& pass);

// Everything else: ground truth and pass images, heat maps, report.json, counters.csv,
// quality.csv and report.html.
// With a multi-frame run's images, report.html gains the sequence sections.
void StageStudyFiles(OutputDir& dir, const Study& study, const RunCommandOptions& options,
                     const SequenceImages* sequenceImages = nullptr);
// The frame strips show the aliased frame's hardest region, as the report's first crop.
void SetSequenceRegion(SequenceImages& images, const StudyFrame& frame);

// The run's resolved options, echoed in report.json and at the end of report.html.
nlohmann::ordered_json RunConfigurationJson(const RunCommandOptions& options, int threads);

nlohmann::ordered_json StudyJson(const Study& study, const RunCommandOptions& options);
Report StudyHtml(const Study& study, const RunCommandOptions& options, const SequenceImages* sequenceImages = nullptr);

}  // namespace cli
