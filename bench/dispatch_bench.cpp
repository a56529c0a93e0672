// aasim_dispatch_bench: what the machine itself costs the host per 1080p dispatch, with kernels
// that do nothing, or only the fetches and stores the passes are made of. The passes' own times
// (aasim_frame_bench) sit on these floors: a kernel can be no faster than its fetches and stores.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include "bench/bench_util.h"
#include "sim/dispatch.h"
#include "sim/gpu_config.h"
#include "sim/host_memory.h"
#include "sim/resources.h"
#include "sim/views.h"

namespace {

constexpr int kWidth = 1920, kHeight = 1080;

struct BenchOptions {
  int threads = tbb::info::default_concurrency();
  int repeats = 7;
};

// The fastest of `repeats` runs: the floor is what the host can do, not what a busy moment did.
double FastestMs(int repeats, const std::function<void()>& run) {
  double fastest = 0.0;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    run();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    fastest = r == 0 ? ms : std::min(fastest, ms);
  }
  return fastest;
}

struct Case {
  std::string name;
  std::function<void()> run;
};

std::vector<Case> Cases(sim::Machine& machine, sim::Texture2D<glm::vec4>& srgb, sim::Texture2D<glm::vec4>& unorm,
                        sim::Texture2D<glm::vec4>& target) {
  const sim::KernelInfo kernel{.vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 10};
  const sim::FullScreenCall screen{.width = kWidth, .height = kHeight};
  const sim::ComputeGrid grid{.threads = {kWidth, kHeight, 1}, .groupSize = {8, 8, 1}};
  const glm::vec2 texel(1.0f / kWidth, 1.0f / kHeight);
  const auto centre = [](const sim::PixelLane& lane) {
    return (glm::vec2(lane.x, lane.y) + 0.5f) / glm::vec2(kWidth, kHeight);
  };
  // The pixel's centre and its right and upper neighbours' centres, summed: the fetches of SMAA's
  // neighbourhood blend (UNORM8 weights) or colour (sRGB) at their positions.
  const auto threeBilinear = [&](const sim::PixelLane& lane, const sim::TextureView<glm::vec4>& in,
                                 const sim::RwTextureView<glm::vec4>& out) {
    const glm::vec2 uv = centre(lane);
    out.Store(lane, lane.x, lane.y,
              in.SampleBilinear(lane, uv) + in.SampleBilinear(lane, uv + glm::vec2(texel.x, 0.0f)) +
                  in.SampleBilinear(lane, uv - glm::vec2(0.0f, texel.y)));
  };
  // A pixel kernel on every pixel: body(lane, in, out).
  const auto pixels = [&](const char* name, sim::Texture2D<glm::vec4>& input, auto body) {
    sim::Dispatch d(name, kernel);
    const sim::TextureView<glm::vec4> in = d.Read(input);
    const sim::RwTextureView<glm::vec4> out = d.ReadWrite(target);
    machine.FullScreen(d, screen, [&](sim::PixelLane& lane) { body(lane, in, out); });
    machine.ClearReports();
  };
  return {
      {"pixel: empty", [&] { pixels("empty", srgb, [](auto&, auto&, auto&) {}); }},
      {"pixel: 1 store",
       [&] { pixels("store", srgb, [](auto& lane, auto&, auto& out) { out.Store(lane, lane.x, lane.y, glm::vec4(0.5f)); }); }},
      {"pixel: 3 loads (RGBA8), 1 store",
       [&] {
         pixels("loads", unorm, [](auto& lane, auto& in, auto& out) {
           out.Store(lane, lane.x, lane.y,
                     in.Load(lane, lane.x, lane.y) + in.Load(lane, lane.x + 1, lane.y) + in.Load(lane, lane.x, lane.y - 1));
         });
       }},
      {"pixel: 3 bilinear (UNORM8 fixed point), 1 store", [&] { pixels("bilinear-unorm8", unorm, threeBilinear); }},
      {"pixel: 3 bilinear (sRGB, float), 1 store", [&] { pixels("bilinear-srgb", srgb, threeBilinear); }},
      {"compute 8x8: empty",
       [&] {
         sim::Dispatch d("empty", kernel);
         d.SetPixelGrid(kWidth, kHeight);
         machine.Compute(d, grid, [](sim::ComputeLane&) {});
         machine.ClearReports();
       }},
      {"compute 8x8: 1 load, 1 store",
       [&] {
         sim::Dispatch d("copy", kernel);
         d.SetPixelGrid(kWidth, kHeight);
         const sim::TextureView<glm::vec4> in = d.Read(srgb);
         const sim::RwTextureView<glm::vec4> out = d.ReadWrite(target);
         machine.Compute(d, grid, [&](sim::ComputeLane& lane) {
           out.Store(lane, lane.threadId.x, lane.threadId.y, in.Load(lane, lane.threadId.x, lane.threadId.y));
         });
         machine.ClearReports();
       }},
  };
}

int RunBench(const BenchOptions& options) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(options.threads));
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  sim::Texture2D<glm::vec4> srgb("srgb", kWidth, kHeight, sim::Format::RGBA8Srgb);
  sim::Texture2D<glm::vec4> unorm("unorm", kWidth, kHeight, sim::Format::RGBA8Unorm);
  sim::Texture2D<glm::vec4> target("target", kWidth, kHeight, sim::Format::RGBA8Srgb);
  std::printf("aasim dispatch bench: %dx%d, ps4-class, %d threads, fastest of %d runs (ms per dispatch; ns per pixel "
              "x threads)\n",
              kWidth, kHeight, options.threads, options.repeats);
  const double lanes = static_cast<double>(kWidth) * kHeight;
  for (const Case& c : Cases(machine, srgb, unorm, target)) {
    const double ms = FastestMs(options.repeats, c.run);
    std::printf("  %-48s %8.1f ms %8.1f ns\n", c.name.c_str(), ms, ms * 1e6 * options.threads / lanes);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sim::KeepFreedHostMemory();  // frame-sized buffers reused, not re-faulted (sim/host_memory.h)
  CLI::App app{"Dispatch benchmark: the machine's own host cost per 1920x1080 dispatch, for kernels that do "
               "nothing or only fetch and store",
               "aasim_dispatch_bench"};
  BenchOptions options;
  app.add_option("--threads", options.threads, "Worker threads [default: all cores]")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  app.add_option("--repeats", options.repeats, "Runs of each dispatch; the fastest is reported")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  return bench::ParseAndRun(app, argc, argv, [&] { return RunBench(options); });
}
