// Option registry and cross-option checks of `aasim run` (see run_options.h).

#include "cli/run_options.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include <CLI/CLI.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "cli/common_options.h"
#include "cli/frame_options.h"
#include "passes/metrics.h"
#include "passes/registry.h"
#include "passes/craa/craa_lut.h"
#include "passes/resolve.h"
#include "raster/jitter_schedule.h"
#include "scenes/motion.h"
#include "study/study.h"

namespace cli {
namespace {

constexpr std::string_view kAllPasses = "all";
constexpr std::string_view kNoPasses = "none";

struct NamedProgress {
  std::string_view name;
  ProgressMode mode;
};
constexpr NamedProgress kProgressModes[] = {
    {"auto", ProgressMode::Auto}, {"always", ProgressMode::Always}, {"never", ProgressMode::Never}};

std::vector<std::string_view> SplitList(std::string_view list) {
  std::vector<std::string_view> items;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    items.push_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}

// "8S/4Z/2F" or "8/4/2": three numbers, each optionally followed by its letter.
bool ParseMode(std::string_view text, fmask::EqaaConfig& mode) {
  int values[3] = {0, 0, 0};
  constexpr char kLetters[3] = {'S', 'Z', 'F'};
  std::size_t at = 0;
  for (int part = 0; part < 3; ++part) {
    if (part > 0) {
      if (at >= text.size() || text[at] != '/') return false;
      ++at;
    }
    const std::size_t digits = at;
    while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at])) && at - digits < 3) {
      values[part] = values[part] * 10 + (text[at] - '0');
      ++at;
    }
    if (at == digits) return false;
    if (at < text.size() && std::toupper(static_cast<unsigned char>(text[at])) == kLetters[part]) ++at;
  }
  mode = {values[0], values[1], values[2]};
  return at == text.size();
}

std::vector<passes::PassConfig> ResolvePasses(const std::string& post) {
  if (post == kNoPasses) return {};
  std::vector<passes::PassConfig> chosen;
  try {
    for (const std::string& spec : post == kAllPasses ? passes::PassNames() : passes::SplitPassList(post)) {
      passes::PassConfig config = passes::ResolvePass(spec);
      const bool repeated = std::any_of(chosen.begin(), chosen.end(),
                                        [&](const passes::PassConfig& each) { return each.pass == config.pass; });
      if (repeated) throw passes::SettingsError("'" + std::string(config.Info().name) + "' is named twice");
      chosen.push_back(std::move(config));
    }
  } catch (const passes::SettingsError& error) {
    throw CLI::ValidationError("--post " + post + ": " + error.what());
  }
  return chosen;
}

