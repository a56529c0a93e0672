// Frame benchmark: times the frame pipeline (draw with the material kernel into an EQAA surface,
// box resolve) and the demonstration post pass under both dispatch strategies on a real glTF
// scene at 1920x1080, prints the blend dispatch of each strategy side by side, and checks that
// one thread and all threads give identical counters and images.

#include <algorithm>
#include <chrono>
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

#include "bench/bench_util.h"
#include "cli/frame_input.h"
#include "passes/demo_edge_blend.h"
#include "scenes/scene.h"
#include "sim/frame.h"

namespace {

constexpr int kWidth = 1920;
constexpr int kHeight = 1080;

struct BenchOptions {
  std::string scene = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  std::string gpu = std::string(sim::kDefaultGpuName);
  int frames = 3;
  int threads = tbb::info::default_concurrency();
  std::string json;
};

// One frame: its reports and the images that must not depend on the thread count.
struct FrameRun {
  std::vector<sim::DispatchReport> reports;
  std::vector<glm::vec4> colour, stencilOutput, queueOutput;
  double frameMs = 0.0, stencilMs = 0.0, queueMs = 0.0;
};

double MsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<glm::vec4> Pixels(const sim::Texture2D<glm::vec4>& texture) {
  return {texture.Texels().begin(), texture.Texels().end()};
}

FrameRun RunFrame(const sim::FrameGeometry& geometry, sim::Machine& machine, sim::FramePipeline& pipeline) {
  FrameRun run;
  machine.ClearReports();
  auto start = std::chrono::steady_clock::now();
  pipeline.Render(geometry);
  run.frameMs = MsSince(start);
  start = std::chrono::steady_clock::now();
  const passes::DemoEdgeBlendResult stencil =
      passes::RunDemoEdgeBlend(machine, pipeline.Colour(), passes::Strategy::StencilCulled);
  run.stencilMs = MsSince(start);
  start = std::chrono::steady_clock::now();
  const passes::DemoEdgeBlendResult queue =
      passes::RunDemoEdgeBlend(machine, pipeline.Colour(), passes::Strategy::DeferredQueue);
  run.queueMs = MsSince(start);
  run.reports = machine.Reports();
  run.colour = Pixels(pipeline.Colour());
  run.stencilOutput = Pixels(stencil.output);
  run.queueOutput = Pixels(queue.output);
  return run;
}

bool SameRun(const FrameRun& a, const FrameRun& b) {
  if (a.reports.size() != b.reports.size()) return false;
  for (std::size_t i = 0; i < a.reports.size(); ++i) {
    if (!a.reports[i].SameSimulation(b.reports[i])) return false;
  }
  return a.colour == b.colour && a.stencilOutput == b.stencilOutput && a.queueOutput == b.queueOutput;
}

FrameRun CaptureFrame(const sim::FrameGeometry& geometry, const sim::GpuConfig& gpu, int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  sim::Machine machine(gpu);
  sim::FramePipeline pipeline(machine, sim::FrameSettings{});
  return RunFrame(geometry, machine, pipeline);
}

const sim::DispatchReport& Find(const std::vector<sim::DispatchReport>& reports, const std::string& name,
                                sim::DispatchKind kind) {
  for (const sim::DispatchReport& r : reports) {
    if (r.name == name && r.kind == kind) return r;
  }
  throw std::logic_error("no dispatch " + name);
}

double Percent(std::uint64_t part, std::uint64_t whole) {
  return whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

void PrintBlendComparison(const std::vector<sim::DispatchReport>& reports) {
  const sim::DispatchReport& ps = Find(reports, "demo/blend", sim::DispatchKind::FullScreen);
  const sim::DispatchReport& cs = Find(reports, "demo/blend", sim::DispatchKind::IndirectCompute);
  std::printf("demo/blend          %14s %14s\n", "stencil (PS)", "queue (CS)");
  auto row = [](const char* label, double a, double b, const char* format) {
    std::printf("  %-18s", label);
    std::printf(format, a);
    std::printf(format, b);
    std::printf("\n");
  };
  row("waves", static_cast<double>(ps.lanes.waves), static_cast<double>(cs.lanes.waves), " %14.0f");
  row("lanes launched", static_cast<double>(ps.lanes.lanesLaunched), static_cast<double>(cs.lanes.lanesLaunched),
      " %14.0f");
  row("lanes active", static_cast<double>(ps.lanes.lanesActive), static_cast<double>(cs.lanes.lanesActive), " %14.0f");
  row("utilization %", Percent(ps.lanes.lanesActive, ps.lanes.lanesLaunched),
      Percent(cs.lanes.lanesActive, cs.lanes.lanesLaunched), " %14.1f");
  row("DRAM KB", static_cast<double>(ps.DramBytes()) / 1024.0, static_cast<double>(cs.DramBytes()) / 1024.0,
      " %14.1f");
  row("estimated us", ps.time.totalMicroseconds, cs.time.totalMicroseconds, " %14.1f");
}

int RunBench(const BenchOptions& options) {
  std::ofstream jsonFile;
  if (!options.json.empty()) {
    jsonFile.open(options.json);
    if (!jsonFile) throw std::runtime_error(options.json + ": cannot write JSON");
  }
  const float aspect = static_cast<float>(kWidth) / static_cast<float>(kHeight);
  const cli::FrameScene scene = cli::ToFrameScene(scenes::LoadScene(options.scene, aspect), aspect);
  const sim::FrameGeometry geometry = scene.Geometry();
  const sim::GpuConfig gpu = sim::GpuConfigByName(options.gpu);

  std::vector<double> frameMs, stencilMs, queueMs;
  FrameRun last;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(options.threads));
    sim::Machine machine(gpu);
    sim::FramePipeline pipeline(machine, sim::FrameSettings{});
    const FrameRun warmUp = RunFrame(geometry, machine, pipeline);
    std::printf("warm-up frame: %.1f ms (not counted)\n", warmUp.frameMs + warmUp.stencilMs + warmUp.queueMs);
    for (int frame = 0; frame < options.frames; ++frame) {
      last = RunFrame(geometry, machine, pipeline);
      frameMs.push_back(last.frameMs);
      stencilMs.push_back(last.stencilMs);
      queueMs.push_back(last.queueMs);
    }
  }
  const bool deterministic = SameRun(CaptureFrame(geometry, gpu, 1), last);
  const bool identicalImages = last.stencilOutput == last.queueOutput;
  const sim::FrameSettings settings;
  std::printf("aasim frame bench: %s (%zu triangles), %dx%d, %s, %s, %d threads, median of %d frames\n",
              options.scene.c_str(), scene.clip.TriangleCount(), kWidth, kHeight,
              fmask::EqaaName(settings.eqaa).c_str(), gpu.name.c_str(), options.threads, options.frames);
  std::printf("  frame pipeline (draw + material kernel + EQAA + resolve): %8.1f ms\n", bench::Median(frameMs));
  std::printf("  demo pass, stencil strategy (2 dispatches):                %8.1f ms\n", bench::Median(stencilMs));
  std::printf("  demo pass, queue strategy (3 dispatches):                  %8.1f ms\n", bench::Median(queueMs));
  PrintBlendComparison(last.reports);
  std::printf("identical images: %s; deterministic (1 vs %d threads): %s\n", identicalImages ? "yes" : "no",
              options.threads, deterministic ? "yes" : "no");
  if (jsonFile.is_open()) {
    const nlohmann::ordered_json json = {{"schema", "aasim.bench.frame"},
                                         {"version", 1},
                                         {"scene", options.scene},
                                         {"triangles", scene.clip.TriangleCount()},
                                         {"width", kWidth},
                                         {"height", kHeight},
                                         {"eqaa", fmask::EqaaName(settings.eqaa)},
                                         {"gpu", gpu.name},
                                         {"threads", options.threads},
                                         {"frames", options.frames},
                                         {"frame_ms", frameMs},
                                         {"stencil_strategy_ms", stencilMs},
                                         {"queue_strategy_ms", queueMs},
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
  CLI::App app{
      "Frame benchmark: the frame pipeline and the demo post pass (both dispatch strategies) at "
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
  app.add_option("--json", options.json, "Also write the results as JSON to FILE")->type_name("FILE");
  return bench::ParseAndRun(app, argc, argv, [&] { return RunBench(options); });
}
