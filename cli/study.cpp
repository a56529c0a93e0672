// The main job's computation (see study.h).

#include "cli/study.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <type_traits>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>

#include "cli/frame_options.h"

namespace cli {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One line per step on the log, with the host time it took; silent with --progress never.
class StepLog {
 public:
  StepLog(std::ostream& out, bool enabled) : out_(out), enabled_(enabled) {}
  template <typename Body>
  auto Step(const std::string& what, Body&& body) {
    const Clock::time_point start = Clock::now();
    if constexpr (std::is_void_v<decltype(body())>) {
      body();
      Done(what, start);
    } else {
      auto result = body();
      Done(what, start);
      return result;
    }
  }

 private:
  void Done(const std::string& what, Clock::time_point start) {
    if (!enabled_) return;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2f", SecondsSince(start));
    out_ << "aasim run: " << what << " (" << seconds << " s)\n" << std::flush;
  }
  std::ostream& out_;
  bool enabled_;
};

scenes::ProgressCallback ProgressBar(const RunCommandOptions& options, std::string label) {
  switch (options.progressMode) {
    case ProgressMode::Never: return {};
    case ProgressMode::Always: return scenes::StderrProgressBar(std::move(label), true);
    case ProgressMode::Auto: break;
  }
  return scenes::StderrProgressBar(std::move(label), false);
}

StudyGroundTruth RenderGroundTruth(const StudyInputs& inputs, const RunCommandOptions& options) {
  const Clock::time_point start = Clock::now();
  scenes::GroundTruthSettings settings;
  settings.width = options.width;
  settings.height = options.height;
  settings.samplesPerPixel = options.groundTruthSamples;
  const scenes::ProgressCallback progress = ProgressBar(options, "ground truth");
  StudyGroundTruth truth;
  if (options.noCache) {
    truth.image = scenes::RenderGroundTruth(inputs.scene, inputs.scene.camera, settings, progress);
  } else {
    const scenes::GroundTruthCache cache(options.cache);
    scenes::CachedGroundTruth cached = cache.LoadOrRender(inputs.scene, inputs.scene.camera, settings, progress);
    truth.image = std::move(cached.image);
    truth.cacheHit = cached.cacheHit;
    truth.cacheFile = cached.file;
  }
  truth.edgeMask.reserve(truth.image.edge.size());
  for (const std::uint8_t edge : truth.image.edge) truth.edgeMask.push_back(edge != 0 ? 1.0f : 0.0f);
  truth.colour = sim::Texture2D<glm::vec4>("ground truth", truth.image.width, truth.image.height);
  for (std::size_t i = 0; i < truth.image.colour.size(); ++i) {
    truth.colour.Texels()[i] = glm::vec4(truth.image.colour[i], 1.0f);
  }
  truth.seconds = SecondsSince(start);
  return truth;
}

// Without edge pixels the edge scores have nothing to average: NaN, shown as "n/a" and null.
passes::QualityResult Score(const sim::Texture2D<glm::vec4>& image, const StudyGroundTruth& groundTruth) {
  const passes::ImageView test = passes::ViewOf(image), reference = passes::ViewOf(groundTruth.colour);
  if (passes::CountSelected(groundTruth.edgeMask) > 0) {
    return passes::ScoreWithMaps(test, reference, groundTruth.edgeMask);
  }
  const std::vector<float> everyPixel(groundTruth.edgeMask.size(), 1.0f);
  passes::QualityResult result = passes::ScoreWithMaps(test, reference, everyPixel);
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  result.scores.edgePsnr = result.scores.edgeSsim = result.scores.edgeFlip = kNone;
  result.scores.edgePixels = 0;
  return result;
}

sim::Texture2D<glm::vec4> FetchResolve(const fmask::EqaaSurface& surface) {
  sim::Texture2D<glm::vec4> resolved("fetch resolve", surface.Width(), surface.Height());
  const int samples = surface.Config().coverageSamples;
  tbb::parallel_for(0, surface.Height(), [&](int y) {
    for (int x = 0; x < surface.Width(); ++x) {
      glm::vec4 sum(0.0f);
      for (int s = 0; s < samples; ++s) {
        const fmask::Colour c = surface.FetchSample(x, y, s);
        sum += glm::vec4(c.r, c.g, c.b, c.a);
      }
      resolved.At(x, y) = sum / static_cast<float>(samples);
    }
  });
  return resolved;
}

sim::FrameSettings FrameSettingsFor(const StudyInputs& inputs, const RunCommandOptions& options,
                                    std::size_t mode) {
  sim::FrameSettings settings;
  settings.width = options.width;
  settings.height = options.height;
  settings.eqaa = options.eqaaModes[mode];
  settings.pattern = inputs.patterns[mode];
  settings.policy = fmask::PolicyByName(options.policy);
  settings.flush = WaveFlushByName(options.flush);
  ApplyLighting(inputs.scene.lighting, settings);
  return settings;
}

class StudyRunner {
 public:
  StudyRunner(const StudyInputs& inputs, const RunCommandOptions& options, std::ostream& log)
      : inputs_(inputs), options_(options), log_(log, options.progressMode != ProgressMode::Never),
        machine_(inputs.gpu) {}

