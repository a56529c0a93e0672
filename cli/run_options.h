#pragma once
// The options of `aasim run`, the main job (and of `aasim` with no arguments): the scene, the
// EQAA modes to render, the ground truth, the machine and where the report goes. Every rule runs
// before any work; violations are CLI::ValidationError (exit 2).

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cli/cli11_fwd.h"
#include "cli/frame_options.h"
#include "fmask/eqaa_surface.h"
#include "passes/registry.h"
#include "study/experiment.h"

namespace cli {

// What --quick changes unless the option is given explicitly: a small image and a ground truth of
// 8x8 strata, so the whole study runs in seconds.
inline constexpr int kQuickWidth = 640;
inline constexpr int kQuickHeight = 360;
inline constexpr int kQuickGroundTruthSamples = 64;

// 1S/1Z/1F first: the aliased frame the post passes work on, and the baseline every mode is
// compared with; then the EQAA study of issue 14: 8x MSAA, 8x EQAA with 4 and 2 fragments (the
// HRAA talk's examples, seed 001), 8x CRAA (1F), 16x EQAA and 16x CRAA, and 4x CRAA.
inline constexpr std::string_view kDefaultModes =
    "1S/1Z/1F,8S/8Z/8F,8S/8Z/4F,8S/4Z/2F,8S/8Z/1F,16S/8Z/4F,16S/8Z/1F,4S/4Z/1F";

enum class ProgressMode : std::uint8_t { Auto, Always, Never };

struct RunCommandOptions {
  std::string scene;  // default set by AddRunCommand
  int width = 1920;
  int height = 1080;
  bool quick = false;
  std::string modes = std::string(kDefaultModes);
  std::string pattern = "eqaa";
  std::string policy = "hraa";
  std::string resolves = "all";          // registered resolves run on the modes they read
  std::int64_t lutConfigurations = 0;    // the CRAA LUT's fit; 0 = the generator's default
  std::string comparePolicies = "none";  // further policies the EQAA modes are drawn under
  std::string gpu;  // default set by AddRunCommand (AddMachineOptions)
  std::string flush = "mix";
  FrameSetupOptions setup;
  std::string post = "all";
  std::string strategy = "both";  // stencil, queue or both
  std::vector<std::string> sweeps;  // --sweep PASS:SETTING=V1,V2,... (repeatable)
  int groundTruthSamples = 256;
  std::string cache;  // default set by AddRunCommand: scenes::GroundTruthCache::DefaultDirectory
  bool noCache = false;
  // A multi-frame run (study/sequence.h): frames, camera path, jitter override, frame rate.
  int frames = 1;
  std::string cameraPath = "still";
  double cameraSpeed = 0.0;  // 0 = the path's default speed (scenes/motion.h)
  std::string jitter;        // "" = each temporal pass's own schedule
  double framesPerSecond = 60.0;
  std::string velocityBuffer = "float";
  std::string sequencePost = "temporal";  // temporal, all or a list of --post passes
  std::string progress = "auto";
  int threads = 0;  // default set by AddRunCommand: every core
  std::string out = "out/report";

  // Filled by ResolveRunOptions.
  std::vector<fmask::EqaaConfig> eqaaModes;
  std::vector<passes::PassConfig> postPasses;
  std::vector<passes::Strategy> strategies;  // empty = every strategy each pass declares
  std::vector<std::string> resolveNames;
  std::vector<std::string> comparedPolicies;
  std::vector<study::SweepAxis> sweepAxes;
  ProgressMode progressMode = ProgressMode::Auto;
};

// Registers the `run` subcommand on `app`, bound to `options`.
CLI::App* AddRunCommand(CLI::App& app, RunCommandOptions& options);

// Applies --quick to the options not given explicitly, parses --modes and --post, checks the
// rules between options and the memory the run needs.
void ResolveRunOptions(CLI::App& command, RunCommandOptions& options);

// "8S/4Z/2F,16S/8Z/4F" (or "8/4/2"): each a legal EQAA mode, no repeats, at least one.
// Throws CLI::ValidationError naming the bad entry and listing the legal modes.
std::vector<fmask::EqaaConfig> ParseEqaaModes(std::string_view list);

// The experiment the resolved options describe (plain data for the study library).
study::ExperimentConfig ExperimentFrom(const RunCommandOptions& options);

// Bytes held at once: the ground truth and its metrics, one frame pipeline at the largest mode,
// every frame's kept images (the modes, and the EQAA modes again per compared policy) with those
// of the resolves that read it, and the post passes' outputs.
std::uint64_t EstimateRunBytes(int width, int height, const std::vector<fmask::EqaaConfig>& modes,
                               std::span<const passes::PassConfig> postPasses,
                               std::span<const std::string> resolves = {}, std::size_t comparedPolicies = 0);
// What a multi-frame run adds while its sequence runs (study/sequence_study.cpp): every frame's
// ground truth, and the largest group (they run one at a time): its frame pipeline and
// reprojection state, its temporal passes' instances, one spatial pass run, and per technique its
// last image and each frame's display codes.
std::uint64_t EstimateSequenceBytes(const study::ExperimentConfig& config);

}  // namespace cli
