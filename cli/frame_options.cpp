// Option registry and cross-option checks of `aasim frame` (see frame_options.h).

#include "cli/frame_options.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "cli/common_options.h"
#include "raster/limits.h"
#include "sim/gpu_config.h"

namespace cli {
namespace {

struct NamedWaveFlush {
  std::string_view name;
  sim::WaveFlush flush;
};
constexpr NamedWaveFlush kWaveFlushes[] = {
    {"mix", sim::WaveFlush::MixPrimitives},
    {"primitive", sim::WaveFlush::OnePrimitivePerWave},
};

constexpr std::string_view kPostNone = "none";

void AddSurfaceOptions(CLI::App& command, FrameCommandOptions& options) {
  command.add_option("--samples", options.samples, "Coverage samples per pixel S")
      ->check(SampleCountCheck())
      ->capture_default_str();
  command.add_option("--depth-samples", options.depthSamples, "Anchored depth samples per pixel Z")
      ->check(DepthSampleCountCheck())
      ->capture_default_str();
  command.add_option("--fragments", options.fragments, "Colour fragments per pixel F")
      ->check(FragmentCountCheck())
      ->capture_default_str();
  AddPatternOption(command, options.pattern);
  command
      .add_option("--policy", options.policy,
                  "Fragment arbitration policy when all F slots are taken (docs/eqaa.md)")
      ->check(CLI::IsMember(fmask::PolicyNames()))
      ->capture_default_str();
}

std::vector<std::string> DrawOrderNames() {
  std::vector<std::string> names;
  for (const sim::NamedDrawOrder& entry : sim::kDrawOrders) names.emplace_back(entry.name);
  return names;
}

void AddPostOptions(CLI::App& command, FrameCommandOptions& options) {
  command
      .add_option("--post", options.post,
                  "Post pass after the frame, NAME[:key=value,...] (passes: " + JoinNames(passes::PassNames()) +
                      "; their settings: aasim passes), or none = the frame alone")
      ->type_name("PASS")
      ->capture_default_str();
  command
      .add_option("--strategy", options.strategy,
                  "Dispatch strategy of the post pass: stencil = stencil-culled full-screen "
                  "pixel shader, queue = deferred queue + indirect compute, both = each, compared "
                  "[default: both]")
      ->check(CLI::IsMember(StrategyChoices()));
}

void AddRunOptions(CLI::App& command, FrameCommandOptions& options) {
  AddThreadsOption(command, options.threads);
  command
      .add_option("--out", options.out,
                  "Output directory for colour.png, frame.exr, post/, heat/, dispatches.json and "
                  "dispatches.csv (created if missing)")
      ->type_name("DIR")
      ->required();
}

void CheckMemory(const FrameCommandOptions& options) {
  const std::uint64_t bytes =
      EstimateFrameBytes(options.width, options.height, options.Eqaa(),
                         options.pass ? &options.pass->Info() : nullptr, options.Strategies().size());
  if (bytes > kMaxRunBytes) {
    throw CLI::ValidationError(
        "--width " + std::to_string(options.width) + " --height " + std::to_string(options.height) +
        " --samples " + std::to_string(options.samples) + " --depth-samples " +
        std::to_string(options.depthSamples) + " --fragments " + std::to_string(options.fragments) +
        ": needs about " + FormatGiB(bytes) +
        " GiB (EQAA surfaces, quads, pixel targets, post pass and images), over the " +
        FormatGiB(kMaxRunBytes) + " GiB limit");
  }
}

}  // namespace

std::vector<std::string> StrategyChoices() {
  std::vector<std::string> choices{std::string(kBothStrategies)};
  for (const passes::Strategy strategy : passes::kAllStrategies) {
    choices.emplace_back(passes::StrategyName(strategy));
  }
  return choices;
}

std::vector<passes::Strategy> ChosenStrategies(const passes::PassInfo& info, std::string_view choice) {
  std::vector<passes::Strategy> chosen;
  for (const passes::Strategy each : info.strategies) {
    if (choice == kBothStrategies || choice == passes::StrategyName(each)) chosen.push_back(each);
  }
  return chosen;
}

void AddGpuOption(CLI::App& command, std::string& gpu) {
  gpu = std::string(sim::kDefaultGpuName);
  command
      .add_option("--gpu", gpu,
                  "GPU configuration for occupancy and the timing estimate: a built-in (" +
                      JoinNames(sim::BuiltinGpuNames()) + ") or a configuration file")
      ->type_name("NAME|PATH")
      ->capture_default_str();
}

void AddMachineOptions(CLI::App& command, std::string& gpu, std::string& flush) {
  AddGpuOption(command, gpu);
  command
      .add_option("--flush", flush,
                  "When the pixel-wave packer closes a wave: mix = when 16 quads are in or the "
                  "bin ends, primitive = also when the primitive changes")
      ->check(CLI::IsMember(Names(kWaveFlushes)))
      ->capture_default_str();
}

sim::DrawOrder FrameSetupOptions::Order() const {
  const std::optional<sim::DrawOrder> order = sim::DrawOrderByName(drawOrder);
  if (!order) throw std::invalid_argument("unknown draw order");
  return *order;
}

void AddFrameSetupOptions(CLI::App& command, FrameSetupOptions& setup) {
  command
      .add_option("--draw-order", setup.drawOrder,
                  "Triangle order of the frame's draw: submission = the scene's, front-to-back = "
                  "triangles by nearest depth, objects-front-to-back = meshes by nearest depth "
                  "(stable sorts; docs/eqaa.md \"CRAA setup\")")
      ->check(CLI::IsMember(DrawOrderNames()))
      ->capture_default_str();
  command.add_flag("--depth-prepass", setup.depthPrepass,
                   "Draw depth only first (its own dispatch, no pixel shader), then the material "
                   "draw with depth test EQUAL and depth writes off");
  command
      .add_option("--max-zplanes", setup.maxZPlanes,
                  "Z planes an 8x8 depth tile holds before it decompresses (0 = no depth "
                  "compression, so unanchored samples are never tested exactly)")
      ->check(CLI::Range(0, raster::kMaxZPlanesPerTile))
      ->capture_default_str();
}

std::vector<passes::Strategy> FrameCommandOptions::Strategies() const {
  if (!pass) return {};
  return ChosenStrategies(pass->Info(), strategy);
}

CLI::App* AddFrameCommand(CLI::App& app, FrameCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "frame",
      "Render a scene on the modelled GPU (raster, pixel waves, material kernel, EQAA colour), "
      "run a post pass under each dispatch strategy; write images, heat maps and "
      "per-dispatch reports");
  // Scripts append overrides to a base command line, so a repeated option means its last value.
  command->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  AddViewportOptions(*command, options.scene, options.width, options.height);
  AddSurfaceOptions(*command, options);
  AddMachineOptions(*command, options.gpu, options.flush);
  AddFrameSetupOptions(*command, options.setup);
  AddPostOptions(*command, options);
  AddRunOptions(*command, options);
  return command;
}