  Study Run(const FrameCallback& onFrame) {
    const Clock::time_point start = Clock::now();
    study_.sceneName = inputs_.scene.name;
    study_.triangles = inputs_.scene.TriangleCount();
    study_.gpu = inputs_.gpu;
    study_.groundTruth = log_.Step(GroundTruthStep(), [&] { return RenderGroundTruth(inputs_, options_); });
    for (std::size_t mode = 0; mode < options_.eqaaModes.size(); ++mode) RunMode(mode, onFrame);
    study_.dispatches = machine_.Reports();
    study_.hostSeconds = SecondsSince(start);
    return std::move(study_);
  }

 private:
  std::string GroundTruthStep() const {
    return "ground truth " + std::to_string(options_.width) + "x" + std::to_string(options_.height) + ", " +
           std::to_string(options_.groundTruthSamples) + " rays per pixel" +
           (options_.noCache ? "" : " (cache: " + options_.cache + ")");
  }

  void RunMode(std::size_t mode, const FrameCallback& onFrame) {
    const std::string label = fmask::EqaaName(options_.eqaaModes[mode]);
    sim::FramePipeline pipeline(machine_, FrameSettingsFor(inputs_, options_, mode));
    StudyFrame frame{.mode = options_.eqaaModes[mode],
                     .image = {label, "frames/" + ModeSlug(options_.eqaaModes[mode]), {"frame colour", 1, 1}, {}},
                     .drawDispatch = machine_.Reports().size()};
    log_.Step("frame " + label, [&] { pipeline.Render(inputs_.frame.Geometry()); });
    Tag(label, "");
    frame.image.colour = pipeline.Colour();
    frame.fragments = pipeline.Fragments();
    frame.image.quality = log_.Step("metrics " + label, [&] { return Score(frame.image.colour, study_.groundTruth); });
    if (frame.mode.fragments < frame.mode.coverageSamples) {
      ScoredImage fetch{label + " fetch", frame.image.folder + "/fetch", FetchResolve(pipeline.Eqaa()), {}};
      fetch.quality = log_.Step("metrics " + fetch.label, [&] { return Score(fetch.colour, study_.groundTruth); });
      frame.fetchResolve = std::move(fetch);
    }
    if (onFrame) onFrame(frame, pipeline);
    // Post-process AA works on the aliased frame a renderer without MSAA produces: the first mode.
    if (mode == 0) {
      for (const passes::PassConfig& pass : options_.postPasses) RunPass(pass, pipeline, label);
    }
    study_.frames.push_back(std::move(frame));
  }

  void RunPass(const passes::PassConfig& config, const sim::FramePipeline& pipeline, const std::string& frameLabel) {
    const passes::PassInfo& info = config.Info();
    const std::string name(info.name);
    StudyPass result{.name = name,
                     .description = std::string(info.description),
                     .studiedDispatch = std::string(info.studiedDispatches.front()),
                     .settings = passes::DescribeSettings(config.settings),
                     .inputFrame = frameLabel,
                     .image = {name, "passes/" + name, {"pass output", 1, 1}, {}}};
    std::optional<passes::PassOutput> first;
    for (const passes::Strategy strategy : info.strategies) {
      const std::string strategyName(passes::StrategyName(strategy));
      StudyPassRun run{.strategy = strategy, .firstDispatch = machine_.Reports().size(), .endDispatch = 0, .layers = {}};
      // One instance per strategy: a pass with history must not carry one strategy's into the other's.
      const std::unique_ptr<passes::Pass> pass = config.Make();
      passes::PassOutput output = log_.Step("pass " + name + " [" + strategyName + "]", [&] {
        return pass->Run(machine_, passes::FrameInputsOf(pipeline), strategy);
      });
      run.endDispatch = machine_.Reports().size();
      Tag(frameLabel, strategyName);
      run.layers = output.layers;
      if (!first) {
        first = std::move(output);
      } else if (result.difference.Identical()) {
        result.difference = passes::CompareOutputs(*first, output);
      }
      result.runs.push_back(std::move(run));
    }
    result.workItems = first->workItems;
    result.image.colour = std::move(first->colour);
    result.image.quality = log_.Step("metrics " + name, [&] { return Score(result.image.colour, study_.groundTruth); });
    study_.passes.push_back(std::move(result));
  }

  // Labels the dispatches added since the last call.
  void Tag(const std::string& frame, const std::string& strategy) {
    const std::size_t count = machine_.Reports().size();
    study_.dispatchFrames.resize(count, frame);
    study_.dispatchStrategies.resize(count, strategy);
  }

  const StudyInputs& inputs_;
  const RunCommandOptions& options_;
  StepLog log_;
  sim::Machine machine_;
  Study study_;
};

}  // namespace

std::string ModeSlug(const fmask::EqaaConfig& mode) {
  return std::to_string(mode.coverageSamples) + "s-" + std::to_string(mode.depthSamples) + "z-" +
         std::to_string(mode.fragments) + "f";
}

StudyInputs LoadStudyInputs(const RunCommandOptions& options) {
  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  StudyInputs inputs{scenes::LoadScene(options.scene, aspect), {}, {}, sim::GpuConfigByName(options.gpu)};
  inputs.frame = ToFrameScene(inputs.scene, aspect);
  for (const fmask::EqaaConfig& mode : options.eqaaModes) {
    inputs.patterns.push_back(raster::ResolvePattern(options.pattern, mode.coverageSamples));
  }
  return inputs;
}

Study RunStudy(const StudyInputs& inputs, const RunCommandOptions& options, const FrameCallback& onFrame,
               std::ostream& log) {
  StudyRunner runner(inputs, options, log);
  Study study = runner.Run(onFrame);
  study.threads = static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  return study;
}

}  // namespace cli
