// `aasim frame` (see frame_command.h): renders a scene on the machine, runs the post pass under
// each strategy and writes the output set.

#include "cli/frame_command.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
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
#include "cli/text_io.h"
#include "passes/compare.h"
#include "passes/registry.h"
#include "raster/sample_pattern.h"
#include "scenes/scene.h"
#include "sim/frame.h"
#include "sim/gpu_config.h"

namespace cli {
namespace {

struct PassRun {
  passes::Strategy strategy;
  passes::PassOutput output;
  std::size_t firstDispatch = 0, endDispatch = 0;  // [first, end) in the machine's reports
};

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
  return settings;
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

void WriteReports(OutputDir& dir, const FrameCommandOptions& options, const sim::GpuConfig& gpu,
                  std::span<const study::DispatchRecord> records, int threads) {
  for (std::size_t i = 0; i < records.size(); ++i) {
    const sim::DispatchReport& report = records[i].report;
    if (report.heat.Empty()) continue;
    const std::string stem = "heat/" + HeatMapStem(i, report.name, records[i].strategy);
    WriteHeatMap(report.heat, dir.Stage(stem + ".exr"), dir.Stage(stem + ".png"));
  }
  WriteJson(dir.Stage("dispatches.json"), DispatchReportsJson(records, gpu, ConfigurationJson(options, threads)));
  WriteText(dir.Stage("dispatches.csv"), DispatchReportsCsv(records));
}

// The study's question side by side: what the studied dispatch costs under each strategy.
void PrintComparison(std::ostream& out, std::span<const study::DispatchRecord> reports, std::string_view studied,
                     const PassRun& first, const PassRun& second, const passes::StrategyDifference& difference) {
  auto dispatches = [&](const PassRun& run) { return reports.subspan(run.firstDispatch, run.endDispatch - run.firstDispatch); };
  out << "\n" << passes::StrategyName(first.strategy) << " vs " << passes::StrategyName(second.strategy) << ": "
      << studied << " (" << first.output.workItems << " work-set pixels)\n";
  PrintDispatchComparison(out, std::string(studied), passes::StrategyName(first.strategy), dispatches(first),
                          passes::StrategyName(second.strategy), dispatches(second));
  out << "identical output: "
      << (difference.Identical() ? "yes (output and layers bit-identical)" : "NO, " + difference.Describe()) << '\n';
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
  std::vector<PassRun> passRuns;
  for (const passes::Strategy strategy : options.Strategies()) {
    // One instance per strategy, as the study makes them.
    const std::unique_ptr<passes::Pass> pass = options.pass->Make();
    const std::string strategyName(passes::StrategyName(strategy));
    PassRun run{.strategy = strategy, .output = {}, .firstDispatch = records.size()};
    run.output = pass->Run(machine, passes::FrameInputsOf(pipeline), strategy);
    study::TakeDispatches(machine, records, "", std::string(options.pass->Info().name), strategyName);
    run.endDispatch = records.size();
    passRuns.push_back(std::move(run));
  }
  passes::StrategyDifference difference;
  for (std::size_t i = 1; i < passRuns.size() && difference.Identical(); ++i) {
    difference = passes::CompareOutputs(passRuns.front().output, passRuns[i].output);
  }

  WriteImages(dir, pipeline, passRuns);
  WriteReports(dir, options, machine.Gpu(), records, threads);
  dir.Commit("dispatches.json");

  summary << "frame      " << options.scene << ", " << options.width << "x" << options.height
          << ", " << fmask::EqaaName(options.Eqaa()) << ", pattern " << options.pattern
          << ", policy " << options.policy << ", GPU " << machine.Gpu().name << "\n\n";
  PrintDispatchSummary(summary, records, machine.Gpu());
  if (passRuns.size() == 2) {
    PrintComparison(summary, records, options.pass->Info().studiedDispatches.front(), passRuns[0], passRuns[1],
                    difference);
  }
  double hostMs = 0.0;
  for (const study::DispatchRecord& record : records) hostMs += record.report.hostMilliseconds;
  summary << "\nhost time  " << std::llround(hostMs) << " ms simulating the dispatches (" << threads
          << " threads; wall time of this program, not a GPU time)\n"
          << "report: " << (dir.Path() / "dispatches.json").string() << '\n';
  if (!difference.Identical()) {
    throw std::runtime_error("--strategy both: the strategies' outputs differ (" + difference.Describe() +
                             "): a bug in " + std::string(options.pass->Info().source) + " (outputs kept in " +
                             dir.Path().string() + ")");
  }
}

}  // namespace cli
