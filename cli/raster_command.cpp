// `aasim raster` (see raster_command.h): runs the raster layer on a scene and writes its
// output set.

#include "cli/raster_command.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include "cli/counters_json.h"
#include "cli/eqaa_output.h"
#include "cli/eqaa_trace.h"
#include "study/frame_scene.h"
#include "cli/image_io.h"
#include "cli/output_dir.h"
#include "cli/ownership.h"
#include "cli/text_io.h"
#include "fmask/eqaa_surface.h"
#include "raster/rasterizer.h"
#include "raster/sample_pattern.h"
#include "scenes/scene.h"

namespace cli {
namespace {

// The colour block's part of a run (--fragments).
struct EqaaRun {
  fmask::EqaaSurface surface;
  fmask::FragmentCounters counters;
  double updateMs = 0.0;
};

struct RasterRun {
  raster::RasterResult result;
  PixelOwnership ownership;
  double rasterizeMs = 0.0;
  int threads = 0;
  std::optional<EqaaRun> eqaa;
};

double MsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

raster::DrawState MakeDrawState(const RasterCommandOptions& options) {
  raster::DrawState state;
  state.cull = CullModeByName(options.cull);
  state.depth.func = DepthFuncByName(options.depthFunc);
  state.depth.hiZEnable = !options.noHiZ;
  return state;
}

// One plane per anchored sample, as a depth decompress would write them.
std::vector<std::vector<float>> AnchorDepths(const raster::DepthStencilSurface& surface) {
  const raster::DepthSurfaceConfig& config = surface.Config();
  const std::size_t width = static_cast<std::size_t>(config.width);
  std::vector<std::vector<float>> planes(config.depthSamples,
                                         std::vector<float>(width * config.height));
  tbb::parallel_for(0, config.height, [&](int y) {
    for (int x = 0; x < config.width; ++x) {
      for (int anchor = 0; anchor < config.depthSamples; ++anchor) {
        planes[anchor][y * width + x] = surface.AnchorDepth(x, y, anchor);
      }
    }
  });
  return planes;
}

void WriteDepthExr(const std::filesystem::path& path, const raster::DepthStencilSurface& surface,
                   const PixelOwnership& ownership) {
  const std::vector<std::vector<float>> anchors = AnchorDepths(surface);
  std::vector<ExrChannel> channels{{"Z", anchors[0]}};
  for (std::size_t anchor = 0; anchor < anchors.size(); ++anchor) {
    channels.push_back({"depth.s" + std::to_string(anchor), anchors[anchor]});
  }
  channels.push_back({"coverage", ownership.coverage});
  WriteExr(path, surface.Config().width, surface.Config().height, channels);
}

// samples.exr: per coverage sample s, `coverage.s{s}` is 1 where some primitive covered the
// sample (before depth and stencil) and `primitive.s{s}` the id of the primitive that last
// passed depth there (the visible one), kNoPrimitive where none did. Written one row of bins
// at a time: those bins own exactly the strip's pixels, so they fill it in parallel and the
// per-sample layers never exist for the whole image at once.
void WriteSamplesExr(const std::filesystem::path& path, const raster::RasterResult& result,
                     int width, int height, int samples) {
  std::vector<std::string> names;
  for (int s = 0; s < samples; ++s) {
    names.push_back("coverage.s" + std::to_string(s));
    names.push_back("primitive.s" + std::to_string(s));
  }
  const auto fill = [&](int firstRow, int /*rows*/, std::vector<std::vector<std::uint32_t>>& strip) {
    for (int s = 0; s < samples; ++s) {
      std::fill(strip[2 * s + 1].begin(), strip[2 * s + 1].end(), kNoPrimitive);
    }
    const std::size_t binRow = static_cast<std::size_t>(firstRow / raster::kBinSize);
    const std::size_t binsX = static_cast<std::size_t>(result.binsX);
    tbb::parallel_for(std::size_t{0}, binsX, [&](std::size_t bx) {
      for (const raster::QuadFragment& quad : result.quadsByBin[binRow * binsX + bx]) {
        for (int p = 0; p < raster::kQuadPixels; ++p) {
          if (quad.covered.Pixel(p) == 0) continue;  // also every pixel outside the image
          const std::size_t pixel =
              static_cast<std::size_t>(quad.y + (p >> 1) - firstRow) * static_cast<std::size_t>(width) +
              static_cast<std::size_t>(quad.x + (p & 1));
          for (int s = 0; s < samples; ++s) {
            if (quad.covered.Sample(p, s)) strip[2 * s][pixel] = 1u;
            if (quad.passed.Sample(p, s)) strip[2 * s + 1][pixel] = quad.primitiveId;
          }
        }
      }
    });
  };
  WriteUintExr(path, width, height, names, raster::kBinSize, fill);
}

// A ratio computed at report time; null when the denominator is zero (style.md habit 15).
nlohmann::ordered_json Ratio(double numerator, double denominator) {
  return denominator == 0.0 ? nlohmann::ordered_json(nullptr)
                            : nlohmann::ordered_json(numerator / denominator);
}

nlohmann::ordered_json DerivedJson(const RasterCommandOptions& options, const RasterRun& run) {
  const raster::RasterCounters& c = run.result.counters;
  const std::uint64_t liveQuads = c.quadsLive1 + c.quadsLive2 + c.quadsLive3 + c.quadsLive4;
  const std::uint64_t livePixels =
      c.quadsLive1 + 2 * c.quadsLive2 + 3 * c.quadsLive3 + 4 * c.quadsLive4;
  const double pixels = double(options.width) * double(options.height);
  return {
      {"quads_total", run.result.QuadCount()},
      {"quad_pixel_utilization", Ratio(double(livePixels), 4.0 * double(liveQuads))},
      {"covered_samples_per_pixel", Ratio(double(c.samplesCovered), pixels)},
      {"depth_pass_ratio", Ratio(double(c.samplesDepthPassed), double(c.samplesCovered))},
      {"pixels_covered", run.ownership.PixelsCovered()},
      {"pixels_partial", run.ownership.PixelsPartial()},
  };
}

nlohmann::ordered_json EqaaJson(const RasterCommandOptions& options, const EqaaRun& eqaa) {
  return {{"config", fmask::EqaaName(options.Eqaa())},
          {"policy", options.policy},
          {"init", options.fmaskInit},
          {"counters", FragmentCountersJson(eqaa.counters)}};
}

nlohmann::ordered_json CountersDocument(const RasterCommandOptions& options, const RasterRun& run) {
  nlohmann::ordered_json document = {
      {"schema", "aasim.raster.counters"},
      {"version", 1},
      {"config",
       {{"scene", options.scene},
        {"width", options.width},
        {"height", options.height},
        {"samples", options.samples},
        {"depth_samples", options.depthSamples},
        {"pattern", options.pattern},
        {"max_zplanes", options.maxZPlanes},
        {"cull", options.cull},
        {"depth_func", options.depthFunc},
        {"hiz", !options.noHiZ},
        {"threads", run.threads}}},
      {"counters", CountersJson(run.result.counters)},
      {"derived", DerivedJson(options, run)},
  };
  if (run.eqaa) document["eqaa"] = EqaaJson(options, *run.eqaa);
  document["timing"] = {{"rasterize_ms", run.rasterizeMs}};
  if (run.eqaa) document["timing"]["eqaa_ms"] = run.eqaa->updateMs;
  return document;
}

void WriteEqaaOutputs(OutputDir& dir, const RasterCommandOptions& options, const EqaaRun& eqaa) {
  const EqaaPlanes planes = ReadEqaaPlanes(eqaa.surface);
  WriteEqaaExr(dir.Stage("eqaa.exr"), planes);
  WritePng(dir.Stage("resolve.png"), planes.width, planes.height, 3, ResolveImage(planes));
  WritePng(dir.Stage("fmask.png"), planes.width, planes.height, 3, FmaskImage(planes));
  if (!options.traced.empty()) {
    WriteText(dir.Stage("trace.txt"), TraceText(options, eqaa.surface));
    WriteJson(dir.Stage("trace.json"), TraceJson(options, eqaa.surface));
  }
}

std::vector<std::filesystem::path> WriteOutputs(OutputDir& dir, const RasterCommandOptions& options,
                                                const raster::DepthStencilSurface& surface,
                                                const RasterRun& run) {
  WritePng(dir.Stage("coverage.png"), options.width, options.height, 1,
           CoverageImage(run.ownership));
  WritePng(dir.Stage("primitives.png"), options.width, options.height, 3,
           PrimitiveImage(run.ownership));
  WriteDepthExr(dir.Stage("depth.exr"), surface, run.ownership);
  WriteSamplesExr(dir.Stage("samples.exr"), run.result, options.width, options.height,
                  options.samples);
  if (run.eqaa) WriteEqaaOutputs(dir, options, *run.eqaa);
  WriteJson(dir.Stage("counters.json"), CountersDocument(options, run));
  return dir.Commit("counters.json");
}

std::string FormatMs(double ms) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", ms);
  return text;
}

// Fragment counts are only meaningful up to F, so the histogram stops there.
void PrintEqaaSummary(std::ostream& out, const RasterCommandOptions& options, const EqaaRun& eqaa) {
  const fmask::FragmentCounters& c = eqaa.counters;
  out << "eqaa       " << fmask::EqaaName(options.Eqaa()) << ", policy " << options.policy
      << ", FMASK init " << options.fmaskInit << ", " << c.pixelUpdates << " pixel updates\n"
      << "fragments  per pixel after each update, 0..F:";
  for (int k = 0; k <= options.fragments; ++k) {
    out << (k == 0 ? " " : " / ") << c.fragmentsAfter[static_cast<std::size_t>(k)];
  }
  out << "; " << c.evictions << " evictions, " << c.fragmentsRejected << " rejected\n"
      << "unknown    samples " << c.samplesUnknownByEviction << " by eviction, "
      << c.samplesUnknownByUntestable << " untestable; " << c.zPlaneRescues << " z-plane rescues\n";
}

std::string FormatTime(const RasterRun& run) {
  std::string text = FormatMs(run.rasterizeMs) + " ms rasterize";
  if (run.eqaa) text += ", " + FormatMs(run.eqaa->updateMs) + " ms colour block";
  return text;
}

void PrintSummary(std::ostream& out, const RasterCommandOptions& options, const RasterRun& run,
                  const std::vector<std::filesystem::path>& written) {
  const raster::RasterCounters& c = run.result.counters;
  out << "scene      " << options.scene << ", " << options.width << "x" << options.height
      << ", S=" << options.samples << " Z=" << options.depthSamples << ", pattern "
      << options.pattern << "\n"
      << "triangles  " << c.trianglesIn << " in, " << c.trianglesRasterized << " rasterized ("
      << c.trianglesCulled << " culled, " << c.trianglesOutsideView << " outside view, "
      << c.trianglesZeroArea << " zero area)\n"
      << "tiles      " << c.tilesFull << " full, " << c.tilesPartial << " partial, " << c.tilesEmpty
      << " empty, " << c.tilesHiZRejected << " hi-Z rejected\n"
      << "quads      by live pixels 1/2/3/4: " << c.quadsLive1 << " / " << c.quadsLive2 << " / "
      << c.quadsLive3 << " / " << c.quadsLive4 << "\n"
      << "samples    " << c.samplesCovered << " covered, " << c.samplesDepthPassed
      << " depth-passed\n"
      << "z-planes   " << c.zPlaneDecompressions << " tile decompressions\n";
  if (run.eqaa) PrintEqaaSummary(out, options, *run.eqaa);
  out << "time       " << FormatTime(run) << " (" << run.threads << " threads)\n"
      << "wrote     ";
  for (const std::filesystem::path& path : written) out << ' ' << path.string();
  out << '\n';
}

// Feeds the quad stream, shaded with flat primitive colours, to a fresh EQAA surface.
EqaaRun RunColourBlock(const RasterCommandOptions& options, const raster::RasterResult& result) {
  EqaaRun eqaa{.surface = fmask::EqaaSurface(options.width, options.height, options.Eqaa(),
                                             fmask::PolicyByName(options.policy),
                                             FmaskInitByName(options.fmaskInit), kClearColour),
               .counters = {},
               .updateMs = 0.0};
  eqaa.surface.TracePixels(options.traced);
  const auto start = std::chrono::steady_clock::now();
  eqaa.counters = eqaa.surface.UpdateAll(result, [](const raster::QuadFragment& quad, int) {
    return PrimitiveColour(quad.primitiveId);
  });
  eqaa.updateMs = MsSince(start);
  return eqaa;
}

}  // namespace

