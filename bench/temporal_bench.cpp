// Temporal benchmark: every registered temporal pass over a sequence at 1920x1080 on the jitter
// schedule it is built for (study::SequenceRenderer: camera path, moving meshes, velocities),
// timed per frame under each dispatch strategy with counters on. Prints the median milliseconds
// per frame, the history bytes per pixel and the estimated time of the last frame, and exits 1
// unless the strategies' images match on every frame and one thread gives the same sequence.

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include "bench/bench_util.h"
#include "passes/compare.h"
#include "passes/registry.h"
#include "raster/jitter_schedule.h"
#include "scenes/motion.h"
#include "scenes/scene.h"
#include "study/sequence.h"
#include "sim/host_memory.h"

namespace {

constexpr int kWidth = 1920;
constexpr int kHeight = 1080;

struct BenchOptions {
  std::string scene = "builtin:wheel";
  std::string cameraPath = "orbit";
  std::string gpu = std::string(sim::kDefaultGpuName);
  int frames = 8;
  int threads = tbb::info::default_concurrency();
  std::string json;
  std::vector<std::string> passes;  // empty: every registered temporal pass
  bool dispatchTimes = false;
};

struct DispatchTime {
  std::string name;
  double ms = 0.0;
};

struct FrameResult {
  std::vector<passes::PassOutput> outputs;        // per strategy (released once checked, in the timed run)
  std::vector<double> ms;                          // per strategy
  std::vector<std::uint64_t> historyBytes;         // per strategy
  std::vector<double> estimatedMicroseconds;       // per strategy
  std::vector<std::vector<DispatchTime>> dispatches;  // per strategy, in order
};

double MsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

struct Sequence {
  scenes::Scene scene;
  study::FrameScene frame;
};

// The pass over the sequence, one instance per strategy, with `threads` host threads. Each
// frame's results go to frameDone(k, result) before the next frame runs, so a caller that lets
// them go keeps the timed frames on reused host memory, as a renderer reuses its targets (holding
// every frame's outputs made each frame fault in fresh pages: docs/PERFORMANCE.md, stop 26).
void RunPass(const passes::RegisteredPass& registered, const Sequence& sequence, const BenchOptions& options,
             int threads, const std::function<void(int, FrameResult&)>& frameDone) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const passes::PassInfo& info = registered.info();
  const int samples = std::max(1, raster::JitterScheduleSamples(info.jitter));
  sim::FrameSettings settings;
  settings.eqaa = {samples, samples, samples};
  settings.pattern = raster::MakeBuiltinPattern("standard", samples);
  sim::Machine machine(sim::GpuConfigByName(options.gpu));
  study::SequenceConfig config;
  config.frames = options.frames;
  config.cameraPath.kind = scenes::ParseCameraPathKind(options.cameraPath);
  study::SequenceRenderer renderer(machine, sequence.scene, sequence.frame, settings,
                                   raster::JitterSchedule::Make(info.jitter, settings.pattern), config);
  std::vector<std::unique_ptr<passes::Pass>> instances;
  for (std::size_t s = 0; s < info.strategies.size(); ++s) instances.push_back(registered.make(passes::PassSettings(info.name, info.settings)));
  for (int k = 0; k < options.frames; ++k) {
    renderer.Render(k);
    machine.ClearReports();
    FrameResult result;
    for (std::size_t s = 0; s < info.strategies.size(); ++s) {
      const auto start = std::chrono::steady_clock::now();
      result.outputs.push_back(instances[s]->Run(machine, renderer.Inputs(), info.strategies[s]));
      result.ms.push_back(MsSince(start));
      std::uint64_t history = 0;
      double estimate = 0.0;
      std::vector<DispatchTime>& dispatches = result.dispatches.emplace_back();
      for (const sim::DispatchReport& report : machine.TakeReports()) {
        estimate += report.time.totalMicroseconds;
        dispatches.push_back({report.name, report.hostMilliseconds});
        for (const sim::ResourceTraffic& traffic : report.resources) {
          if (passes::IsHistoryResource(traffic.name)) history += traffic.bytesRead + traffic.bytesWritten;
        }
      }
      result.historyBytes.push_back(history);
      result.estimatedMicroseconds.push_back(estimate);
    }
    frameDone(k, result);
  }
}

// Host time of each dispatch of the last frame under strategy s, and the pass's time outside them.
void PrintDispatchTimes(const FrameResult& frame, std::size_t s) {
  double inDispatches = 0.0;
  for (const DispatchTime& dispatch : frame.dispatches[s]) {
    std::printf("    %-40s %8.1f ms (last frame)\n", dispatch.name.c_str(), dispatch.ms);
    inDispatches += dispatch.ms;
  }
  std::printf("    %-40s %8.1f ms (last frame)\n", "outside dispatches", frame.ms[s] - inDispatches);
}

bool StrategiesIdentical(const FrameResult& frame) {
  for (const passes::PassOutput& output : frame.outputs) {
    if (!passes::CompareOutputs(frame.outputs.front(), output).Identical()) return false;
  }
  return true;
}

bool SameFrame(const FrameResult& a, const FrameResult& b) {
  for (std::size_t s = 0; s < a.outputs.size(); ++s) {
    if (!passes::CompareOutputs(a.outputs[s], b.outputs[s]).Identical()) return false;
    if (a.historyBytes[s] != b.historyBytes[s]) return false;
  }
  return true;
}