void AddStudyOptions(CLI::App& command, RunCommandOptions& options) {
  command.add_flag("--quick", options.quick,
                   "A small run: " + std::to_string(kQuickWidth) + "x" + std::to_string(kQuickHeight) +
                       " and " + std::to_string(kQuickGroundTruthSamples) +
                       " ground-truth samples per pixel, unless --width, --height or --gt-samples "
                       "say otherwise");
  command
      .add_option("--modes", options.modes,
                  "EQAA modes to render, comma-separated S/Z/F (e.g. 8S/4Z/2F); the first is the "
                  "frame the post passes work on")
      ->type_name("LIST")
      ->capture_default_str();
  AddPatternOption(command, options.pattern);
  command
      .add_option("--policy", options.policy,
                  "Fragment arbitration policy when all F slots are taken (docs/eqaa.md)")
      ->check(CLI::IsMember(fmask::PolicyNames()))
      ->capture_default_str();
  command
      .add_option("--compare-policies", options.comparePolicies,
                  "Further arbitration policies, comma-separated, under which every EQAA mode (F < S) is drawn "
                  "again and resolved, for the EQAA study's policy column: " + JoinNames(fmask::PolicyNames()) +
                      ", all (every policy but --policy) or none; post passes run only on --policy's frames")
      ->type_name("LIST")
      ->capture_default_str();
  command
      .add_option("--resolves", options.resolves,
                  "Resolves of the EQAA surface run on every mode they read, besides the frame's box resolve, "
                  "comma-separated: " + JoinNames(passes::ResolveNames()) + ", all or none (docs/craa.md)")
      ->type_name("LIST")
      ->capture_default_str();
  command
      .add_option("--lut-configurations", options.lutConfigurations,
                  "Synthetic configurations the CRAA LUT of each sample pattern is fitted to, as `aasim craa-lut "
                  "--configurations` (fewer: faster, coarser; tables are cached per count) [default: the "
                  "generator's, 960000]")
      ->check(CLI::Range(std::int64_t{1}, passes::craa::kMaxLutConfigurations));
  command
      .add_option("--post", options.post,
                  "Post passes, comma-separated, each NAME[:key=value,...], run under every dispatch "
                  "strategy they have: " +
                      JoinNames(passes::PassNames()) +
                      ", or all (every pass the --modes feed: a pass reading an S-sample EQAA surface, such as "
                      "smaa-s2x, runs on the first S-sample mode and is left out of all without one), or none "
                      "(settings: aasim passes)")
      ->type_name("LIST")
      ->capture_default_str();
  command
      .add_option("--sweep", options.sweeps,
                  "A sweep axis: one setting of a --post pass run at each value, each an entry of its own "
                  "(\"smaa threshold=0.05\"), PASS:SETTING=V1,V2,...; repeat for other passes (one axis per pass)")
      ->type_name("PASS:SETTING=VALUES")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command
      .add_option("--strategy", options.strategy,
                  "Dispatch strategies the passes run under: stencil = stencil-culled full-screen pixel shader, "
                  "queue = deferred queue + indirect compute, both = each a pass declares, compared")
      ->check(CLI::IsMember({"both", "stencil", "queue"}))
      ->capture_default_str();
}

// Frames a run may ask for: each is drawn and scored once per jitter schedule.
constexpr int kMaxFrames = 1024;

void AddSequenceOptions(CLI::App& command, RunCommandOptions& options) {
  command
      .add_option("--frames", options.frames,
                  "Frames of a multi-frame run (docs/temporal.md): every post pass followed over N frames along "
                  "--camera-path with the scene's moving objects, temporal passes on their jitter schedules, "
                  "scored per frame against a ground-truth sequence, with flicker, ghosting and convergence; "
                  "1 = the single-frame study only")
      ->check(CLI::Range(1, kMaxFrames))
      ->capture_default_str();
  command
      .add_option("--camera-path", options.cameraPath,
                  "Camera motion over the frames: " + JoinNames(scenes::CameraPathKindNames()) +
                      " (scenes/motion.h; frame 0 is the scene's camera)")
      ->check(CLI::IsMember(scenes::CameraPathKindNames()))
      ->capture_default_str();
  command
      .add_option("--camera-speed", options.cameraSpeed,
                  "Speed of --camera-path per frame: orbit degrees, pan pixels (at the target's depth), dolly "
                  "fraction of the distance [default: the path's own, 0.25 / 0.5 / 0.005]")
      ->check(CLI::Range(-1000.0, 1000.0));
  command
      .add_option("--jitter", options.jitter,
                  "Jitter schedule for every temporal pass instead of its own: " +
                      JoinNames(raster::JitterScheduleNames()) + " (raster/jitter_schedule.h)")
      ->check(CLI::IsMember(raster::JitterScheduleNames()));
  AddFramesPerSecondOption(command, options.framesPerSecond);
  command
      .add_option("--sequence-post", options.sequencePost,
                  "The --post passes followed over the frames: temporal (every temporal pass), all, or a "
                  "comma-separated list; spatial passes cost a run and a scoring per frame each")
      ->type_name("LIST")
      ->capture_default_str();
  command
      .add_option("--velocity-buffer", options.velocityBuffer,
                  "What passes read as velocities: float (the frame's target), rg8 or rg8-half (seed 000's 8-bit "
                  "two-piece-linear buffer over 0..40 px, at full or half resolution with the front-most velocity of "
                  "each 2x2; docs/temporal.md)")
      ->check(CLI::IsMember(study::VelocityBufferNames()))
      ->capture_default_str();
}

