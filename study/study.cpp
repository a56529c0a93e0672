// The main job's computation (see study.h).

#include "study/study.h"
#include "study/study_steps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <type_traits>

#include <oneapi/tbb/global_control.h>

#include "sim/formats.h"

namespace study {
namespace detail {

StudyGroundTruth ToStudyGroundTruth(scenes::GroundTruthImage image) {
  StudyGroundTruth truth;
  truth.image = std::move(image);
  truth.edgeMask.reserve(truth.image.edge.size());
  for (const std::uint8_t edge : truth.image.edge) truth.edgeMask.push_back(edge != 0 ? 1.0f : 0.0f);
  truth.colour = sim::Texture2D<glm::vec4>("ground truth", truth.image.width, truth.image.height);
  for (std::size_t i = 0; i < truth.image.colour.size(); ++i) {
    truth.colour.Texels()[i] = glm::vec4(truth.image.colour[i], 1.0f);
  }
  truth.scoring.emplace(passes::ViewOf(truth.colour));
  return truth;
}

StudyGroundTruth RenderGroundTruth(const scenes::Scene& scene, const ExperimentConfig& config,
                                   const StudyObserver& observer) {
  const Clock::time_point start = Clock::now();
  scenes::GroundTruthSettings settings;
  settings.width = config.width;
  settings.height = config.height;
  settings.samplesPerPixel = config.groundTruth.samplesPerPixel;
  StudyGroundTruth truth;
  if (!config.groundTruth.cache) {
    truth = ToStudyGroundTruth(scenes::RenderGroundTruth(scene, scene.camera, settings, observer.groundTruthProgress));
  } else {
    const scenes::GroundTruthCache cache(*config.groundTruth.cache);
    scenes::CachedGroundTruth cached = cache.LoadOrRender(scene, scene.camera, settings, observer.groundTruthProgress);
    truth = ToStudyGroundTruth(std::move(cached.image));
    truth.cacheHit = cached.cacheHit;
    truth.cacheFile = cached.file;
  }
  truth.seconds = SecondsSince(start);
  return truth;
}

// Without edge pixels the edge scores have nothing to average: NaN, shown as "n/a" and null.
passes::QualityResult ScoreAgainstGroundTruth(const sim::Texture2D<glm::vec4>& image, const StudyGroundTruth& groundTruth) {
  const passes::ImageView test = passes::ViewOf(image);
  const passes::ScoringReference reference =
      groundTruth.scoring ? *groundTruth.scoring : passes::ScoringReference(passes::ViewOf(groundTruth.colour));
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

sim::FrameSettings FrameSettingsFor(const StudyInputs& inputs, const ExperimentConfig& config,
                                    const fmask::EqaaConfig& mode, const raster::SamplePattern& pattern,
                                    const std::string& policy) {
  sim::FrameSettings settings;
  settings.width = config.width;
  settings.height = config.height;
  settings.eqaa = mode;
  settings.pattern = pattern;
  settings.policy = fmask::PolicyByName(policy);
  settings.flush = config.flush;
  settings.drawOrder = config.drawOrder;
  settings.depthPrepass = config.depthPrepass;
  settings.maxZPlanes = config.maxZPlanes;
  ApplyLighting(inputs.scene.lighting, settings);
  return settings;
}

std::vector<passes::Strategy> ChosenStrategies(const ExperimentConfig& config, const passes::PassInfo& info) {
  if (config.strategies.empty()) return info.strategies;
  std::vector<passes::Strategy> chosen;
  for (const passes::Strategy strategy : info.strategies) {
    if (std::find(config.strategies.begin(), config.strategies.end(), strategy) != config.strategies.end()) {
      chosen.push_back(strategy);
    }
  }
  return chosen;
}

StudyPass NewStudyPass(const PlannedPass& planned, const std::string& frameLabel) {
  const passes::PassInfo& info = planned.config.Info();
  const std::string name(info.name);
  std::string folder = "passes/" + name;
  if (!planned.sweepPoint.empty()) folder += "/" + SweepSlug(planned.sweepPoint);
  StudyPass pass{.name = name,
                 .sweepPoint = planned.sweepPoint,
                 .description = std::string(info.description),
                 .studiedDispatch = std::string(info.studiedDispatches.front()),
                 .settings = passes::DescribeSettings(planned.config.settings),
                 .inputFrame = frameLabel,
                 .image = {name, folder, {"pass output", 1, 1}, {}}};
  pass.image.label = pass.Label();
  return pass;
}

void FinishStudyPass(StudyPass result, passes::PassOutput first, const StudyGroundTruth& groundTruth,
                     const StudyObserver& observer, Study& study) {
  const passes::PassInfo& info = passes::PassByName(result.name).info();
  result.workItems = first.workItems;
  result.workSet = first.workSet;
  result.image.colour = std::move(first.colour);
  result.image.quality = Step(observer, "metrics " + result.name,
                              [&] { return ScoreAgainstGroundTruth(result.image.colour, groundTruth); });
  for (const StudyPass& earlier : study.passes) {
    if (earlier.name == info.variantOf && earlier.sweepPoint.empty() && earlier.inputFrame == result.inputFrame) {
      result.variant = CompareVariant(earlier.name, result.image.colour, earlier.image.colour);
    }
  }
  if (observer.passDone) {
    observer.passDone(result);
    for (StudyPassRun& run : result.runs) std::vector<passes::PassLayer>().swap(run.layers);
  }
  study.passes.push_back(std::move(result));
}

}  // namespace detail

namespace {

using namespace detail;

class StudyRunner {
 public:
  StudyRunner(const StudyInputs& inputs, const ExperimentConfig& config, const StudyObserver& observer)
      : inputs_(inputs), config_(config), observer_(observer), machine_(inputs.gpu) {}

