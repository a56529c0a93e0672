// Resolve benchmark: the EQAA surface's resolves at 1920x1080 on a real glTF scene — the frame's
// box resolve and every registered resolve (passes/resolve.h) on every mode it reads — with
// host time (median), what each read per pixel, and its estimated GPU time; exits 1 unless a
// resolve's image and counters are identical between one thread and all threads.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include "bench/bench_util.h"
#include "cli/run_options.h"
#include "passes/resolve.h"
#include "raster/sample_pattern.h"
#include "scenes/scene.h"
#include "sim/eqaa_resolve.h"
#include "sim/frame.h"
#include "study/frame_scene.h"
#include "sim/host_memory.h"

namespace {

constexpr int kWidth = 1920;
constexpr int kHeight = 1080;

struct BenchOptions {
  std::string scene = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  std::string gpu = std::string(sim::kDefaultGpuName);
  std::string modes = "8S/8Z/1F,16S/8Z/1F,4S/4Z/1F,8S/4Z/2F";
  std::string pattern = "eqaa";
  int repeats = 3;
  int threads = tbb::info::default_concurrency();
  std::string json;
};

struct Timed {
  std::vector<double> ms;
  sim::Texture2D<glm::vec4> image{"resolve", 1, 1};
  std::vector<sim::DispatchReport> reports;
};

// One resolve run `repeats` times with `threads` host threads; the reports are the last run's.
template <typename Run>
Timed TimeResolve(sim::Machine& machine, int repeats, int threads, Run&& run) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  Timed timed;
  for (int i = 0; i < repeats; ++i) {
    machine.ClearReports();
    const auto start = std::chrono::steady_clock::now();
    timed.image = run();
    timed.ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  timed.reports = machine.TakeReports();
  return timed;
}

bool SameResult(const Timed& a, const Timed& b) {
  if (a.reports.size() != b.reports.size()) return false;
  for (std::size_t i = 0; i < a.reports.size(); ++i) {
    if (!a.reports[i].SameSimulation(b.reports[i])) return false;
  }
  const auto ta = a.image.Texels(), tb = b.image.Texels();
  return std::equal(ta.begin(), ta.end(), tb.begin(), tb.end());
}

std::uint64_t BytesRead(const std::vector<sim::DispatchReport>& reports) {
  std::uint64_t bytes = 0;
  for (const sim::DispatchReport& report : reports) {
    for (const sim::ResourceTraffic& traffic : report.resources) bytes += traffic.bytesRead;
  }
  return bytes;
}

double EstimatedUs(const std::vector<sim::DispatchReport>& reports) {
  double us = 0.0;
  for (const sim::DispatchReport& report : reports) us += report.time.totalMicroseconds;
  return us;
}

int RunBench(const BenchOptions& options) {
  const float aspect = static_cast<float>(kWidth) / static_cast<float>(kHeight);
  const study::FrameScene scene = study::ToFrameScene(scenes::LoadScene(options.scene, aspect), aspect);
  const sim::GpuConfig gpu = sim::GpuConfigByName(options.gpu);
  std::printf("aasim resolve bench: %s, %dx%d, %s, %d threads, median of %d runs (host ms; GPU µs are "
              "timing-model estimates)\n",
              options.scene.c_str(), kWidth, kHeight, gpu.name.c_str(), options.threads, options.repeats);
  std::printf("  %-10s %-12s %10s %10s %12s %14s\n", "mode", "resolve", "host ms", "1-thread", "read B/px", "estimated µs");
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  bool deterministic = true;
  for (const fmask::EqaaConfig& mode : cli::ParseEqaaModes(options.modes)) {
    sim::Machine machine(gpu);
    sim::FrameSettings settings;
    settings.eqaa = mode;
    settings.pattern = raster::ResolvePattern(options.pattern, mode.coverageSamples);
    sim::FramePipeline pipeline(machine, settings);
    pipeline.Render(scene.Geometry());
    auto bench = [&](const std::string& name, auto&& run) {
      const Timed all = TimeResolve(machine, options.repeats, options.threads, run);
      const Timed one = TimeResolve(machine, 1, 1, run);
      const bool same = SameResult(all, one);
      deterministic = deterministic && same;
      const double pixels = double(kWidth) * kHeight;
      const std::vector<sim::DispatchReport>& lastRun = all.reports;
      std::printf("  %-10s %-12s %10.1f %10.1f %12.2f %14.1f%s\n", fmask::EqaaName(mode).c_str(), name.c_str(),
                  bench::Median(all.ms), one.ms.front(), double(BytesRead(lastRun)) / pixels, EstimatedUs(lastRun),
                  same ? "" : "  NOT DETERMINISTIC");
      results.push_back({{"mode", fmask::EqaaName(mode)}, {"resolve", name}, {"host_ms_median", bench::Median(all.ms)},
                         {"host_ms_one_thread", one.ms.front()}, {"bytes_read_per_pixel", double(BytesRead(lastRun)) / pixels},
                         {"estimated_us", EstimatedUs(lastRun)}, {"deterministic", same}});
    };
    bench("box", [&] {
      sim::Texture2D<glm::vec4> out("box", kWidth, kHeight, 4);
      sim::RunBoxResolve(machine, pipeline.Eqaa(), out, "resolve/box");
      return out;
    });
    const passes::ResolveContext context{.pattern = &settings.pattern, .tableCache = std::nullopt};
    for (const passes::RegisteredResolve& registered : passes::AllResolves()) {
      if (!registered.info().reads(mode)) continue;
      const std::unique_ptr<passes::Resolve> resolve = registered.make(context);
      bench(std::string(registered.info().name), [&] { return resolve->Run(machine, pipeline.Eqaa()); });
    }
  }
  if (!options.json.empty()) {
    std::ofstream file(options.json);
    if (!file) throw std::runtime_error(options.json + ": cannot write JSON");
    file << nlohmann::ordered_json{{"scene", options.scene}, {"gpu", gpu.name}, {"threads", options.threads},
                                   {"results", results}}
                .dump(2)
         << '\n';
  }
  std::printf("deterministic (1 thread vs %d): %s\n", options.threads, deterministic ? "yes" : "NO");
  return deterministic ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  sim::KeepFreedHostMemory();  // frame-sized buffers reused, not re-faulted (sim/host_memory.h)
  CLI::App app{"Resolve benchmark: the box resolve and every registered resolve of the EQAA surface on every mode "
               "it reads at 1920x1080; exits 1 unless one thread and all threads give identical images and counters",
               "aasim_resolve_bench"};
  BenchOptions options;
  app.add_option("--scene", options.scene, "glTF file or builtin:NAME")->type_name("FILE|builtin:NAME")->capture_default_str();
  app.add_option("--gpu", options.gpu, "GPU configuration: a built-in name or a file")->capture_default_str();
  app.add_option("--modes", options.modes, "EQAA modes, comma-separated S/Z/F")->capture_default_str();
  app.add_option("--pattern", options.pattern, "Sample pattern: a built-in name or a JSON file")->capture_default_str();
  app.add_option("--repeats", options.repeats, "Timed runs per resolve")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--threads", options.threads, "Worker threads for the timed runs [default: all cores]")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  app.add_option("--json", options.json, "Also write the results as JSON to FILE")->type_name("FILE");
  return bench::ParseAndRun(app, argc, argv, [&] { return RunBench(options); });
}
