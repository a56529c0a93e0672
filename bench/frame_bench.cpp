// Frame benchmark: times the frame pipeline (draw with the material kernel into an EQAA surface,
// box resolve) and every registered post pass under each of its dispatch strategies on a real
// glTF scene at 1920x1080, prints each pass's studied dispatch under both strategies side by
// side, and checks that the strategies' images match and that one thread and all threads give
// identical counters and images.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include "bench/bench_util.h"
#include "study/frame_scene.h"
#include "passes/compare.h"
#include "passes/registry.h"
#include "raster/sample_pattern.h"
#include "scenes/scene.h"
#include "sim/frame.h"
#include "sim/host_memory.h"

namespace {

constexpr int kWidth = 1920;
constexpr int kHeight = 1080;

struct BenchOptions {
  std::string scene = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  std::string gpu = std::string(sim::kDefaultGpuName);
  int frames = 3;
  int threads = tbb::info::default_concurrency();
  std::string json;
  std::vector<std::string> passes;  // empty: every registered pass
  bool dispatchTimes = false;
};

// One run of a pass under one strategy.
struct StrategyRun {
  passes::Strategy strategy;
  passes::PassOutput output;
  double ms = 0.0;
  std::size_t firstDispatch = 0, endDispatch = 0;
};

// One frame: its reports and the images that must not depend on the thread count.
struct FrameRun {
  std::vector<sim::DispatchReport> reports;
  std::vector<glm::vec4> colour;
  double frameMs = 0.0;
  std::vector<std::vector<StrategyRun>> passes;  // per registered pass, per strategy
};

double MsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Pass instances per registered pass and strategy. The timed frames reuse one set, as a renderer
// keeps its passes and their render targets from frame to frame; the determinism check runs one
// frame on a fresh set with one thread and another with all threads.
using PassInstances = std::vector<std::vector<std::unique_ptr<passes::Pass>>>;

PassInstances MakeInstances() {
  PassInstances instances;
  for (const passes::RegisteredPass& registered : passes::AllPasses()) {
    const passes::PassInfo& info = registered.info();
    std::vector<std::unique_ptr<passes::Pass>>& perStrategy = instances.emplace_back();
    for (std::size_t s = 0; s < info.strategies.size(); ++s) {
      perStrategy.push_back(registered.make(passes::PassSettings(info.name, info.settings)));
    }
  }
  return instances;
}

std::vector<StrategyRun> RunPass(const passes::PassInfo& info, std::vector<std::unique_ptr<passes::Pass>>& instances,
                                 sim::Machine& machine, const sim::FramePipeline& pipeline) {
  std::vector<StrategyRun> runs;
  for (std::size_t s = 0; s < info.strategies.size(); ++s) {
    const passes::Strategy strategy = info.strategies[s];
    StrategyRun run{.strategy = strategy, .output = {}, .firstDispatch = machine.Reports().size()};
    const auto start = std::chrono::steady_clock::now();
    run.output = instances[s]->Run(machine, passes::FrameInputsOf(pipeline), strategy);
    run.ms = MsSince(start);
    run.endDispatch = machine.Reports().size();
    runs.push_back(std::move(run));
  }
  return runs;
}

// A pass reading an S-sample EQAA surface (SMAA S2x) gets its own frame: {S, S, S} with the
// standard pattern, rendered untimed before it runs.
sim::FrameSettings SettingsFor(int eqaaSamples) {
  sim::FrameSettings settings;
  if (eqaaSamples != 0) {
    settings.eqaa = {eqaaSamples, eqaaSamples, eqaaSamples};
    settings.pattern = raster::MakeBuiltinPattern("standard", eqaaSamples);
  }
  return settings;
}

FrameRun RunFrame(const BenchOptions& options, const sim::FrameGeometry& geometry, sim::Machine& machine,
                  sim::FramePipeline& pipeline, PassInstances& instances) {
  FrameRun run;
  machine.ClearReports();
  const auto start = std::chrono::steady_clock::now();
  pipeline.Render(geometry);
  run.frameMs = MsSince(start);
  const std::span<const passes::RegisteredPass> registered = passes::AllPasses();
  for (std::size_t p = 0; p < registered.size(); ++p) {
    const passes::PassInfo& info = registered[p].info();
    const int samples = info.eqaaSamples;
    if (!bench::Selected(options.passes, info.name)) {
      run.passes.emplace_back();
      continue;
    }
    if (samples == 0 || samples == pipeline.Settings().eqaa.coverageSamples) {
      run.passes.push_back(RunPass(info, instances[p], machine, pipeline));
      continue;
    }
    sim::FramePipeline own(machine, SettingsFor(samples));
    own.Render(geometry);
    run.passes.push_back(RunPass(info, instances[p], machine, own));
  }
  run.reports = machine.Reports();
  run.colour = {pipeline.Colour().Texels().begin(), pipeline.Colour().Texels().end()};
  return run;
}

bool SameRun(const FrameRun& a, const FrameRun& b) {
  if (a.reports.size() != b.reports.size() || a.colour != b.colour) return false;
  for (std::size_t i = 0; i < a.reports.size(); ++i) {
    if (!a.reports[i].SameSimulation(b.reports[i])) return false;
  }
  for (std::size_t p = 0; p < a.passes.size(); ++p) {
    for (std::size_t s = 0; s < a.passes[p].size(); ++s) {
      if (!passes::CompareOutputs(a.passes[p][s].output, b.passes[p][s].output).Identical()) return false;
    }
  }
  return true;
}

bool StrategiesIdentical(const std::vector<StrategyRun>& runs) {
  for (const StrategyRun& run : runs) {
    if (!passes::CompareOutputs(runs.front().output, run.output).Identical()) return false;
  }
  return true;
}

FrameRun CaptureFrame(const BenchOptions& options, const sim::FrameGeometry& geometry, const sim::GpuConfig& gpu,
                      int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  sim::Machine machine(gpu);
  sim::FramePipeline pipeline(machine, sim::FrameSettings{});
  PassInstances fresh = MakeInstances();
  return RunFrame(options, geometry, machine, pipeline, fresh);
}

const sim::DispatchReport* Find(const FrameRun& frame, const StrategyRun& run, std::string_view name) {
  for (std::size_t i = run.firstDispatch; i < run.endDispatch; ++i) {
    if (frame.reports[i].name == name) return &frame.reports[i];
  }
  return nullptr;
}

double Percent(std::uint64_t part, std::uint64_t whole) {
  return whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

// The pass's first studied dispatch under its first two strategies, side by side.
void PrintComparison(const FrameRun& frame, const passes::PassInfo& info, const std::vector<StrategyRun>& runs) {
  if (runs.size() < 2) return;
  const std::string_view studied = info.studiedDispatches.front();
  const sim::DispatchReport* left = Find(frame, runs[0], studied);
  const sim::DispatchReport* right = Find(frame, runs[1], studied);
  if (left == nullptr || right == nullptr) throw std::logic_error("no dispatch " + std::string(studied));
  std::printf("%-19.*s %14s %14s\n", static_cast<int>(studied.size()), studied.data(),
              std::string(passes::StrategyName(runs[0].strategy)).c_str(),
              std::string(passes::StrategyName(runs[1].strategy)).c_str());
  auto row = [](const char* label, double a, double b, const char* format) {
    std::printf("  %-18s", label);
    std::printf(format, a);
    std::printf(format, b);
    std::printf("\n");
  };
  const sim::LaneCounters &l = left->lanes, &r = right->lanes;
  row("waves", static_cast<double>(l.waves), static_cast<double>(r.waves), " %14.0f");
  row("lanes launched", static_cast<double>(l.lanesLaunched), static_cast<double>(r.lanesLaunched), " %14.0f");
  row("lanes active", static_cast<double>(l.lanesActive), static_cast<double>(r.lanesActive), " %14.0f");
  row("utilization %", Percent(l.lanesActive, l.lanesLaunched), Percent(r.lanesActive, r.lanesLaunched), " %14.1f");
  row("DRAM KB", static_cast<double>(left->DramBytes()) / 1024.0, static_cast<double>(right->DramBytes()) / 1024.0,
      " %14.1f");
  row("estimated us", left->time.totalMicroseconds, right->time.totalMicroseconds, " %14.1f");
}

// Host time of each dispatch of the last timed frame: where a pass's time goes, the rest of its
// time being host work outside dispatches.
void PrintDispatchTimes(const FrameRun& frame, const StrategyRun& run) {
  double inDispatches = 0.0;
  for (std::size_t i = run.firstDispatch; i < run.endDispatch; ++i) {
    const sim::DispatchReport& report = frame.reports[i];
    std::printf("    %-40s %8.1f ms (last frame)\n", report.name.c_str(), report.hostMilliseconds);
    inDispatches += report.hostMilliseconds;
  }
  std::printf("    %-40s %8.1f ms (last frame)\n", "outside dispatches", run.ms - inDispatches);
}

int RunBench(const BenchOptions& options) {
  std::ofstream jsonFile;
  if (!options.json.empty()) {
    jsonFile.open(options.json);
    if (!jsonFile) throw std::runtime_error(options.json + ": cannot write JSON");
  }
  const float aspect = static_cast<float>(kWidth) / static_cast<float>(kHeight);
  const study::FrameScene scene = study::ToFrameScene(scenes::LoadScene(options.scene, aspect), aspect);
  const sim::FrameGeometry geometry = scene.Geometry();
  const sim::GpuConfig gpu = sim::GpuConfigByName(options.gpu);

  std::vector<double> frameMs;
  // Per pass, per strategy: the timed runs.
  std::vector<std::vector<std::vector<double>>> passMs;
  FrameRun last;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(options.threads));
    sim::Machine machine(gpu);
    sim::FramePipeline pipeline(machine, sim::FrameSettings{});
    PassInstances instances = MakeInstances();
    // A frame's results are released before the next frame runs, so each timed frame reuses the
    // host memory of the one before, as a renderer reuses its targets. Keeping the warm-up's
    // results (or the last frame's while the next ran) made the first two timed frames fault in
    // fresh pages for every pass output: up to three times the steady time (docs/PERFORMANCE.md).
    std::printf("warm-up frame: %.1f ms (not counted)\n",
                RunFrame(options, geometry, machine, pipeline, instances).frameMs);
    for (int frame = 0; frame < options.frames; ++frame) {
      last = FrameRun{};
      last = RunFrame(options, geometry, machine, pipeline, instances);
      frameMs.push_back(last.frameMs);
      passMs.resize(last.passes.size());
      for (std::size_t p = 0; p < last.passes.size(); ++p) {
        passMs[p].resize(last.passes[p].size());
        for (std::size_t s = 0; s < last.passes[p].size(); ++s) passMs[p][s].push_back(last.passes[p][s].ms);
      }
    }
  }
  // Fresh instances on both sides: the timed frames' temporal passes carry history from the frames
  // before, which a single fresh frame cannot have.
  const bool deterministic =
      SameRun(CaptureFrame(options, geometry, gpu, 1), CaptureFrame(options, geometry, gpu, options.threads));
  bool identicalImages = true;
  const sim::FrameSettings settings;
  std::printf("aasim frame bench: %s (%zu triangles), %dx%d, %s, %s, %d threads, median of %d frames\n",
              options.scene.c_str(), scene.clip.TriangleCount(), kWidth, kHeight,
              fmask::EqaaName(settings.eqaa).c_str(), gpu.name.c_str(), options.threads, options.frames);
  std::printf("  frame pipeline (draw + material kernel + EQAA + resolve): %8.1f ms\n", bench::Median(frameMs));
  nlohmann::ordered_json passesJson = nlohmann::ordered_json::array();
  for (std::size_t p = 0; p < last.passes.size(); ++p) {
    const passes::PassInfo& info = passes::AllPasses()[p].info();
    if (last.passes[p].empty()) continue;
    const bool identical = StrategiesIdentical(last.passes[p]);
    identicalImages = identicalImages && identical;
    nlohmann::ordered_json strategies = nlohmann::ordered_json::object();
    for (std::size_t s = 0; s < last.passes[p].size(); ++s) {
      const std::string strategy(passes::StrategyName(last.passes[p][s].strategy));
      const std::size_t dispatches = last.passes[p][s].endDispatch - last.passes[p][s].firstDispatch;
      std::printf("  %s pass [%s] (%zu dispatches): %8.1f ms\n", std::string(info.name).c_str(), strategy.c_str(),
                  dispatches, bench::Median(passMs[p][s]));
      if (options.dispatchTimes) PrintDispatchTimes(last, last.passes[p][s]);
      strategies[strategy + "_ms"] = passMs[p][s];
    }
    PrintComparison(last, info, last.passes[p]);
    passesJson.push_back({{"name", info.name}, {"strategies", strategies}, {"identical_images", identical}});
  }
  std::printf("identical images: %s; deterministic (1 vs %d threads): %s\n", identicalImages ? "yes" : "no",
              options.threads, deterministic ? "yes" : "no");
  if (jsonFile.is_open()) {
    const nlohmann::ordered_json json = {{"schema", "aasim.bench.frame"},
                                         {"version", 2},
                                         {"scene", options.scene},
                                         {"triangles", scene.clip.TriangleCount()},
                                         {"width", kWidth},
                                         {"height", kHeight},
                                         {"eqaa", fmask::EqaaName(settings.eqaa)},
                                         {"gpu", gpu.name},
                                         {"threads", options.threads},
                                         {"frames", options.frames},
                                         {"frame_ms", frameMs},
                                         {"passes", passesJson},
                                         {"identical_images", identicalImages},
                                         {"deterministic", deterministic}};
    jsonFile << json.dump(2) << '\n';
    jsonFile.close();
    if (!jsonFile) throw std::runtime_error(options.json + ": cannot write JSON");
  }
  return deterministic && identicalImages ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  sim::KeepFreedHostMemory();  // frame-sized buffers reused, not re-faulted (sim/host_memory.h)
  CLI::App app{
      "Frame benchmark: the frame pipeline and every registered post pass (each dispatch strategy) at "
      "1920x1080; exits 1 unless the strategies' images match and 1 thread and all threads give "
      "identical counters and images",
      "aasim_frame_bench"};
  BenchOptions options;
  app.add_option("--scene", options.scene, "glTF file or builtin:NAME")->type_name("FILE|builtin:NAME")->capture_default_str();
  app.add_option("--gpu", options.gpu, "GPU configuration: a built-in name or a file")->capture_default_str();
  app.add_option("--frames", options.frames, "Timed frames, after one warm-up")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--threads", options.threads, "Worker threads for the timed frames [default: all cores]")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  app.add_option("--pass", options.passes, "Time only this registered pass (repeatable) [default: every pass]")
      ->type_name("NAME")
      ->check([](const std::string& name) {
        try {
          passes::PassByName(name);
          return std::string();
        } catch (const std::exception& error) {
          return std::string(error.what());
        }
      });
  app.add_flag("--dispatch-times", options.dispatchTimes,
               "Also print each dispatch's host time in the last timed frame, and the pass's time outside them");
  app.add_option("--json", options.json, "Also write the results as JSON to FILE")->type_name("FILE");
  return bench::ParseAndRun(app, argc, argv, [&] { return RunBench(options); });
}