  Study Run() {
    const Clock::time_point start = Clock::now();
    study_.sceneName = inputs_.scene.name;
    study_.triangles = inputs_.scene.TriangleCount();
    study_.gpu = inputs_.gpu;
    study_.groundTruth =
        Step(observer_, GroundTruthStep(), [&] { return RenderGroundTruth(inputs_.scene, config_, observer_); });
    for (std::size_t mode = 0; mode < config_.modes.size(); ++mode) RunMode(mode);
    for (const std::string& policy : config_.comparedPolicies) {
      for (std::size_t mode = 0; mode < config_.modes.size(); ++mode) {
        if (config_.modes[mode].fragments < config_.modes[mode].coverageSamples) RunComparedPolicy(mode, policy);
      }
    }
    if (config_.sequence.frames > 1) RunSequenceStudy(inputs_, config_, observer_, machine_, study_);
    study_.hostSeconds = SecondsSince(start);
    return std::move(study_);
  }

 private:
  std::string GroundTruthStep() const {
    return "ground truth " + std::to_string(config_.width) + "x" + std::to_string(config_.height) + ", " +
           std::to_string(config_.groundTruth.samplesPerPixel) + " rays per pixel" +
           (config_.groundTruth.cache ? " (cache: " + config_.groundTruth.cache->string() + ")" : "");
  }

  // Draws the scene under the pipeline's mode and policy, scores its box resolve, runs the resolves.
  StudyFrame DrawFrame(std::size_t mode, const std::string& label, const std::string& folder,
                       sim::FramePipeline& pipeline) {
    StudyFrame frame{.mode = config_.modes[mode],
                     .policy = pipeline.Settings().policy.name,
                     .image = {label, folder, {"frame colour", 1, 1}, {}},
                     .drawDispatch = study_.dispatches.size() + pipeline.DispatchesBeforeDraw()};
    Step(observer_, "frame " + label, [&] { pipeline.Render(inputs_.frame.Geometry()); });
    TakeDispatches(machine_, study_.dispatches, label);
    frame.image.colour = pipeline.Colour();
    frame.fragments = pipeline.Fragments();
    frame.unknown = CountUnknownSamples(pipeline.Eqaa());
    frame.image.quality =
        Step(observer_, "metrics " + label, [&] { return ScoreAgainstGroundTruth(frame.image.colour, study_.groundTruth); });
    RunResolves(mode, pipeline, frame);
    return frame;
  }