void AddGroundTruthOptions(CLI::App& command, RunCommandOptions& options) {
  command
      .add_option("--gt-samples", options.groundTruthSamples,
                  "Ground-truth rays per pixel, a perfect square (n x n jittered strata)")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  command
      .add_option("--cache", options.cache,
                  "Directory of cached ground truths [default: $XDG_CACHE_HOME/aasim/ground-truth "
                  "or ~/.cache/aasim/ground-truth]")
      ->type_name("DIR");
  command.add_flag("--no-cache", options.noCache,
                   "Render the ground truth without reading or writing the cache");
}

void AddRunOutputOptions(CLI::App& command, RunCommandOptions& options) {
  AddThreadsOption(command, options.threads);
  command
      .add_option("--progress", options.progress,
                  "Progress bars on stderr: auto = when stderr is a terminal")
      ->check(CLI::IsMember(Names(kProgressModes)))
      ->capture_default_str();
  command
      .add_option("--out", options.out,
                  "Output directory for report.html, report.json, counters.csv and images/ "
                  "(created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
}

void CheckGroundTruthSamples(int samples) {
  int root = 0;
  while ((root + 1) * (root + 1) <= samples) ++root;
  if (root * root != samples) {
    throw CLI::ValidationError("--gt-samples " + std::to_string(samples) +
                               ": must be a perfect square (e.g. " + std::to_string(root * root) +
                               " or " + std::to_string((root + 1) * (root + 1)) + ")");
  }
}

// A temporal pass's schedule must draw the samples it reads, and sequence options need frames.
void CheckSequence(const CLI::App& command, const RunCommandOptions& options) {
  for (const char* option :
       {"--camera-path", "--camera-speed", "--jitter", "--fps", "--velocity-buffer", "--sequence-post"}) {
    if (options.frames == 1 && command.count(option) > 0) {
      throw CLI::ValidationError(std::string(option) + ": only a multi-frame run uses it; add --frames N (N > 1)");
    }
  }
  if (options.frames == 1) return;
  if (options.sequencePost != "temporal" && options.sequencePost != "all") {
    for (const std::string_view item : SplitList(options.sequencePost)) {
      const bool posted = std::any_of(options.postPasses.begin(), options.postPasses.end(),
                                      [&](const passes::PassConfig& pass) { return pass.Info().name == item; });
      if (!posted) {
        throw CLI::ValidationError("--sequence-post: " + std::string(item) + " is not one of the run's --post passes");
      }
    }
  }
  for (const passes::PassConfig& pass : options.postPasses) {
    const passes::PassInfo& info = pass.Info();
    if (!info.temporal) continue;
    const std::string schedule = options.jitter.empty() ? std::string(info.jitter) : options.jitter;
    const int samples = raster::JitterScheduleSamples(schedule);
    if (info.eqaaSamples != 0 && samples != info.eqaaSamples) {
      throw CLI::ValidationError("--jitter " + schedule + ": pass " + std::string(info.name) + " reads " +
                                 std::to_string(info.eqaaSamples) + " samples per pixel, the schedule draws " +
                                 std::to_string(samples));
    }
  }
}

// "smaa:threshold=0.05,0.1" -> {smaa, threshold, {0.05, 0.1}}; the study checks the names and
// values against the run's passes (study::PlanPasses).
study::SweepAxis ParseSweep(const std::string& text) {
  const std::size_t colon = text.find(':'), equals = text.find('=');
  if (colon == std::string::npos || equals == std::string::npos || equals < colon || colon == 0 || equals == colon + 1) {
    throw CLI::ValidationError("--sweep " + text + ": expected PASS:SETTING=V1,V2,... such as smaa:threshold=0.05,0.1");
  }
  study::SweepAxis axis{text.substr(0, colon), text.substr(colon + 1, equals - colon - 1), {}};
  for (const std::string_view item : SplitList(std::string_view(text).substr(equals + 1))) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), value);
    if (item.empty() || error != std::errc() || end != item.data() + item.size() || !std::isfinite(value)) {
      throw CLI::ValidationError("--sweep " + text + ": '" + std::string(item) + "' is not a finite decimal");
    }
    axis.values.push_back(value);
  }
  return axis;
}

