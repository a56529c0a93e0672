// The multi-frame part of the study (see study_steps.h): the passes SequenceConfig::followed names
// (the temporal ones by default) followed over a sequence drawn with the jitter schedule each is
// built for, scored frame by frame against a jitter-free ground truth of the same frame, with
// flicker, ghosting and convergence.
//
// Techniques are grouped by the frames they read: one group per (schedule, mode). Spatial passes
// read the run's first frame mode unjittered ("none"); a temporal pass reads its PassInfo::jitter
// schedule (or the run's override) drawn as S/S/S with the schedule's S. Every frame's ground
// truth is made first; then the groups run one at a time, each drawing its frames once for all its
// passes, so only one group's pipeline and temporal passes' targets exist at once. Reports of the
// last frame join Study::dispatches (a temporal pass's study entry is its last frame); earlier
// frames are summarised into SequenceFrameCounters and dropped.

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "scenes/motion.h"
#include "sim/colour.h"
#include "study/stability.h"
#include "study/study_steps.h"

namespace study::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Ages saturate here; only ages below kGhostFrames are ever asked for.
constexpr std::uint8_t kAgeCap = 255;

SequenceFrameCounters Summarise(const std::vector<sim::DispatchReport>& reports) {
  SequenceFrameCounters counters;
  for (const sim::DispatchReport& report : reports) {
    counters.lanes.Merge(report.lanes);
    ++counters.dispatches;
    counters.dramBytes += report.DramBytes();
    counters.estimatedMicroseconds += report.time.totalMicroseconds;
    for (const sim::ResourceTraffic& traffic : report.resources) {
      if (passes::IsHistoryResource(traffic.name)) counters.historyBytes += traffic.bytesRead + traffic.bytesWritten;
    }
  }
  return counters;
}

struct TrackState {
  const PlannedPass* pass = nullptr;  // null: the drawn frames
  std::vector<passes::Strategy> strategies;
  // One per strategy. A temporal pass keeps its instances for the whole sequence (its history);
  // a spatial pass gets fresh ones every frame (it keeps nothing between frames, tests/
  // passes_all_test.cpp), so a group holds only its temporal passes' targets at once.
  std::vector<std::unique_ptr<passes::Pass>> instances;
  std::vector<DisplayImage> frames;  // every frame's image as displayed (the last is the previous)
};

struct GroupState {
  SequenceGroup result;
  sim::FrameSettings settings;
  raster::SamplePattern pattern;
  std::unique_ptr<SequenceRenderer> renderer;  // while the group runs
  std::vector<TrackState> tracks;
  std::optional<sim::Texture2D<std::uint32_t>> previousIds;
  std::vector<std::uint8_t> ages;
};

std::string ScheduleOf(const ExperimentConfig& config, const passes::PassInfo& info) {
  if (!info.temporal) return "none";
  return config.sequence.jitterOverride.empty() ? std::string(info.jitter) : config.sequence.jitterOverride;
}

class SequenceStudy {
 public:
  SequenceStudy(const StudyInputs& inputs, const ExperimentConfig& config, const StudyObserver& observer,
                sim::Machine& machine, Study& study)
      : inputs_(inputs), config_(config), observer_(observer), machine_(machine), study_(study) {}

  void Run() {
    const int frames = config_.sequence.frames;
    StudySequence& sequence = study_.sequence.emplace();
    sequence.frames = frames;
    sequence.cameraPath = std::string(scenes::CameraPathKindName(config_.sequence.cameraPath.kind));
    sequence.framesPerSecond = config_.sequence.framesPerSecond;
    sequence.groundTruthStill = NothingMoves();
    for (const PlannedPass& pass : planned_) {
      if (Follows(config_.sequence, pass.config.Info())) AddPass(pass);
    }
    for (int frame = 0; frame < frames; ++frame) AddGroundTruth(frame);
    // One group at a time, so only its pipeline and its temporal passes' targets exist at once.
    for (GroupState& group : groups_) {
      RunGroup(group);
      sequence.groups.push_back(std::move(group.result));
      group = {};
    }
  }