  void RunComparedPolicy(std::size_t mode, const std::string& policy) {
    const fmask::EqaaConfig& eqaa = config_.modes[mode];
    sim::FramePipeline pipeline(machine_, FrameSettingsFor(inputs_, config_, eqaa, inputs_.patterns[mode], policy));
    StudyFrame frame = DrawFrame(mode, fmask::EqaaName(eqaa) + " " + policy, "frames/" + ModeSlug(eqaa) + "-" + policy,
                                 pipeline);
    if (observer_.frameDone) observer_.frameDone(frame, pipeline);
    study_.frames.push_back(std::move(frame));
  }

  void RunMode(std::size_t mode) {
    const fmask::EqaaConfig& eqaa = config_.modes[mode];
    const std::string label = fmask::EqaaName(eqaa);
    sim::FramePipeline pipeline(machine_, FrameSettingsFor(inputs_, config_, eqaa, inputs_.patterns[mode], config_.policy));
    StudyFrame frame = DrawFrame(mode, label, "frames/" + ModeSlug(eqaa), pipeline);
    if (FeedsAPass(mode)) {
      ScoredImage srgb8{label + " sRGB8", frame.image.folder + "/srgb8",
                        passes::DecodedSrgb8("frame sRGB8", pipeline.ColourSrgb8()), {}};
      srgb8.quality =
          Step(observer_, "metrics " + srgb8.label, [&] { return ScoreAgainstGroundTruth(srgb8.colour, study_.groundTruth); });
      frame.srgb8 = std::move(srgb8);
    }
    if (observer_.frameDone) observer_.frameDone(frame, pipeline);
    for (const PlannedPass& pass : planned_) {
      if (SingleFramePass(pass.config) && PassFrame(config_, pass.config.Info()) == mode) RunPass(pass, pipeline, label);
    }
    study_.frames.push_back(std::move(frame));
  }

  void RunResolves(std::size_t mode, const sim::FramePipeline& pipeline, StudyFrame& frame) {
    const passes::ResolveContext context{.pattern = &inputs_.patterns[mode], .tableCache = config_.tableCache,
                                               .tableConfigurations = config_.tableConfigurations};
    for (const std::string& name : config_.resolves) {
      const passes::RegisteredResolve& registered = passes::ResolveByName(name);
      if (!registered.info().reads(frame.mode)) continue;
      StudyResolve resolve{.name = name,
                           .image = {frame.image.label + " " + name, frame.image.folder + "/" + name, {"resolve", 1, 1}, {}},
                           .firstDispatch = study_.dispatches.size()};
      passes::Resolve& kernel = ResolveFor(registered, mode, context);
      resolve.image.colour = Step(observer_, "resolve " + resolve.image.label, [&] { return kernel.Run(machine_, pipeline.Eqaa()); });
      TakeDispatches(machine_, study_.dispatches, frame.image.label);
      resolve.endDispatch = study_.dispatches.size();
      resolve.image.quality = Step(observer_, "metrics " + resolve.image.label,
                                   [&] { return ScoreAgainstGroundTruth(resolve.image.colour, study_.groundTruth); });
      frame.resolves.push_back(std::move(resolve));
    }
  }

  // One instance per resolve and mode, made (its tables derived) once however many policies draw
  // the mode.
  passes::Resolve& ResolveFor(const passes::RegisteredResolve& registered, std::size_t mode,
                              const passes::ResolveContext& context) {
    std::unique_ptr<passes::Resolve>& made = resolves_[{std::string(registered.info().name), mode}];
    if (!made) {
      made = Step(observer_, "table " + fmask::EqaaName(config_.modes[mode]) + " " + std::string(registered.info().name),
                  [&] { return registered.make(context); });
    }
    return *made;
  }