std::vector<passes::PassConfig> PlannedPassConfigs(const RunCommandOptions& options) {
  study::ExperimentConfig config;
  config.passes = options.postPasses;
  config.sweeps = options.sweepAxes;
  std::vector<passes::PassConfig> planned;
  for (study::PlannedPass& pass : study::PlanPasses(config)) planned.push_back(std::move(pass.config));
  return planned;
}

void ResolveSweeps(RunCommandOptions& options) {
  options.sweepAxes.clear();
  for (const std::string& text : options.sweeps) {
    options.sweepAxes.push_back(ParseSweep(text));
    study::ExperimentConfig config;
    config.passes = options.postPasses;
    config.sweeps = options.sweepAxes;
    try {
      study::PlanPasses(config);
    } catch (const std::exception& error) {
      // The study names the axis as "sweep PASS:SETTING: ..."; the option names it here.
      std::string problem = error.what();
      if (problem.starts_with("sweep ")) problem = problem.substr(problem.find(": ") + 2);
      throw CLI::ValidationError("--sweep " + text + ": " + problem);
    }
  }
}

void CheckMemory(const RunCommandOptions& options) {
  std::uint64_t bytes = EstimateRunBytes(options.width, options.height, options.eqaaModes, PlannedPassConfigs(options),
                                         options.resolveNames, options.comparedPolicies.size());
  std::string what = "--width " + std::to_string(options.width) + " --height " + std::to_string(options.height) +
                     " --modes " + options.modes;
  if (options.frames > 1) {
    bytes += EstimateSequenceBytes(ExperimentFrom(options));
    what += " --frames " + std::to_string(options.frames);
  }
  if (bytes > kMaxStudyBytes) {
    throw CLI::ValidationError(what + ": needs about " + FormatGiB(bytes) + " GiB, over the " +
                               FormatGiB(kMaxStudyBytes) + " GiB limit");
  }
}

}  // namespace

namespace {

// "all" (every name but `excluded`), "none", or a list of distinct legal names other than `excluded`.
std::vector<std::string> ParseNameList(const std::string& option, std::string_view list,
                                       const std::vector<std::string>& legal, const std::string& excluded) {
  std::vector<std::string> names;
  if (list == "none") return names;
  if (list == "all") {
    for (const std::string& name : legal) {
      if (name != excluded) names.push_back(name);
    }
    return names;
  }
  for (const std::string_view item : SplitList(list)) {
    const std::string name(item);
    if (std::find(legal.begin(), legal.end(), name) == legal.end()) {
      throw CLI::ValidationError(option + ": unknown name '" + name + "' (" + JoinNames(legal) + ", all or none)");
    }
    if (name == excluded) throw CLI::ValidationError(option + ": " + name + " is already the run's --policy");
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      throw CLI::ValidationError(option + ": " + name + " is named twice");
    }
    names.push_back(name);
  }
  return names;
}

}  // namespace

std::vector<fmask::EqaaConfig> ParseEqaaModes(std::string_view list) {
  std::vector<fmask::EqaaConfig> modes;
  for (const std::string_view item : SplitList(list)) {
    fmask::EqaaConfig mode;
    if (!ParseMode(item, mode)) {
      throw CLI::ValidationError("--modes: '" + std::string(item) +
                                 "' is not an EQAA mode S/Z/F such as 8S/4Z/2F");
    }
    CheckEqaaMode(mode);
    if (std::find(modes.begin(), modes.end(), mode) != modes.end()) {
      throw CLI::ValidationError("--modes: " + fmask::EqaaName(mode) + " is named twice");
    }
    modes.push_back(mode);
  }
  return modes;
}

