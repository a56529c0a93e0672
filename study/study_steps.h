#pragma once
// Pieces the single-frame study (study.cpp) and the sequence study (sequence_study.cpp) share.
// Internal to study/.

#include <chrono>
#include <string>
#include <type_traits>
#include <vector>

#include "study/study.h"

namespace study::detail {

using Clock = std::chrono::steady_clock;

inline double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Runs `body` as one named step and tells the observer how long it took.
template <typename Body>
auto Step(const StudyObserver& observer, const std::string& what, Body&& body) {
  const Clock::time_point start = Clock::now();
  auto done = [&] {
    if (observer.stepDone) observer.stepDone(what, SecondsSince(start));
  };
  if constexpr (std::is_void_v<decltype(body())>) {
    body();
    done();
  } else {
    auto result = body();
    done();
    return result;
  }
}

// The ray-traced image with its edge mask and RGBA form for the metrics.
StudyGroundTruth ToStudyGroundTruth(scenes::GroundTruthImage image);
// The scene at `camera`, through the configured cache when there is one.
StudyGroundTruth RenderGroundTruth(const scenes::Scene& scene, const ExperimentConfig& config,
                                   const StudyObserver& observer);

passes::QualityResult ScoreAgainstGroundTruth(const sim::Texture2D<glm::vec4>& image,
                                              const StudyGroundTruth& groundTruth);

sim::FrameSettings FrameSettingsFor(const StudyInputs& inputs, const ExperimentConfig& config,
                                    const fmask::EqaaConfig& mode, const raster::SamplePattern& pattern,
                                    const std::string& policy);

// The strategies a pass runs under: those it declares, narrowed to the configured ones.
std::vector<passes::Strategy> ChosenStrategies(const ExperimentConfig& config, const passes::PassInfo& info);

// A pass's study entry before its runs: name, settings, the frame it read.
StudyPass NewStudyPass(const PlannedPass& planned, const std::string& frameLabel);
// Completes the entry from the first strategy's output (image, quality, variant), hands it to
// the observer and appends it to the study.
void FinishStudyPass(StudyPass result, passes::PassOutput first, const StudyGroundTruth& groundTruth,
                     const StudyObserver& observer, Study& study);

// The multi-frame part of a run (ExperimentConfig::sequence.frames > 1): fills study.sequence
// and adds each temporal pass's last frame to study.passes.
void RunSequenceStudy(const StudyInputs& inputs, const ExperimentConfig& config, const StudyObserver& observer,
                      sim::Machine& machine, Study& study);

}  // namespace study::detail