  bool FeedsAPass(std::size_t mode) const {
    return std::any_of(config_.passes.begin(), config_.passes.end(), [&](const passes::PassConfig& pass) {
      return SingleFramePass(pass) && PassFrame(config_, pass.Info()) == mode;
    });
  }

  // A temporal pass in a multi-frame run runs on the sequence only (its single-frame entry is
  // its sequence's last frame).
  bool SingleFramePass(const passes::PassConfig& pass) const {
    return !pass.Info().temporal || config_.sequence.frames <= 1;
  }

  void RunPass(const PlannedPass& planned, const sim::FramePipeline& pipeline, const std::string& frameLabel) {
    const passes::PassConfig& config = planned.config;
    StudyPass result = NewStudyPass(planned, frameLabel);
    const std::vector<passes::Strategy> strategies = ChosenStrategies(config_, config.Info());
    if (strategies.empty()) throw std::invalid_argument("pass " + result.name + " runs under none of the chosen strategies");
    std::optional<passes::PassOutput> first;
    for (const passes::Strategy strategy : strategies) {
      const std::string strategyName(passes::StrategyName(strategy));
      StudyPassRun run{.strategy = strategy, .firstDispatch = study_.dispatches.size(), .endDispatch = 0, .layers = {}};
      // One instance per strategy: a pass with history must not carry one strategy's into the other's.
      const std::unique_ptr<passes::Pass> pass = config.Make();
      passes::PassOutput output = Step(observer_, "pass " + result.Label() + " [" + strategyName + "]", [&] {
        return pass->Run(machine_, passes::FrameInputsOf(pipeline), strategy);
      });
      TakeDispatches(machine_, study_.dispatches, frameLabel, result.name, strategyName, result.sweepPoint);
      run.endDispatch = study_.dispatches.size();
      run.layers = output.layers;
      if (!first) {
        first = std::move(output);
      } else if (result.difference.Identical()) {
        result.difference = passes::CompareOutputs(*first, output);
      }
      result.runs.push_back(std::move(run));
    }
    FinishStudyPass(std::move(result), std::move(*first), study_.groundTruth, observer_, study_);
  }