 private:
  bool NothingMoves() const {
    if (config_.sequence.cameraPath.kind != scenes::CameraPathKind::Still) return false;
    return std::all_of(inputs_.scene.meshes.begin(), inputs_.scene.meshes.end(),
                       [](const scenes::Mesh& mesh) { return mesh.motion.IsStatic(); });
  }

  // Every frame's ground truth is kept for the groups that follow, only what scoring reads (colour,
  // edge mask) and its display form; when nothing moves, one serves all.
  void AddGroundTruth(int frame) {
    StudySequence& sequence = *study_.sequence;
    if (!sequence.groundTruthStill || truths_.empty()) {
      StudyGroundTruth truth = Step(observer_, "ground truth frame " + std::to_string(frame), [&] {
        return RenderGroundTruth(scenes::SceneAt(inputs_.scene, config_.sequence.cameraPath, frame), config_, observer_);
      });
      sequence.groundTruthSeconds += truth.seconds;
      sequence.groundTruthCacheHits += truth.cacheHit ? 1 : 0;
      truth.image = {};
      truthsShown_.push_back(ToDisplay(truth.colour));
      truths_.push_back(std::move(truth));
    }
    if (observer_.sequenceImage) observer_.sequenceImage(nullptr, nullptr, frame, TruthAt(frame).colour);
  }

  static std::size_t Index(int frame, std::size_t count) { return std::min(static_cast<std::size_t>(frame), count - 1); }
  const StudyGroundTruth& TruthAt(int frame) const { return truths_[Index(frame, truths_.size())]; }
  const DisplayImage& TruthShownAt(int frame) const { return truthsShown_[Index(frame, truthsShown_.size())]; }

  void RunGroup(GroupState& group) {
    group.renderer = std::make_unique<SequenceRenderer>(machine_, inputs_.scene, inputs_.frame, group.settings,
                                                        raster::JitterSchedule::Make(group.result.schedule, group.pattern),
                                                        config_.sequence);
    for (TrackState& track : group.tracks) {
      if (track.pass && track.pass->config.Info().temporal) track.instances = MakeInstances(track);
    }
    for (int frame = 0; frame < config_.sequence.frames; ++frame) StepGroup(group, frame);
    for (std::size_t t = 0; t < group.tracks.size(); ++t) Conclude(group.result, group.result.tracks[t], group.tracks[t]);
  }

  static std::vector<std::unique_ptr<passes::Pass>> MakeInstances(const TrackState& track) {
    std::vector<std::unique_ptr<passes::Pass>> instances;
    for (std::size_t s = 0; s < track.strategies.size(); ++s) instances.push_back(track.pass->config.Make());
    return instances;
  }

  // The group the pass reads its frames from, made on first use.
  GroupState& GroupFor(const passes::PassInfo& info) {
    const std::string schedule = ScheduleOf(config_, info);
    const int scheduleSamples = raster::JitterScheduleSamples(schedule);
    fmask::EqaaConfig mode = config_.modes.front();
    raster::SamplePattern pattern = inputs_.patterns.front();
    if (scheduleSamples == 0) {
      const std::optional<std::size_t> index = PassFrame(config_, info);
      if (!index) throw std::invalid_argument("pass " + std::string(info.name) + " reads no mode of this run");
      mode = config_.modes[*index];
      pattern = inputs_.patterns[*index];
    } else {
      if (info.eqaaSamples != 0 && info.eqaaSamples != scheduleSamples) {
        throw std::invalid_argument("pass " + std::string(info.name) + " reads " + std::to_string(info.eqaaSamples) +
                                    " samples but jitter schedule '" + schedule + "' draws " +
                                    std::to_string(scheduleSamples));
      }
      mode = {scheduleSamples, scheduleSamples, scheduleSamples};
    }
    for (GroupState& group : groups_) {
      if (group.result.schedule == schedule && group.result.mode == mode) return group;
    }
    GroupState& group = groups_.emplace_back(GroupState{.result = {}, .settings = FrameSettingsFor(inputs_, config_, mode, pattern, config_.policy),
                                                        .pattern = pattern, .renderer = nullptr, .tracks = {}, .previousIds = {}, .ages = {}});
    group.result.schedule = schedule;
    group.result.mode = mode;
    AddTrack(group, nullptr);
    return group;
  }