int RunBench(const BenchOptions& options) {
  const float aspect = static_cast<float>(kWidth) / static_cast<float>(kHeight);
  Sequence sequence{scenes::LoadScene(options.scene, aspect), {}};
  sequence.frame = study::ToFrameScene(sequence.scene, aspect);
  std::printf("aasim temporal bench: %s, camera %s, %dx%d, %d frames, %s, %d threads; ms per frame, median over "
              "frames 1.. (frame 0 has no history)\n",
              options.scene.c_str(), options.cameraPath.c_str(), kWidth, kHeight, options.frames,
              options.gpu.c_str(), options.threads);
  nlohmann::ordered_json passesJson = nlohmann::ordered_json::array();
  bool allGood = true;
  for (const passes::RegisteredPass& registered : passes::AllPasses()) {
    const passes::PassInfo& info = registered.info();
    if (!info.temporal || !bench::Selected(options.passes, info.name)) continue;
    // The one-thread run first, untimed and kept whole: each timed frame is checked against it
    // and against the other strategy, then released.
    std::vector<FrameResult> oneThread;
    RunPass(registered, sequence, options, 1, [&](int, FrameResult& result) { oneThread.push_back(std::move(result)); });
    std::vector<FrameResult> frames;
    bool identical = true, deterministic = true;
    RunPass(registered, sequence, options, options.threads, [&](int k, FrameResult& result) {
      identical = identical && StrategiesIdentical(result);
      deterministic = deterministic && SameFrame(oneThread[static_cast<std::size_t>(k)], result);
      result.outputs.clear();
      frames.push_back(std::move(result));
    });
    allGood = allGood && identical && deterministic;
    nlohmann::ordered_json strategies = nlohmann::ordered_json::object();
    for (std::size_t s = 0; s < info.strategies.size(); ++s) {
      std::vector<double> ms;
      for (std::size_t k = 1; k < frames.size(); ++k) ms.push_back(frames[k].ms[s]);
      const FrameResult& last = frames.back();
      const std::string strategy(passes::StrategyName(info.strategies[s]));
      std::printf("  %-22s [%s] schedule %-15s %8.1f ms/frame  history %5.2f B/px  estimated %7.1f us\n",
                  std::string(info.name).c_str(), strategy.c_str(), std::string(info.jitter).c_str(),
                  bench::Median(ms), static_cast<double>(last.historyBytes[s]) / (double(kWidth) * kHeight),
                  last.estimatedMicroseconds[s]);
      if (options.dispatchTimes) PrintDispatchTimes(last, s);
      strategies[strategy] = {{"ms_per_frame", ms},
                              {"history_bytes_last_frame", last.historyBytes[s]},
                              {"estimated_us_last_frame", last.estimatedMicroseconds[s]}};
    }
    passesJson.push_back({{"name", info.name}, {"schedule", info.jitter}, {"strategies", strategies},
                          {"identical_images", identical}, {"deterministic", deterministic}});
    std::printf("    identical images on every frame: %s; deterministic (1 vs %d threads): %s\n",
                identical ? "yes" : "no", options.threads, deterministic ? "yes" : "no");
  }
  if (!options.json.empty()) {
    std::ofstream file(options.json);
    file << nlohmann::ordered_json({{"schema", "aasim.bench.temporal"}, {"version", 1}, {"scene", options.scene},
                                    {"camera_path", options.cameraPath}, {"width", kWidth}, {"height", kHeight},
                                    {"frames", options.frames}, {"threads", options.threads}, {"passes", passesJson}})
                .dump(2)
         << '\n';
    if (!file) throw std::runtime_error(options.json + ": cannot write JSON");
  }
  return allGood ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  sim::KeepFreedHostMemory();  // frame-sized buffers reused, not re-faulted (sim/host_memory.h)
  CLI::App app{"Temporal benchmark: every registered temporal pass over a 1920x1080 sequence on its jitter schedule, "
               "per frame and strategy; exits 1 unless the strategies' images match on every frame and 1 thread "
               "gives the same sequence",
               "aasim_temporal_bench"};
  BenchOptions options;
  app.add_option("--scene", options.scene, "glTF file or builtin:NAME")->capture_default_str();
  app.add_option("--camera-path", options.cameraPath, "still, orbit, pan or dolly")
      ->check(CLI::IsMember(scenes::CameraPathKindNames()))
      ->capture_default_str();
  app.add_option("--gpu", options.gpu, "GPU configuration: a built-in name or a file")->capture_default_str();
  app.add_option("--frames", options.frames, "Frames of the sequence (frame 0 is not timed)")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  app.add_option("--threads", options.threads, "Worker threads [default: all cores]")->check(CLI::Range(1, 1024));
  app.add_option("--pass", options.passes, "Time only this registered temporal pass (repeatable) [default: every one]")
      ->type_name("NAME")
      ->check([](const std::string& name) {
        try {
          return passes::PassByName(name).info().temporal ? std::string() : name + " is not a temporal pass";
        } catch (const std::exception& error) {
          return std::string(error.what());
        }
      });
  app.add_flag("--dispatch-times", options.dispatchTimes,
               "Also print each dispatch's host time in the last frame, and the pass's time outside them");
  app.add_option("--json", options.json, "Also write the results as JSON to FILE")->type_name("FILE");
  return bench::ParseAndRun(app, argc, argv, [&] { return RunBench(options); });
}
