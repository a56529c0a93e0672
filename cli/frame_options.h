#pragma once
// The options of `aasim frame`: one registry (name, default, legal range, help) from which
// CLI11 builds --help and checks single values, plus the checks between options. Every rule
// runs before any work; violations are CLI::ValidationError (exit 2).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/cli11_fwd.h"
#include "fmask/eqaa_surface.h"
#include "passes/registry.h"
#include "sim/draw_order.h"
#include "sim/wave.h"

namespace cli {

// Seed 001's CRAA setup notes as frame settings (sim::FrameSettings drawOrder, depthPrepass,
// maxZPlanes; docs/eqaa.md "CRAA setup"), shared by `aasim frame` and `aasim run`.
struct FrameSetupOptions {
  std::string drawOrder = "submission";  // a sim::kDrawOrders name
  bool depthPrepass = false;
  int maxZPlanes = 4;  // hw-facts §5.2 default; 0 = depth compression off

  sim::DrawOrder Order() const;
};

// --draw-order, --depth-prepass and --max-zplanes.
void AddFrameSetupOptions(CLI::App& command, FrameSetupOptions& setup);

struct FrameCommandOptions {
  std::string scene;  // "builtin:NAME" or a glTF path; default set by AddFrameCommand
  int width = 1920;
  int height = 1080;
  int samples = 8;
  int depthSamples = 4;
  int fragments = 2;
  // radeonsi's EQAA order, the positions the hardware uses with these surfaces (hw-facts §4.3).
  std::string pattern = "eqaa";
  std::string policy = "hraa";
  std::string gpu;  // name or file; default set by AddFrameCommand: sim::kDefaultGpuName
  std::string flush = "mix";
  FrameSetupOptions setup;
  std::string post = "demo";  // NAME[:key=value,...] or "none"
  std::string strategy;  // empty until ResolveFrameOptions: "both" with a post pass
  int threads = 0;       // default set by AddFrameCommand: every core
  std::string out;

  // Filled by ResolveFrameOptions: the pass --post names, with its settings.
  std::optional<passes::PassConfig> pass;

  fmask::EqaaConfig Eqaa() const { return {samples, depthSamples, fragments}; }
  // The strategies the post pass runs under, in run order; empty with --post none.
  std::vector<passes::Strategy> Strategies() const;
};

// Registers the `frame` subcommand on `app`, bound to `options`.
CLI::App* AddFrameCommand(CLI::App& app, FrameCommandOptions& options);

// Fills defaults that depend on other options and checks the rules between options.
void ResolveFrameOptions(FrameCommandOptions& options);

// Bytes held at once: the EQAA depth and colour surfaces with one layer of quads, the
// pipeline's pixel targets and shaded quad colours, the frame's output images, and per
// strategy what the pass declares (PassInfo::bytesPerPixel) and its previews.
std::uint64_t EstimateFrameBytes(int width, int height, const fmask::EqaaConfig& eqaa,
                                 const passes::PassInfo* pass, std::size_t strategies);

sim::WaveFlush WaveFlushByName(std::string_view name);

// --gpu NAME|PATH (default sim::kDefaultGpuName), for every command that runs the machine.
void AddGpuOption(CLI::App& command, std::string& gpu);
// --gpu and --flush mix|primitive (default: what `flush` holds), for every command that renders
// a frame on the machine.
void AddMachineOptions(CLI::App& command, std::string& gpu, std::string& flush);

// --strategy's values: "both", then every strategy's name.
inline constexpr std::string_view kBothStrategies = "both";
std::vector<std::string> StrategyChoices();
// The strategies of `info` that --strategy `choice` selects, in the pass's order.
std::vector<passes::Strategy> ChosenStrategies(const passes::PassInfo& info, std::string_view choice);

}  // namespace cli
