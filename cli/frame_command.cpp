// `aasim frame` (see frame_command.h): renders a scene on the machine, runs the post pass under
// each strategy and writes the output set.

#include "cli/frame_command.h"

#include <cstdint>
#include <string>
#include <vector>

#include <oneapi/tbb/global_control.h>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "cli/dispatch_output.h"
#include "cli/frame_output.h"
#include "study/frame_scene.h"
#include "cli/image_io.h"
#include "cli/output_dir.h"
#include "cli/pass_runs.h"
#include "passes/registry.h"
#include "raster/sample_pattern.h"
#include "scenes/scene.h"
#include "sim/frame.h"
#include "sim/gpu_config.h"

namespace cli {
namespace {

sim::FrameSettings MakeSettings(const FrameCommandOptions& options, raster::SamplePattern pattern,
                                const scenes::Lighting& lighting) {
  sim::FrameSettings settings;
  study::ApplyLighting(lighting, settings);
  settings.width = options.width;
  settings.height = options.height;
  settings.eqaa = options.Eqaa();
  settings.pattern = std::move(pattern);
  settings.policy = fmask::PolicyByName(options.policy);
  settings.flush = WaveFlushByName(options.flush);
  settings.drawOrder = options.setup.Order();
  settings.depthPrepass = options.setup.depthPrepass;
  settings.maxZPlanes = options.setup.maxZPlanes;
  return settings;
}

// The CRAA setup settings that differ from the defaults, for the summary's first line.
std::string SetupSummary(const FrameSetupOptions& setup) {
  const FrameSetupOptions defaults;
  std::string text;
  if (setup.drawOrder != defaults.drawOrder) text += ", draw order " + setup.drawOrder;
  if (setup.depthPrepass) text += ", depth pre-pass";
  if (setup.maxZPlanes != defaults.maxZPlanes) text += ", max Z planes " + std::to_string(setup.maxZPlanes);
  return text;
}

nlohmann::ordered_json ConfigurationJson(const FrameCommandOptions& options, int threads) {
  return {{"scene", options.scene},
          {"width", options.width},
          {"height", options.height},
          {"samples", options.samples},
          {"depth_samples", options.depthSamples},
          {"fragments", options.fragments},
          {"eqaa", fmask::EqaaName(options.Eqaa())},
          {"pattern", options.pattern},
          {"policy", options.policy},
          {"gpu", options.gpu},
          {"flush", options.flush},
          {"draw_order", options.setup.drawOrder},
          {"depth_prepass", options.setup.depthPrepass},
          {"max_zplanes", options.setup.maxZPlanes},
          {"post", options.pass ? nlohmann::ordered_json(options.pass->Info().name) : nlohmann::ordered_json("none")},
          {"pass_settings", options.pass ? nlohmann::ordered_json(passes::DescribeSettings(options.pass->settings))
                                         : nlohmann::ordered_json(nullptr)},
          {"strategy", options.strategy.empty() ? nlohmann::ordered_json(nullptr)
                                                : nlohmann::ordered_json(options.strategy)},
          {"threads", threads}};
}

void WriteImages(OutputDir& dir, const sim::FramePipeline& pipeline,
                 const std::vector<PassRun>& passRuns) {
  const sim::Texture2D<glm::vec4>& colour = pipeline.Colour();
  WritePng(dir.Stage("colour.png"), colour.Width(), colour.Height(), 3, SrgbImage(colour.Texels()));
  WriteFrameExr(dir.Stage("frame.exr"), pipeline);
  for (const PassRun& run : passRuns) {
    const std::string folder = "post/" + std::string(passes::StrategyName(run.strategy)) + "/";
    const sim::Texture2D<glm::vec4>& output = run.output.colour;
    WritePng(dir.Stage(folder + "output.png"), output.Width(), output.Height(), 3,
             SrgbImage(output.Texels()));
    for (const passes::PassLayer& layer : run.output.layers) WriteLayerPng(dir.Stage(folder + layer.name + ".png"), layer);
  }
}

}  // namespace

void RunFrameCommand(const FrameCommandOptions& options, std::ostream& summary) {
  const tbb::global_control threadLimit(tbb::global_control::max_allowed_parallelism,
                                        static_cast<std::size_t>(options.threads));
  const int threads = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  // Every input is read and checked before the output directory exists, so a bad input leaves
  // no directory behind.
  raster::SamplePattern pattern = raster::ResolvePattern(options.pattern, options.samples);
  sim::Machine machine(sim::GpuConfigByName(options.gpu));
  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  const scenes::Scene loaded = scenes::LoadScene(options.scene, aspect);
  const study::FrameScene scene = study::ToFrameScene(loaded, aspect);
  sim::FramePipeline pipeline(machine, MakeSettings(options, std::move(pattern), loaded.lighting));
  OutputDir dir = OpenOutOption(options.out);

  pipeline.Render(scene.Geometry());
  std::vector<study::DispatchRecord> records;
  study::TakeDispatches(machine, records, "");
  const PassRuns passRuns = options.pass ? RunUnderStrategies(machine, *options.pass, passes::FrameInputsOf(pipeline),
                                                               options.Strategies(), records)
                                        : PassRuns{};

  WriteImages(dir, pipeline, passRuns.runs);
  WriteDispatchReports(dir, records, machine.Gpu(), ConfigurationJson(options, threads));
  dir.Commit("dispatches.json");

  summary << "frame      " << options.scene << ", " << options.width << "x" << options.height
          << ", " << fmask::EqaaName(options.Eqaa()) << ", pattern " << options.pattern
          << ", policy " << options.policy << SetupSummary(options.setup) << ", GPU " << machine.Gpu().name
          << "\n\n";
  PrintDispatchSummary(summary, records, machine.Gpu());
  if (passRuns.runs.size() == 2) PrintStrategyComparison(summary, records, options.pass->Info(), passRuns);
  PrintHostTime(summary, records, threads);
  summary << "report: " << (dir.Path() / "dispatches.json").string() << '\n';
  if (options.pass) ThrowIfStrategiesDiffer(passRuns, options.pass->Info(), dir.Path());
}

}  // namespace cli
