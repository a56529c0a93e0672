#pragma once
// A scene rendered frame after frame (issue 15's multi-frame runs): frame k is the scene moved
// along its camera path and its meshes' motion to k (scenes::SceneAt), drawn with the jitter
// schedule's pattern k into one reused frame pipeline, with velocities from the same vertices
// one frame earlier. Jitter moves only the sample positions, never the geometry, so velocities
// carry no jitter (what a renderer gets by projecting both frames with unjittered matrices).

#include <optional>
#include <string>

#include "passes/pass.h"
#include "raster/jitter_schedule.h"
#include "scenes/motion.h"
#include "scenes/scene.h"
#include "sim/frame.h"
#include "study/frame_scene.h"
#include "study/velocity_buffer.h"

namespace study {

// What a multi-frame run adds to an experiment.
struct SequenceConfig {
  int frames = 1;  // 1: the single-frame study only
  scenes::CameraPath cameraPath{};
  // Simulated frame rate: passes read 1 / framesPerSecond as FrameInputs::frameSeconds.
  double framesPerSecond = 60.0;
  // The passes of ExperimentConfig::passes followed over the sequence, by name; nullopt: the
  // temporal ones (a spatial pass over a sequence costs a run and a scoring per frame).
  std::optional<std::vector<std::string>> followed;
  // Replaces every temporal pass's own schedule (PassInfo::jitter) when set.
  std::string jitterOverride;
  // What passes read as velocities: the float target, or seed 000's 8-bit buffers
  // (study/velocity_buffer.h), packed by a dispatch after each frame's draw.
  VelocityBuffer velocityBuffer = VelocityBuffer::Float;
};

// Whether the sequence follows the pass (SequenceConfig::followed).
bool Follows(const SequenceConfig& config, const passes::PassInfo& info);

class SequenceRenderer {
 public:
  // `settings` gives the mode, size, lighting and frame set-up; its pattern is replaced by the
  // schedule's. `base` is ToFrameScene of `scene` (its textures and ids are reused).
  SequenceRenderer(sim::Machine& machine, const scenes::Scene& scene, const FrameScene& base, sim::FrameSettings settings,
                   raster::JitterSchedule schedule, const SequenceConfig& config);

  // Draws frame `frame` (>= 0); dispatches go to the machine's report list.
  void Render(int frame);
  const sim::FramePipeline& Pipeline() const { return pipeline_; }
  const raster::JitterSchedule& Schedule() const { return schedule_; }
  // The targets of the last rendered frame, with its pattern, jitter and frame time.
  passes::FrameInputs Inputs() const;

 private:
  sim::Machine& machine_;
  const scenes::Scene& scene_;
  FrameScene frame_;
  VelocityBuffer velocityBuffer_;
  std::optional<sim::Texture2D<glm::vec2>> packedVelocity_;  // decoded, when the buffer is packed
  raster::JitterSchedule schedule_;
  scenes::CameraPath path_;
  double frameSeconds_;
  float aspect_;
  sim::FramePipeline pipeline_;
};

}  // namespace study