CLI::App* AddRunCommand(CLI::App& app, RunCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "run",
      "The main job (also what `aasim` alone runs): ray-traced ground truth, the scene rendered "
      "under several EQAA modes, every post pass under both dispatch strategies, image-quality "
      "metrics and machine counters; writes report.html, report.json, counters.csv and images");
  command->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  AddViewportOptions(*command, options.scene, options.width, options.height);
  AddStudyOptions(*command, options);
  AddMachineOptions(*command, options.gpu, options.flush);
  AddFrameSetupOptions(*command, options.setup);
  AddSequenceOptions(*command, options);
  AddGroundTruthOptions(*command, options);
  AddRunOutputOptions(*command, options);
  return command;
}

// A pass reading an EQAA surface of S samples (SMAA S2x) runs on the first mode with S samples.
// `--post all` leaves out the passes no mode feeds (said in --help); a pass named explicitly is
// an error. In a multi-frame run a temporal pass runs on the sequence only, whose jitter
// schedule draws the samples it reads.
void KeepPassesTheModesFeed(RunCommandOptions& options) {
  std::vector<passes::PassConfig> fed;
  for (passes::PassConfig& pass : options.postPasses) {
    const int samples = pass.Info().eqaaSamples;
    const bool sequenceOnly = options.frames > 1 && pass.Info().temporal;
    const bool feeds = samples == 0 || sequenceOnly || std::any_of(options.eqaaModes.begin(), options.eqaaModes.end(),
                                                   [&](const fmask::EqaaConfig& mode) {
                                                     return mode.coverageSamples == samples;
                                                   });
    if (feeds) {
      fed.push_back(std::move(pass));
    } else if (options.post != kAllPasses) {
      throw CLI::ValidationError("--post " + std::string(pass.Info().name) + ": needs a frame with " +
                                 std::to_string(samples) + " coverage samples; add a mode to --modes (e.g. " +
                                 std::to_string(samples) + "S/" + std::to_string(samples) + "Z/" +
                                 std::to_string(samples) + "F)");
    }
  }
  options.postPasses = std::move(fed);
}

void ResolveRunOptions(CLI::App& command, RunCommandOptions& options) {
  if (options.quick) {
    if (command.count("--width") == 0) options.width = kQuickWidth;
    if (command.count("--height") == 0) options.height = kQuickHeight;
    if (command.count("--gt-samples") == 0) options.groundTruthSamples = kQuickGroundTruthSamples;
  }
  if (options.noCache && command.count("--cache") > 0) {
    throw CLI::ValidationError("--cache " + options.cache + " and --no-cache contradict each other");
  }
  CheckGroundTruthSamples(options.groundTruthSamples);
  options.eqaaModes = ParseEqaaModes(options.modes);
  options.resolveNames = ParseNameList("--resolves", options.resolves, passes::ResolveNames(), {});
  options.comparedPolicies = ParseNameList("--compare-policies", options.comparePolicies, fmask::PolicyNames(),
                                           options.policy);
  options.postPasses = ResolvePasses(options.post);
  KeepPassesTheModesFeed(options);
  options.strategies.clear();
  if (const std::optional<passes::Strategy> one = passes::StrategyByName(options.strategy)) {
    options.strategies = {*one};
    for (const passes::PassConfig& pass : options.postPasses) {
      const std::vector<passes::Strategy>& declared = pass.Info().strategies;
      if (std::find(declared.begin(), declared.end(), *one) == declared.end()) {
        throw CLI::ValidationError("--strategy " + options.strategy + ": pass " + std::string(pass.Info().name) +
                                   " does not run under it");
      }
    }
  }
  for (const NamedProgress& entry : kProgressModes) {
    if (entry.name == options.progress) options.progressMode = entry.mode;
  }
  ResolveSweeps(options);
  CheckSequence(command, options);
  CheckMemory(options);
}