void RunRasterCommand(const RasterCommandOptions& options, std::ostream& summary) {
  const tbb::global_control threadLimit(tbb::global_control::max_allowed_parallelism,
                                        static_cast<std::size_t>(options.threads));
  raster::SamplePattern pattern = raster::ResolvePattern(options.pattern, options.samples);
  OutputDir dir = OpenOutOption(options.out);

  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  const scenes::Scene scene = scenes::LoadScene(options.scene, aspect);
  const study::ClipSpaceScene clip = study::ToClipSpace(scene, aspect);
  raster::DepthStencilSurface surface({.width = options.width,
                                       .height = options.height,
                                       .coverageSamples = options.samples,
                                       .depthSamples = options.depthSamples,
                                       .maxZPlanes = options.maxZPlanes},
                                      std::move(pattern));

  RasterRun run;
  run.threads = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  const auto start = std::chrono::steady_clock::now();
  run.result = raster::Rasterize(clip.DrawInput(), MakeDrawState(options), surface);
  run.rasterizeMs = MsSince(start);
  if (options.fragments > 0) run.eqaa = RunColourBlock(options, run.result);
  run.ownership = ComputeOwnership(run.result, options.width, options.height, options.samples);

  PrintSummary(summary, options, run, WriteOutputs(dir, options, surface, run));
}

}  // namespace cli
