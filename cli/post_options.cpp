// Options of `aasim post` (see post_options.h).

#include "cli/post_options.h"

#include <CLI/CLI.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "cli/common_options.h"
#include "cli/frame_options.h"
#include "cli/passes_command.h"
#include "raster/jitter_schedule.h"

namespace cli {
namespace {

// The option that supplies each passes::FrameInput, in enum order; empty where `aasim post` has
// none (the input only exists in a rendered frame).
struct InputSource {
  std::string_view what;
  std::string_view option;
};
constexpr InputSource kInputSources[] = {
    {"a colour image", "--input"},
    {"a depth buffer", "--depth"},
    {"normals", ""},
    {"object ids", ""},
    {"velocities", "--velocity"},
    {"an EQAA surface", ""},
};

void AddPassOptions(CLI::App& command, PostCommandOptions& options) {
  command.add_option("--pass", options.pass, "The registered post pass to run (listed below)")
      ->type_name("NAME")
      ->required();
  command
      .add_option("--preset", options.preset,
                  "One of the pass's presets (lower case, listed below), applied before every --set")
      ->type_name("PRESET");
  command
      .add_option("--set", options.settings,
                  "One setting of the pass, KEY=VALUE with a decimal VALUE inside the range listed below; "
                  "repeat for more")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

void AddImageOptions(CLI::App& command, PostCommandOptions& options) {
  command
      .add_option("--input", options.inputs,
                  "The image to run the pass on, as a capture tool such as RenderDoc exports a render "
                  "target: an 8-bit PNG, read as sRGB-encoded (grey, RGB, with or without alpha), or an "
                  "OpenEXR file, read as linear R, G, B and optional A; without alpha, alpha is 1. Repeat for a "
                  "sequence: the frames run in order through one pass instance per strategy, as a temporal pass "
                  "needs, and each frame's outputs go to frame-NNN/")
      ->type_name("IMAGE")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->required();
  command
      .add_option("--depth", options.depths,
                  "Depth buffer for passes that read one: an OpenEXR file of the image's size, the depth "
                  "in a channel named Z, Y or R (the first of these present); one per --input")
      ->type_name("EXR")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command
      .add_option("--velocity", options.velocities,
                  "Velocity buffer for passes that read one: an OpenEXR file of the image's size, motion in "
                  "pixels (current minus previous position, +y down) in channels R and G, or X and Y; one per "
                  "--input")
      ->type_name("EXR")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command
      .add_option("--jitter", options.jitter,
                  "The jitter schedule the frames were rendered with (docs/temporal.md), given to the pass as "
                  "each frame's pattern and jitter [default: the pass's own schedule]")
      ->check(CLI::IsMember(raster::JitterScheduleNames()));
  AddFramesPerSecondOption(command, options.framesPerSecond);
}

void AddRunOptions(CLI::App& command, PostCommandOptions& options) {
  command
      .add_option("--strategy", options.strategy,
                  "Dispatch strategy: stencil = stencil-culled full-screen pixel shader, queue = deferred "
                  "queue + indirect compute, both = each, compared bit for bit; the outputs written are "
                  "those of the first strategy run (stencil with both)")
      ->check(CLI::IsMember(StrategyChoices()))
      ->capture_default_str();
  AddGpuOption(command, options.gpu);
  AddThreadsOption(command, options.threads);
  command
      .add_option("--out", options.out,
                  "Output directory for output.png, output.exr, a PNG and an EXR per layer of the pass, "
                  "heat/, dispatches.json, dispatches.csv and report.json (created if missing)")
      ->type_name("DIR")
      ->required();
}

std::string JoinedSpec(const std::string& pass, const std::vector<std::string>& items) {
  std::string spec = pass;
  for (std::size_t i = 0; i < items.size(); ++i) spec += (i == 0 ? ":" : ",") + items[i];
  return spec;
}

// The registry's own "NAME:preset=P,key=value" resolution (passes::ResolvePass), one option at a
// time, so that an error names the option that caused it.
passes::PassConfig ResolveSettings(const PostCommandOptions& options) {
  std::vector<std::string> items;
  auto resolve = [&](const std::string& option) {
    try {
      return passes::ResolvePass(JoinedSpec(options.pass, items));
    } catch (const passes::SettingsError& error) {
      throw CLI::ValidationError(option + ": " + error.what());
    }
  };
  passes::PassConfig config = resolve("--pass " + options.pass);
  if (!options.preset.empty()) {
    if (config.Info().presets.empty()) {
      throw CLI::ValidationError("--preset " + options.preset + ": pass " + options.pass + " has no presets");
    }
    items.push_back("preset=" + options.preset);
    config = resolve("--preset " + options.preset);
  }
  for (const std::string& setting : options.settings) {
    items.push_back(setting);
    config = resolve("--set " + setting);
  }
  return config;
}

// Per-frame files come one per --input or not at all.
void CheckPerFrameFiles(const std::string& option, const std::vector<std::string>& files, std::size_t inputs) {
  if (files.empty() || files.size() == inputs) return;
  throw CLI::ValidationError(option + ": given " + std::to_string(files.size()) + " times for " +
                             std::to_string(inputs) + " --input images; give one per image or none");
}

}  // namespace

std::vector<passes::Strategy> PostCommandOptions::Strategies() const {
  if (!config) return {};
  return ChosenStrategies(config->Info(), strategy);
}

CLI::App* AddPostCommand(CLI::App& app, PostCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "post",
      "Run a registered post pass on your own image (a PNG or OpenEXR export of a render target, e.g. from "
      "RenderDoc) under each dispatch strategy; write the output image, the pass's layers, the dispatch "
      "reports and report.json");
  // As for `aasim frame`: a repeated option means its last value (--set collects every one).
  command->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  AddPassOptions(*command, options);
  AddImageOptions(*command, options);
  AddRunOptions(*command, options);
  command->footer("Registered passes, with their presets and settings (as `aasim passes` prints them):\n\n" +
                  DescribeAllPasses());
  return command;
}

void ResolvePostOptions(PostCommandOptions& options) {
  options.config = ResolveSettings(options);
  if (options.Strategies().empty()) {
    throw CLI::ValidationError("--strategy " + options.strategy + ": pass " + options.pass + " does not run under it");
  }
  CheckPerFrameFiles("--depth", options.depths, options.inputs.size());
  CheckPerFrameFiles("--velocity", options.velocities, options.inputs.size());
  CheckPostInputs(options.config->Info(), !options.depths.empty(), !options.velocities.empty());
  const std::string schedule = options.jitter.empty() ? std::string(options.config->Info().jitter) : options.jitter;
  if (raster::JitterScheduleSamples(schedule) > 1) {
    throw CLI::ValidationError("--jitter " + schedule + ": draws " + std::to_string(raster::JitterScheduleSamples(schedule)) +
                               " samples per pixel; aasim post reads resolved one-sample images (use aasim run --frames)");
  }
}

void CheckPostInputs(const passes::PassInfo& info, bool haveDepth, bool haveVelocity) {
  for (const passes::FrameInput input : info.inputs) {
    const InputSource& source = kInputSources[static_cast<std::size_t>(input)];
    const bool supplied = input == passes::FrameInput::Colour || (input == passes::FrameInput::Depth && haveDepth) ||
                          (input == passes::FrameInput::Velocity && haveVelocity);
    if (supplied) continue;
    const std::string pass = "--pass " + std::string(info.name) + " reads " + std::string(source.what);
    if (source.option.empty()) {
      throw CLI::ValidationError(pass + ", which only a rendered frame has: run it with aasim frame --post " +
                                 std::string(info.name));
    }
    throw CLI::ValidationError(pass + ": give it with " + std::string(source.option));
  }
}

std::uint64_t EstimatePostBytes(int width, int height, const passes::PassInfo& info, std::size_t strategies,
                                bool depth, bool velocity) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  const std::uint64_t image = 2 * sizeof(glm::vec4) + 4;  // decoded twice, and its 8-bit sRGB store
  const std::uint64_t depthBytes = (depth ? 2 * sizeof(float) : 0) + (velocity ? 2 * sizeof(glm::vec2) : 0);
  const std::uint64_t writers = sizeof(glm::vec4) + 4;  // output.exr's planes, output.png's bytes
  return pixels * (image + depthBytes + strategies * info.bytesPerPixel + writers);
}

}  // namespace cli