  const StudyInputs& inputs_;
  const ExperimentConfig& config_;
  const StudyObserver& observer_;
  const std::vector<PlannedPass> planned_ = PlanPasses(config_);
  sim::Machine machine_;
  Study study_;
  std::map<std::pair<std::string, std::size_t>, std::unique_ptr<passes::Resolve>> resolves_;
};

}  // namespace

VariantDifference CompareVariant(std::string baseline, const sim::Texture2D<glm::vec4>& image,
                                 const sim::Texture2D<glm::vec4>& baselineImage) {
  VariantDifference difference{std::move(baseline), 0, 0, 0,
                               passes::Psnr(passes::ViewOf(image), passes::ViewOf(baselineImage))};
  const std::span<const glm::vec4> a = image.Texels(), b = baselineImage.Texels();
  for (std::size_t i = 0; i < a.size(); ++i) {
    int largest = 0;
    for (int c = 0; c < 3; ++c) {
      largest = std::max(largest, std::abs(int(sim::FloatToSrgb8(a[i][c])) - int(sim::FloatToSrgb8(b[i][c]))));
    }
    difference.pixels += largest > 0 ? 1 : 0;
    difference.pixelsOverOneCode += largest > 1 ? 1 : 0;
    difference.maxCodes = std::max(difference.maxCodes, largest);
  }
  return difference;
}

std::optional<std::size_t> PassFrame(const ExperimentConfig& config, const passes::PassInfo& pass) {
  if (pass.eqaaSamples == 0) return config.modes.empty() ? std::nullopt : std::optional<std::size_t>(0);
  for (std::size_t mode = 0; mode < config.modes.size(); ++mode) {
    if (config.modes[mode].coverageSamples == pass.eqaaSamples) return mode;
  }
  return std::nullopt;
}

std::string ModeSlug(const fmask::EqaaConfig& mode) {
  return std::to_string(mode.coverageSamples) + "s-" + std::to_string(mode.depthSamples) + "z-" +
         std::to_string(mode.fragments) + "f";
}

StudyInputs LoadStudyInputs(const ExperimentConfig& config) {
  const float aspect = static_cast<float>(config.width) / static_cast<float>(config.height);
  StudyInputs inputs{scenes::LoadScene(config.scene, aspect), {}, {}, sim::GpuConfigByName(config.gpu)};
  inputs.frame = ToFrameScene(inputs.scene, aspect);
  for (const fmask::EqaaConfig& mode : config.modes) {
    inputs.patterns.push_back(raster::ResolvePattern(config.pattern, mode.coverageSamples));
  }
  for (const std::string& resolve : config.resolves) passes::ResolveByName(resolve);
  PlanPasses(config);
  for (const std::string& policy : config.comparedPolicies) fmask::PolicyByName(policy);
  return inputs;
}

namespace {
const passes::PassConfig& SweptPass(const ExperimentConfig& config, const SweepAxis& axis) {
  const auto found = std::find_if(config.passes.begin(), config.passes.end(),
                                  [&](const passes::PassConfig& pass) { return pass.Info().name == axis.pass; });
  if (found == config.passes.end()) throw std::invalid_argument("sweep " + axis.pass + ":" + axis.setting + ": " + axis.pass + " is not a pass of the run");
  return *found;
}

void CheckSweepValues(const SweepAxis& axis) {
  const std::string where = "sweep " + axis.pass + ":" + axis.setting;
  if (axis.values.empty()) throw std::invalid_argument(where + ": no values");
  for (std::size_t i = 0; i < axis.values.size(); ++i) {
    if (std::find(axis.values.begin(), axis.values.begin() + static_cast<std::ptrdiff_t>(i), axis.values[i]) !=
        axis.values.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw std::invalid_argument(where + ": " + passes::FormatValue(axis.values[i]) + " is given twice");
    }
  }
}
}  // namespace

std::string SweepSlug(const std::string& sweepPoint) {
  std::string slug = sweepPoint;
  std::replace(slug.begin(), slug.end(), '=', '-');
  return slug;
}

std::vector<PlannedPass> PlanPasses(const ExperimentConfig& config) {
  for (std::size_t a = 0; a < config.sweeps.size(); ++a) {
    SweptPass(config, config.sweeps[a]);
    CheckSweepValues(config.sweeps[a]);
    for (std::size_t b = 0; b < a; ++b) {
      if (config.sweeps[b].pass == config.sweeps[a].pass) {
        throw std::invalid_argument("sweep " + config.sweeps[a].pass + ":" + config.sweeps[a].setting + ": pass " +
                                    config.sweeps[a].pass + " already has a sweep axis (" + config.sweeps[b].setting + ")");
      }
    }
  }
  std::vector<PlannedPass> planned;
  for (const passes::PassConfig& pass : config.passes) {
    const auto axis = std::find_if(config.sweeps.begin(), config.sweeps.end(),
                                   [&](const SweepAxis& each) { return each.pass == pass.Info().name; });
    if (axis == config.sweeps.end()) {
      planned.push_back({pass, ""});
      continue;
    }
    for (const double value : axis->values) {
      PlannedPass point{pass, axis->setting + "=" + passes::FormatValue(value)};
      point.config.settings.Set(axis->setting, value);
      planned.push_back(std::move(point));
    }
  }
  return planned;
}

Study RunStudy(const StudyInputs& inputs, const ExperimentConfig& config, const StudyObserver& observer) {
  StudyRunner runner(inputs, config, observer);
  Study study = runner.Run();
  study.threads = static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  return study;
}

}  // namespace study