namespace {
scenes::CameraPath CameraPathFrom(const RunCommandOptions& options) {
  scenes::CameraPath path;
  path.kind = scenes::ParseCameraPathKind(options.cameraPath);
  path.panImageHeight = options.height;
  if (options.cameraSpeed == 0.0) return path;
  const auto speed = static_cast<float>(options.cameraSpeed);
  if (path.kind == scenes::CameraPathKind::Orbit) path.orbitDegreesPerFrame = speed;
  if (path.kind == scenes::CameraPathKind::Pan) path.panPixelsPerFrame = speed;
  if (path.kind == scenes::CameraPathKind::Dolly) path.dollyFractionPerFrame = speed;
  return path;
}
}  // namespace

study::ExperimentConfig ExperimentFrom(const RunCommandOptions& options) {
  study::ExperimentConfig config;
  config.scene = options.scene;
  config.width = options.width;
  config.height = options.height;
  config.modes = options.eqaaModes;
  config.pattern = options.pattern;
  config.policy = options.policy;
  config.comparedPolicies = options.comparedPolicies;
  config.resolves = options.resolveNames;
  config.tableConfigurations = options.lutConfigurations;
  config.gpu = options.gpu;
  config.flush = WaveFlushByName(options.flush);
  config.drawOrder = options.setup.Order();
  config.depthPrepass = options.setup.depthPrepass;
  config.maxZPlanes = options.setup.maxZPlanes;
  config.passes = options.postPasses;
  config.sweeps = options.sweepAxes;
  config.strategies = options.strategies;
  config.groundTruth.samplesPerPixel = options.groundTruthSamples;
  config.sequence.frames = options.frames;
  config.sequence.cameraPath = CameraPathFrom(options);
  config.sequence.framesPerSecond = options.framesPerSecond;
  config.sequence.jitterOverride = options.jitter;
  config.sequence.velocityBuffer = *study::VelocityBufferByName(options.velocityBuffer);
  if (options.sequencePost == "all") {
    config.sequence.followed = std::vector<std::string>();
    for (const passes::PassConfig& pass : options.postPasses) config.sequence.followed->emplace_back(pass.Info().name);
  } else if (options.sequencePost != "temporal") {
    config.sequence.followed = std::vector<std::string>();
    for (const std::string_view item : SplitList(options.sequencePost)) config.sequence.followed->emplace_back(item);
  }
  if (!options.noCache) {
    config.groundTruth.cache = options.cache;
    config.tableCache = std::filesystem::path(options.cache) / "tables";
  }
  return config;
}

std::uint64_t EstimateRunBytes(int width, int height, const std::vector<fmask::EqaaConfig>& modes,
                               std::span<const passes::PassConfig> postPasses, std::span<const std::string> resolves,
                               std::size_t comparedPolicies) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  std::uint64_t largestFrame = 0;
  for (const fmask::EqaaConfig& mode : modes) {
    largestFrame = std::max(largestFrame, EstimateFrameBytes(1, 1, mode, nullptr, 0));
  }
  // Ground truth (colour, coverage, edge, its half of the metrics: passes::ScoringReference) and
  // one metrics evaluation's maps and scratch (passes/metrics.cpp: SSIM's and FLIP's per-pixel
  // planes, 24 floats at most at once).
  const std::uint64_t groundTruth =
      sizeof(glm::vec3) + sizeof(float) + 1 + passes::ScoringReference::kBytesPerPixel;
  const std::uint64_t metrics = 3 * sizeof(float) + 24 * sizeof(float);
  // Kept per scored image (a frame, each resolve of it, the passes' sRGB8 input): colour and three
  // error maps. Compared policies redraw the EQAA modes. While a frame's files are written, its
  // EQAA planes (cli/eqaa_output.h: RGBA, one code per sample, fragments, unknown) exist once.
  const std::uint64_t scoredImage = sizeof(glm::vec4) + 3 * sizeof(float);
  std::uint64_t frames = 0, resolveImages = 0, eqaaPlanes = 0;
  for (const fmask::EqaaConfig& mode : modes) {
    eqaaPlanes = std::max(eqaaPlanes, (6 + std::uint64_t(mode.coverageSamples)) * sizeof(float));
    const std::uint64_t draws = 1 + (mode.fragments < mode.coverageSamples ? comparedPolicies : 0);
    frames += draws;
    for (const std::string& resolve : resolves) resolveImages += draws * passes::ResolveByName(resolve).info().reads(mode);
  }
  // Passes run one instance at a time (PassInfo::bytesPerPixel, the largest counts) and their
  // layers, every strategy's, live until the pass's files are written (StudyObserver::passDone);
  // what the study keeps of each pass stays: its output colour and three error maps.
  std::uint64_t largestRun = 0, kept = 0;
  for (const passes::PassConfig& pass : postPasses) {
    const passes::PassInfo& info = pass.Info();
    largestRun = std::max(largestRun, info.bytesPerPixel + info.strategies.size() * info.layerBytesPerPixel);
    kept += scoredImage;
  }
  const std::uint64_t passInput = postPasses.empty() ? 0 : scoredImage;
  return pixels * (largestFrame + eqaaPlanes + groundTruth + metrics + (frames + resolveImages) * scoredImage +
                   passInput + largestRun + kept);
}

}  // namespace cli

