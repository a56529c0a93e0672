// Raster benchmark: times surface clear + raster::Rasterize on a real glTF scene at 1920x1080
// for S = 1, 4, 8, 16 (Z = min(S, 8)), and checks that one thread and all threads produce
// identical counters and depth (DESIGN.md "Conventions": determinism whatever the threads).

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include "cli/counters_json.h"
#include "bench/bench_util.h"
#include "study/frame_scene.h"
#include "raster/limits.h"
#include "raster/rasterizer.h"
#include "raster/sample_pattern.h"
#include "scenes/scene.h"
#include "sim/host_memory.h"

namespace {

constexpr int kWidth = 1920;
constexpr int kHeight = 1080;
constexpr int kSampleCounts[] = {1, 4, 8, 16};
constexpr const char* kPattern = "standard";

struct BenchOptions {
  std::string scene =
      "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  int frames = 5;
  int threads = tbb::info::default_concurrency();
  std::string json;
};

struct Frame {
  raster::RasterCounters counters;
  std::vector<std::uint32_t> depthBits;  // AnchorDepth of every pixel and anchor, as bits
};

struct ConfigResult {
  int samples = 0;
  int depthSamples = 0;
  double warmUpMs = 0.0;
  std::vector<double> frameMs;
  double medianMs = 0.0;
  raster::RasterCounters counters;
  bool deterministic = false;
};

// A frame loop keeps one Rasterizer, so its buffers are paged in once, not every frame.
const raster::RasterResult& RenderFrame(const study::ClipSpaceScene& clip,
                                        raster::DepthStencilSurface& surface,
                                        raster::Rasterizer& rasterizer) {
  const raster::DepthSurfaceConfig& config = surface.Config();
  surface.Clear(config.clearDepth, config.clearStencil);
  return rasterizer.Run(clip.DrawInput(), raster::DrawState{}, surface);
}

Frame CaptureFrame(const study::ClipSpaceScene& clip, raster::DepthStencilSurface& surface,
                   int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));
  raster::Rasterizer rasterizer;
  Frame frame{RenderFrame(clip, surface, rasterizer).counters, {}};
  const raster::DepthSurfaceConfig& config = surface.Config();
  frame.depthBits.reserve(std::size_t(config.width) * config.height * config.depthSamples);
  for (int y = 0; y < config.height; ++y) {
    for (int x = 0; x < config.width; ++x) {
      for (int anchor = 0; anchor < config.depthSamples; ++anchor) {
        frame.depthBits.push_back(std::bit_cast<std::uint32_t>(surface.AnchorDepth(x, y, anchor)));
      }
    }
  }
  return frame;
}

double TimeFrame(const study::ClipSpaceScene& clip, raster::DepthStencilSurface& surface,
                 raster::Rasterizer& rasterizer) {
  const auto start = std::chrono::steady_clock::now();
  RenderFrame(clip, surface, rasterizer);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// The warm-up frame pages in the surface and the thread pool; it is reported, not counted.
void TimeFrames(const study::ClipSpaceScene& clip, raster::DepthStencilSurface& surface,
                const BenchOptions& options, ConfigResult& result) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(options.threads));
  raster::Rasterizer rasterizer;
  result.warmUpMs = TimeFrame(clip, surface, rasterizer);
  for (int frame = 0; frame < options.frames; ++frame) {
    result.frameMs.push_back(TimeFrame(clip, surface, rasterizer));
  }
}

ConfigResult RunConfig(const study::ClipSpaceScene& clip, const BenchOptions& options, int samples) {
  ConfigResult result;
  result.samples = samples;
  result.depthSamples = std::min(samples, raster::kMaxDepthSamples);
  raster::DepthStencilSurface surface({.width = kWidth,
                                       .height = kHeight,
                                       .coverageSamples = samples,
                                       .depthSamples = result.depthSamples},
                                      raster::MakeBuiltinPattern(kPattern, samples));
  TimeFrames(clip, surface, options, result);
  result.medianMs = bench::Median(result.frameMs);
  const Frame single = CaptureFrame(clip, surface, 1);
  const Frame all = CaptureFrame(clip, surface, tbb::info::default_concurrency());
  result.counters = all.counters;
  result.deterministic = single.counters == all.counters && single.depthBits == all.depthBits;
  return result;
}

double PerSecond(std::uint64_t count, double ms) {
  return ms > 0.0 ? static_cast<double>(count) / (ms / 1000.0) : 0.0;
}

