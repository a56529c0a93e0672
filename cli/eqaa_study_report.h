#pragma once
// The EQAA study in report.html and report.json (docs/report.md "EQAA study"): every mode's
// surface under every resolve that read it, from study::EqaaStudyRows, and aasim's estimates for
// 8x CRAA and SMAA next to the timings seed 001 quotes for a PS4.

#include <nlohmann/json.hpp>

#include "cli/report_html.h"
#include "study/study.h"

namespace cli {

ReportSection EqaaStudySection(const study::Study& study);
nlohmann::ordered_json EqaaStudyJson(const study::Study& study);

}  // namespace cli