namespace cli {

std::uint64_t EstimateSequenceBytes(const study::ExperimentConfig& config) {
  const std::uint64_t pixels = std::uint64_t(config.width) * std::uint64_t(config.height);
  const auto frames = static_cast<std::uint64_t>(config.sequence.frames);
  // Every frame's ground truth is kept as scoring reads it (RGBA colour, edge mask, its half of
  // the metrics) and as displayed (3 codes), and the one being rendered whole (colour, coverage,
  // edge).
  const std::uint64_t groundTruths =
      frames * (sizeof(glm::vec4) + sizeof(float) + passes::ScoringReference::kBytesPerPixel + 3) +
      sizeof(glm::vec3) + sizeof(float) + 1;
  // Groups run one at a time (study/sequence_study.cpp): the largest group's pipeline, object ids,
  // ages and reprojection, its temporal passes' instances (every strategy, alive for the
  // sequence), one spatial pass run at a time with the first strategy's output kept for the
  // comparison, and per track its last image and every frame's display codes.
  struct Group {
    std::string schedule;
    std::uint64_t bytes = 0, largestSpatialRun = 0;
  };
  std::vector<Group> groups;
  const std::uint64_t perTrack = sizeof(glm::vec4) + 3 * frames;
  for (const study::PlannedPass& planned : study::PlanPasses(config)) {
    const passes::PassInfo& info = planned.config.Info();
    if (!study::Follows(config.sequence, info)) continue;
    const std::string schedule =
        !info.temporal ? "none" : (config.sequence.jitterOverride.empty() ? std::string(info.jitter) : config.sequence.jitterOverride);
    auto group = std::find_if(groups.begin(), groups.end(), [&](const Group& each) { return each.schedule == schedule; });
    if (group == groups.end()) {
      const int samples = raster::JitterScheduleSamples(schedule);
      const fmask::EqaaConfig mode = samples == 0 ? config.modes.front() : fmask::EqaaConfig{samples, samples, samples};
      groups.push_back({schedule, EstimateFrameBytes(1, 1, mode, nullptr, 0) + sizeof(std::uint32_t) + 1 +
                                      sizeof(glm::vec2) + 1 + perTrack, 0});
      group = groups.end() - 1;
    }
    group->bytes += perTrack;
    if (info.temporal) {
      group->bytes += info.strategies.size() * info.bytesPerPixel;
    } else {
      group->largestSpatialRun = std::max(group->largestSpatialRun, info.bytesPerPixel + sizeof(glm::vec4));
    }
  }
  std::uint64_t largestGroup = 0;
  for (const Group& group : groups) largestGroup = std::max(largestGroup, group.bytes + group.largestSpatialRun);
  return pixels * (groundTruths + largestGroup);
}

}  // namespace cli