void PrintTable(const BenchOptions& options, std::size_t triangles,
                const std::vector<ConfigResult>& results) {
  std::printf(
      "aasim raster bench: %s (%zu triangles), %dx%d, pattern %s, depth less, "
      "%d threads, median of %d frames\n",
      options.scene.c_str(), triangles, kWidth, kHeight, kPattern, options.threads, options.frames);
  std::printf("%3s %3s %10s %18s %18s %14s\n", "S", "Z", "median ms", "covered Msmp/s",
              "tested Msmp/s", "deterministic");
  for (const ConfigResult& r : results) {
    std::printf("%3d %3d %10.2f %18.1f %18.1f %14s\n", r.samples, r.depthSamples, r.medianMs,
                PerSecond(r.counters.samplesCovered, r.medianMs) / 1e6,
                PerSecond(r.counters.samplesTested, r.medianMs) / 1e6,
                r.deterministic ? "yes" : "no");
  }
}

nlohmann::ordered_json ResultsJson(const BenchOptions& options, std::size_t triangles,
                                   const std::vector<ConfigResult>& results, bool deterministic) {
  nlohmann::ordered_json configs = nlohmann::ordered_json::array();
  for (const ConfigResult& r : results) {
    configs.push_back(
        {{"samples", r.samples},
         {"depth_samples", r.depthSamples},
         {"warmup_ms", r.warmUpMs},
         {"frame_ms", r.frameMs},
         {"median_ms", r.medianMs},
         {"covered_samples_per_second", PerSecond(r.counters.samplesCovered, r.medianMs)},
         {"tested_samples_per_second", PerSecond(r.counters.samplesTested, r.medianMs)},
         {"deterministic", r.deterministic},
         {"counters", cli::CountersJson(r.counters)}});
  }
  return {{"schema", "aasim.bench.raster"},
          {"version", 1},
          {"scene", options.scene},
          {"triangles", triangles},
          {"width", kWidth},
          {"height", kHeight},
          {"pattern", kPattern},
          {"depth_func", "less"},
          {"threads", options.threads},
          {"frames", options.frames},
          {"configs", configs},
          {"deterministic", deterministic}};
}

int RunBench(const BenchOptions& options) {
  // Opened first so an unwritable --json fails before minutes of benchmarking, not after.
  std::ofstream jsonFile;
  if (!options.json.empty()) {
    jsonFile.open(options.json);
    if (!jsonFile) throw std::runtime_error(options.json + ": cannot write JSON");
  }
  const float aspect = static_cast<float>(kWidth) / static_cast<float>(kHeight);
  const study::ClipSpaceScene clip =
      study::ToClipSpace(scenes::LoadScene(options.scene, aspect), aspect);
  std::vector<ConfigResult> results;
  for (const int samples : kSampleCounts) results.push_back(RunConfig(clip, options, samples));
  const bool deterministic = std::all_of(results.begin(), results.end(),
                                         [](const ConfigResult& r) { return r.deterministic; });
  PrintTable(options, clip.TriangleCount(), results);
  std::printf("deterministic: %s\n", deterministic ? "yes" : "no");
  if (jsonFile.is_open()) {
    jsonFile << ResultsJson(options, clip.TriangleCount(), results, deterministic).dump(2) << '\n';
    jsonFile.close();
    if (!jsonFile) throw std::runtime_error(options.json + ": cannot write JSON");
  }
  return deterministic ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  sim::KeepFreedHostMemory();  // frame-sized buffers reused, not re-faulted (sim/host_memory.h)
  CLI::App app{
      "Raster benchmark: surface clear + Rasterize at 1920x1080, standard pattern, "
      "depth less, for S = 1, 4, 8, 16 (Z = min(S, 8)); exits 1 unless 1 thread and all "
      "threads give identical counters and depth",
      "aasim_bench"};
  BenchOptions options;
  app.add_option("--scene", options.scene, "glTF file or builtin:NAME")
      ->type_name("FILE|builtin:NAME")
      ->capture_default_str();
  app.add_option("--frames", options.frames, "Timed frames per configuration, after one warm-up")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--threads", options.threads,
                 "Worker threads for the timed frames [default: all cores]")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  app.add_option("--json", options.json, "Also write the results as JSON to FILE")
      ->type_name("FILE");
  return bench::ParseAndRun(app, argc, argv, [&] { return RunBench(options); });
}
