#pragma once
// What one experiment is, as plain data (no command line): the scene and viewport, the EQAA modes
// and their sample pattern, the machine, the post passes with their settings and strategies, and
// the ground truth. `aasim run` parses its options into this; benchmarks and tests fill it
// directly.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fmask/eqaa_surface.h"
#include "passes/registry.h"
#include "passes/resolve.h"
#include "sim/draw_order.h"
#include "sim/wave.h"
#include "study/sequence.h"

namespace study {

struct GroundTruthConfig {
  int samplesPerPixel = 256;  // a perfect square: n x n jittered strata
  // Where rendered ground truths are cached; nullopt renders without a cache.
  std::optional<std::filesystem::path> cache;
};

// One sweep axis: a setting of one of the run's passes, run at each value (each a study entry of
// its own, with its sweep point "setting=value").
struct SweepAxis {
  std::string pass;     // a pass of ExperimentConfig::passes
  std::string setting;  // a key of its settings schema
  std::vector<double> values;
};

struct ExperimentConfig {
  std::string scene = "builtin:default";  // "builtin:NAME" or a glTF path
  int width = 1920, height = 1080;
  // Rendered in order; post passes work on the first (the aliased frame a renderer without MSAA
  // produces, when it is 1S/1Z/1F).
  std::vector<fmask::EqaaConfig> modes;
  std::string pattern = "eqaa";  // built-in pattern name or file, resolved for each mode's S
  std::string policy = "hraa";   // fragment arbitration policy (docs/eqaa.md)
  // Further policies under which every EQAA mode (F < S) is drawn again and resolved, for the EQAA
  // study's policy column; no post pass runs on those frames.
  std::vector<std::string> comparedPolicies;
  std::string gpu;               // built-in name or file
  sim::WaveFlush flush = sim::WaveFlush::MixPrimitives;
  // Seed 001's CRAA setup notes, carried into every mode's sim::FrameSettings (docs/eqaa.md
  // "CRAA setup"): triangle order, a depth pre-pass then EQUAL, Z planes per tile (0 = off).
  sim::DrawOrder drawOrder = sim::DrawOrder::Submission;
  bool depthPrepass = false;
  int maxZPlanes = 4;  // hw-facts §5.2 default
  std::vector<passes::PassConfig> passes;
  // Settings swept instead of run once (at most one axis per pass).
  std::vector<SweepAxis> sweeps;
  // Resolves (passes/resolve.h) run on every mode they read, besides the frame's box resolve.
  std::vector<std::string> resolves = passes::ResolveNames();
  // Where tables resolves derive from the sample pattern (the CRAA LUT) are cached between runs.
  std::optional<std::filesystem::path> tableCache;
  std::int64_t tableConfigurations = 0;  // passes::ResolveContext::tableConfigurations
  // The strategies every pass runs under, among those it declares; empty = all it declares.
  std::vector<passes::Strategy> strategies;
  GroundTruthConfig groundTruth;
  // Frames, camera path and jitter of a multi-frame run (frames > 1 adds StudySequence).
  SequenceConfig sequence;
};

}  // namespace study