  std::string GroupFolder(const SequenceGroup& group) const {
    return "sequence/" + group.schedule + "-" + ModeSlug(group.mode);
  }

  void AddTrack(GroupState& group, const PlannedPass* pass) {
    SequenceTrack track;
    track.technique = "frames";
    track.folder = GroupFolder(group.result) + "/frames";
    TrackState state;
    state.pass = pass;
    if (pass) {
      const std::string name(pass->config.Info().name);
      track.technique = pass->sweepPoint.empty() ? name : name + " " + pass->sweepPoint;
      track.pass = name;
      track.folder = GroupFolder(group.result) + "/" + name + (pass->sweepPoint.empty() ? "" : "/" + SweepSlug(pass->sweepPoint));
      state.strategies = ChosenStrategies(config_, pass->config.Info());
      if (state.strategies.empty()) throw std::invalid_argument("pass " + name + " runs under none of the chosen strategies");
      for (const passes::Strategy strategy : state.strategies) track.runs.push_back({strategy, {}});
    } else {
      track.runs.push_back({passes::Strategy::StencilCulled, {}});
    }
    group.result.tracks.push_back(std::move(track));
    group.tracks.push_back(std::move(state));
  }

  void AddPass(const PlannedPass& pass) {
    GroupState& group = GroupFor(pass.config.Info());
    AddTrack(group, &pass);
  }

  std::string FrameLabel(const SequenceGroup& group, int frame) const {
    return "frame " + std::to_string(frame) + " " + group.schedule + " " + fmask::EqaaName(group.mode);
  }

  void StepGroup(GroupState& group, int frame) {
    const StudyGroundTruth& truth = TruthAt(frame);
    const std::string label = FrameLabel(group.result, frame);
    Step(observer_, "sequence " + label, [&] { group.renderer->Render(frame); });
    group.result.tracks.front().runs.front().frames.push_back(Summarise(machine_.TakeReports()));
    const passes::FrameInputs inputs = group.renderer->Inputs();
    std::optional<Reprojection> reprojection;
    if (group.previousIds) {
      reprojection = Reproject(*inputs.velocity, *inputs.objectId, *group.previousIds);
      group.ages = AdvanceAges(group.ages, *reprojection, kAgeCap);
    } else {
      group.ages.assign(static_cast<std::size_t>(config_.width) * static_cast<std::size_t>(config_.height), kAgeCap);
    }
    group.result.disoccludedPixels.push_back(reprojection ? reprojection->disoccludedPixels : 0);
    group.result.groundTruthFlicker.push_back(
        reprojection ? CompensatedDifference(TruthShownAt(frame), TruthShownAt(frame - 1), *reprojection) : kNaN);
    const FrameContext context{frame, label, truth, reprojection ? &*reprojection : nullptr, group.ages};
    // The drawn frame as the 8-bit sRGB target the passes read holds it (FrameInputs::colourSrgb8),
    // so it is scored with the quantisation the passes start from.
    Record(group.result, group.result.tracks.front(), group.tracks.front(),
           passes::DecodedSrgb8("frame sRGB8", inputs.ColourSrgb8()), context);
    for (std::size_t t = 1; t < group.tracks.size(); ++t) {
      RunTrack(group.result, group.result.tracks[t], group.tracks[t], inputs, context);
    }
    group.previousIds = *inputs.objectId;
  }

  struct FrameContext {
    int frame;
    const std::string& label;
    const StudyGroundTruth& truth;
    const Reprojection* reprojection;  // null at frame 0
    const std::vector<std::uint8_t>& ages;
  };

  bool LastFrame(int frame) const { return frame + 1 == config_.sequence.frames; }

