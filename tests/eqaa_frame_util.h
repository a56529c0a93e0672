#pragma once
// A built-in scene rendered by the frame pipeline under one EQAA mode, for tests of the resolves
// that read its surface.

#include <memory>
#include <string>

#include "scenes/scene.h"
#include "sim/frame.h"
#include "sim/gpu_config.h"
#include "study/frame_scene.h"

namespace testing_eqaa {

struct RenderedFrame {
  sim::Machine machine{sim::GpuConfigByName("ps4-class")};
  raster::SamplePattern pattern = raster::MakeBuiltinPattern("eqaa", 1);
  std::unique_ptr<sim::FramePipeline> pipeline;
};

inline std::unique_ptr<RenderedFrame> RenderBuiltin(const std::string& scene, int width, int height,
                                                    fmask::EqaaConfig mode, const std::string& pattern = "eqaa") {
  auto frame = std::make_unique<RenderedFrame>();
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const study::FrameScene geometry = study::ToFrameScene(scenes::MakeBuiltinScene(scene, aspect), aspect);
  sim::FrameSettings settings;
  settings.width = width;
  settings.height = height;
  settings.eqaa = mode;
  frame->pattern = raster::ResolvePattern(pattern, mode.coverageSamples);
  settings.pattern = frame->pattern;
  frame->pipeline = std::make_unique<sim::FramePipeline>(frame->machine, settings);
  frame->pipeline->Render(geometry.Geometry());
  frame->machine.ClearReports();
  return frame;
}

}  // namespace testing_eqaa