void ResolveFrameOptions(FrameCommandOptions& options) {
  CheckEqaaMode(options.Eqaa());
  options.pass.reset();
  if (options.post != kPostNone) {
    try {
      options.pass = passes::ResolvePass(options.post);
    } catch (const passes::SettingsError& error) {
      throw CLI::ValidationError("--post " + options.post + ": " + error.what());
    }
  }
  if (options.pass && options.pass->Info().eqaaSamples != 0 &&
      options.pass->Info().eqaaSamples != options.Eqaa().coverageSamples) {
    const std::string samples = std::to_string(options.pass->Info().eqaaSamples);
    throw CLI::ValidationError("--post " + options.post + ": reads a " + samples +
                               "-sample EQAA surface; the frame has " +
                               std::to_string(options.Eqaa().coverageSamples) + " (use --samples " + samples + ")");
  }
  // The strategy only means something to a post pass, so it is refused rather than ignored.
  if (!options.pass && !options.strategy.empty()) {
    throw CLI::ValidationError("--strategy " + options.strategy + " needs a post pass (--post NAME)");
  }
  if (options.strategy.empty() && options.pass) options.strategy = std::string(kBothStrategies);
  if (options.pass && options.Strategies().empty()) {
    throw CLI::ValidationError("--strategy " + options.strategy + ": pass " + std::string(options.pass->Info().name) +
                               " does not run under it");
  }
  CheckMemory(options);
}

std::uint64_t EstimateFrameBytes(int width, int height, const fmask::EqaaConfig& eqaa,
                                 const passes::PassInfo* pass, std::size_t strategies) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  // Resolved colour and its 8-bit sRGB store, depth, normal, object id, velocity; one shaded
  // colour per quad pixel.
  const std::uint64_t targets = 2 * sizeof(glm::vec4) + 4 + sizeof(float) + sizeof(std::uint32_t) +
                                sizeof(glm::vec2) + sizeof(fmask::Colour);
  const std::uint64_t images = 10 * sizeof(float) + 3;  // frame.exr's channels, colour.png
  // What one run of the pass holds, and its previews (output.png, one byte per layer channel).
  const std::uint64_t perStrategy = pass == nullptr ? 0 : pass->bytesPerPixel + 3 + 4;
  const std::uint64_t perPixel =
      SurfaceBytesPerPixel(eqaa.coverageSamples, eqaa.depthSamples, eqaa.fragments) + targets +
      images + strategies * perStrategy;
  return pixels * perPixel;
}

sim::WaveFlush WaveFlushByName(std::string_view name) {
  const auto* found = std::find_if(std::begin(kWaveFlushes), std::end(kWaveFlushes),
                                   [&](const NamedWaveFlush& entry) { return entry.name == name; });
  if (found == std::end(kWaveFlushes)) throw std::invalid_argument("unknown wave flush");
  return found->flush;
}

}  // namespace cli
