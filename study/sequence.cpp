// Frame sequences (see sequence.h).

#include "study/sequence.h"

#include <algorithm>
#include <stdexcept>

namespace study {
namespace {
// A one-sample schedule that moves the sample stands for a jittered projection: every attribute
// follows the sample (sim::FrameSettings::sampleRateShading), not only coverage.
sim::FrameSettings WithPattern(sim::FrameSettings settings, const raster::JitterSchedule& schedule) {
  settings.pattern = schedule.At(0);
  settings.sampleRateShading = schedule.Samples() == 1 && schedule.Name() != "none";
  return settings;
}
}  // namespace

bool Follows(const SequenceConfig& config, const passes::PassInfo& info) {
  if (!config.followed) return info.temporal;
  return std::find(config.followed->begin(), config.followed->end(), info.name) != config.followed->end();
}

SequenceRenderer::SequenceRenderer(sim::Machine& machine, const scenes::Scene& scene, const FrameScene& base,
                                   sim::FrameSettings settings, raster::JitterSchedule schedule,
                                   const SequenceConfig& config)
    : machine_(machine),
      scene_(scene),
      frame_(base),
      velocityBuffer_(config.velocityBuffer),
      schedule_(std::move(schedule)),
      path_(config.cameraPath),
      frameSeconds_(1.0 / config.framesPerSecond),
      aspect_(static_cast<float>(settings.width) / static_cast<float>(settings.height)),
      pipeline_(machine, WithPattern(std::move(settings), schedule_)) {}

void SequenceRenderer::Render(int frame) {
  if (frame < 0) throw std::invalid_argument("sequence frame " + std::to_string(frame) + " is negative");
  MoveFrameScene(scenes::SceneAt(scene_, path_, frame), aspect_, frame_);
  const ClipSpaceScene previous = ToClipSpace(scenes::SceneAt(scene_, path_, frame - 1), aspect_);
  pipeline_.Render(frame_.Geometry(previous.positions), {.pattern = &schedule_.At(frame), .frameIndex = frame});
  if (velocityBuffer_ != VelocityBuffer::Float) {
    packedVelocity_ = PackVelocity(machine_, velocityBuffer_, pipeline_.Velocity(), pipeline_.Depth());
  }
}

passes::FrameInputs SequenceRenderer::Inputs() const {
  passes::FrameInputs inputs = passes::FrameInputsOf(pipeline_);
  inputs.frameSeconds = frameSeconds_;
  if (packedVelocity_) inputs.velocity = &*packedVelocity_;
  return inputs;
}

}  // namespace study
