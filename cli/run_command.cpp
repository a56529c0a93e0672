// `aasim run` (see run_command.h).

#include "cli/run_command.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <oneapi/tbb/global_control.h>

#include "cli/dispatch_output.h"
#include "cli/number_format.h"
#include "cli/output_dir.h"
#include "study/study.h"
#include "cli/study_report.h"

namespace cli {
namespace {

using study::Study;
using study::StudyFrame;
using study::StudyPass;
using study::StudyPassRun;
using study::ScoredImage;

// One line per finished step on the log, with its host time; a progress bar on stderr for the
// ground truth, as --progress says.
study::StudyObserver Observer(const RunCommandOptions& options, std::ostream& log,
                              std::function<void(const StudyFrame&, const sim::FramePipeline&)> frameDone,
                              std::function<void(const StudyPass&)> passDone) {
  study::StudyObserver observer;
  observer.frameDone = std::move(frameDone);
  observer.passDone = std::move(passDone);
  if (options.progressMode == ProgressMode::Never) return observer;
  observer.stepDone = [&log](const std::string& step, double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", seconds);
    log << "aasim run: " << step << " (" << text << " s)\n" << std::flush;
  };
  observer.groundTruthProgress = scenes::StderrProgressBar("ground truth", options.progressMode == ProgressMode::Always);
  return observer;
}

void PrintQuality(std::ostream& out, const ScoredImage& image) {
  const passes::QualityScores& s = image.quality.scores;
  char line[160];
  std::snprintf(line, sizeof line, "  %-22s %8s %8s %8s %10s\n", image.label.c_str(), FormatFixed(s.psnr, 2).c_str(),
                FormatFixed(s.ssim, 4).c_str(), FormatFixed(s.flip, 4).c_str(), FormatFixed(s.edgeFlip, 4).c_str());
  out << line;
}

void PrintPass(std::ostream& out, const Study& study, const StudyPass& pass) {
  out << "\nstencil vs queue: " << pass.studiedDispatch << (pass.sweepPoint.empty() ? "" : " at " + pass.sweepPoint)
      << " on " << pass.inputFrame << " (" << pass.workItems
      << " work-set pixels; estimated µs: docs/timing-model.md)\n";
  if (pass.runs.size() == 2) {
    const StudyPassRun &a = pass.runs[0], &b = pass.runs[1];
    const std::span<const study::DispatchRecord> all(study.dispatches);
    PrintDispatchComparison(out, pass.studiedDispatch, passes::StrategyName(a.strategy),
                            all.subspan(a.firstDispatch, a.endDispatch - a.firstDispatch),
                            passes::StrategyName(b.strategy),
                            all.subspan(b.firstDispatch, b.endDispatch - b.firstDispatch));
  }
  out << "identical output: "
      << (pass.difference.Identical() ? "yes (output and layers bit-identical)" : "NO, " + pass.difference.Describe())
      << '\n';
}

void PrintSummary(std::ostream& out, const Study& study, const RunCommandOptions& options,
                  const std::filesystem::path& dir) {
  out << "run        " << options.scene << ", " << options.width << "x" << options.height << ", GPU "
      << study.gpu.name << ", ground truth " << study.groundTruth.image.samplesPerPixel << " rays/px"
      << (study.groundTruth.cacheHit ? " (cached)" : "") << "\n\n";
  char header[160];
  std::snprintf(header, sizeof header, "  %-22s %8s %8s %8s %10s\n", "image", "PSNR dB", "SSIM", "FLIP", "edge FLIP");
  out << "quality against the ground truth\n" << header;
  for (const StudyFrame& frame : study.frames) {
    PrintQuality(out, frame.image);
    for (const study::StudyResolve& resolve : frame.resolves) PrintQuality(out, resolve.image);
    if (frame.srgb8) PrintQuality(out, *frame.srgb8);
  }
  for (const StudyPass& pass : study.passes) PrintQuality(out, pass.image);
  for (const StudyPass& pass : study.passes) PrintPass(out, study, pass);
  out << "\nhost time  " << FormatFixed(study.hostSeconds, 1) << " s (" << study.threads << " threads)\n"
      << "report: " << std::filesystem::absolute(dir / "report.html").string() << '\n';
}

}  // namespace

void RunRunCommand(const RunCommandOptions& options, std::ostream& summary, std::ostream& log) {
  const tbb::global_control threadLimit(tbb::global_control::max_allowed_parallelism,
                                        static_cast<std::size_t>(options.threads));
  RunCommandOptions resolved = options;
  if (!resolved.noCache && resolved.cache.empty()) {
    resolved.cache = scenes::GroundTruthCache::DefaultDirectory().string();
  }
  // Every input is read and checked before the output directory exists, so a bad input leaves
  // no directory behind.
  const study::ExperimentConfig config = ExperimentFrom(resolved);
  const study::StudyInputs inputs = study::LoadStudyInputs(config);
  OutputDir dir = OpenOutOption(resolved.out);
  SequenceImages sequenceImages(dir);
  study::StudyObserver observer = Observer(
      resolved, log,
      [&](const StudyFrame& frame, const sim::FramePipeline& pipeline) {
        StageFrameFiles(dir, frame, pipeline);
        if (!sequenceImages.HasRegion()) SetSequenceRegion(sequenceImages, frame);
      },
      [&](const StudyPass& pass) { StagePassLayers(dir, pass); });
  observer.sequenceImage = [&](const study::SequenceGroup* group, const study::SequenceTrack* track, int frame,
                               const sim::Texture2D<glm::vec4>& image) { sequenceImages.Add(group, track, frame, image); };
  const Study study = study::RunStudy(inputs, config, observer);
  StageStudyFiles(dir, study, resolved, &sequenceImages);
  dir.Commit("report.json");
  PrintSummary(summary, study, resolved, dir.Path());
  for (const StudyPass& pass : study.passes) {
    if (pass.difference.Identical()) continue;
    throw std::runtime_error("post pass " + pass.Label() + ": the strategies' outputs differ (" +
                             pass.difference.Describe() + "): a bug in passes/ (outputs kept in " +
                             dir.Path().string() + ")");
  }
}

}  // namespace cli