  void RunTrack(SequenceGroup& group, SequenceTrack& track, TrackState& state, const passes::FrameInputs& inputs,
                const FrameContext& context) {
    const bool entry = LastFrame(context.frame) && state.pass->config.Info().temporal;
    std::optional<StudyPass> result;
    if (entry) result = NewStudyPass(*state.pass, context.label);
    std::optional<passes::PassOutput> first;
    const bool temporal = state.pass->config.Info().temporal;
    for (std::size_t s = 0; s < state.strategies.size(); ++s) {
      const std::string strategyName(passes::StrategyName(state.strategies[s]));
      const std::unique_ptr<passes::Pass> fresh = temporal ? nullptr : state.pass->config.Make();
      passes::Pass& pass = temporal ? *state.instances[s] : *fresh;
      passes::PassOutput output = Step(observer_, "sequence " + context.label + " pass " + track.technique + " [" + strategyName + "]",
                                       [&] { return pass.Run(machine_, inputs, state.strategies[s]); });
      std::vector<sim::DispatchReport> reports = machine_.TakeReports();
      track.runs[s].frames.push_back(Summarise(reports));
      if (result) {
        StudyPassRun run{.strategy = state.strategies[s], .firstDispatch = study_.dispatches.size(), .endDispatch = 0,
                         .layers = output.layers};
        for (sim::DispatchReport& report : reports) {
          study_.dispatches.push_back({std::move(report), context.label, track.pass, strategyName, state.pass->sweepPoint});
        }
        run.endDispatch = study_.dispatches.size();
        result->runs.push_back(std::move(run));
      }
      if (!first) {
        first = std::move(output);
        continue;
      }
      if (!track.differenceFrame) {
        passes::StrategyDifference difference = passes::CompareOutputs(*first, output);
        if (!difference.Identical()) {
          track.differenceFrame = context.frame;
          track.difference = std::move(difference);
        }
      }
      if (result && result->difference.Identical()) result->difference = passes::CompareOutputs(*first, output);
    }
    Record(group, track, state, first->colour, context);
    if (result) FinishStudyPass(std::move(*result), std::move(*first), context.truth, observer_, study_);
  }

  void Record(const SequenceGroup& group, SequenceTrack& track, TrackState& state, const sim::Texture2D<glm::vec4>& image,
              const FrameContext& context) {
    track.quality.push_back(
        Step(observer_, "metrics " + context.label + " " + track.technique,
             [&] { return ScoreAgainstGroundTruth(image, context.truth).scores; }));
    DisplayImage shown = ToDisplay(image);
    track.flicker.push_back(context.reprojection ? CompensatedDifference(shown, state.frames.back(), *context.reprojection) : kNaN);
    track.ghosting.push_back(YoungPixelError(shown, TruthShownAt(context.frame), context.ages, kGhostFrames));
    state.frames.push_back(std::move(shown));
    if (observer_.sequenceImage) observer_.sequenceImage(&group, &track, context.frame, image);
  }

  void Conclude(const SequenceGroup& group, SequenceTrack& track, TrackState& state) const {
    // Convergence is judged where aliasing is: the last frame's ground-truth edge pixels.
    const std::vector<float>& edges = TruthAt(config_.sequence.frames - 1).edgeMask;
    for (const DisplayImage& frame : state.frames) {
      track.distanceToFinal.push_back(MeanCodeDifference(frame, state.frames.back(), edges));
    }
    track.convergenceFrame = ConvergenceFrame(track.distanceToFinal, kConvergenceCodes);
    double excess = 0.0;
    for (std::size_t k = 1; k < track.flicker.size(); ++k) excess += track.flicker[k] - group.groundTruthFlicker[k];
    track.excessFlicker = track.flicker.size() > 1 ? excess / static_cast<double>(track.flicker.size() - 1) : kNaN;
    state = {};
  }

  const StudyInputs& inputs_;
  const ExperimentConfig& config_;
  const StudyObserver& observer_;
  sim::Machine& machine_;
  Study& study_;
  const std::vector<PlannedPass> planned_ = PlanPasses(config_);
  std::vector<GroupState> groups_;
  std::vector<StudyGroundTruth> truths_;  // per frame, or one when nothing moves
  std::vector<DisplayImage> truthsShown_;
};

}  // namespace

void RunSequenceStudy(const StudyInputs& inputs, const ExperimentConfig& config, const StudyObserver& observer,
                      sim::Machine& machine, Study& study) {
  SequenceStudy(inputs, config, observer, machine, study).Run();
}

}  // namespace study::detail
