#pragma once
// The main study (`aasim run`) as a library: the ray-traced ground truth, the scene rendered on
// the modelled GPU under every requested EQAA mode, every post pass under each of its dispatch
// strategies on the first mode's frame, and every image scored against the ground truth. The
// result keeps what the report shows; per-frame surfaces too large to keep (EQAA planes, pixel
// targets) are handed to an observer while they exist. Configured by ExperimentConfig.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "study/dispatch_log.h"
#include "study/eqaa_study.h"
#include "study/experiment.h"
#include "study/frame_scene.h"
#include "study/sequence.h"
#include "raster/sample_pattern.h"
#include "scenes/scene.h"
#include "passes/compare.h"
#include "passes/registry.h"
#include "passes/metrics.h"
#include "scenes/ground_truth.h"
#include "sim/dispatch.h"
#include "sim/frame.h"

namespace study {

// An image scored against the ground truth. Edge scores are NaN when the ground truth has no
// edge pixels (nothing to restrict them to).
struct ScoredImage {
  std::string label;   // "8S/4Z/2F", "demo"
  std::string folder;  // output folder of its files: "frames/8s-4z-2f", "passes/demo"
  sim::Texture2D<glm::vec4> colour;
  passes::QualityResult quality;
};

// One registered resolve (passes/resolve.h) of a frame's EQAA surface.
struct StudyResolve {
  std::string name;  // "craa-lut"
  ScoredImage image;
  std::size_t firstDispatch = 0, endDispatch = 0;  // [first, end) in Study::dispatches
};

struct StudyFrame {
  fmask::EqaaConfig mode;
  std::string policy;  // the fragment arbitration policy it was drawn under
  // The frame's box resolve (UNKNOWN samples dropped, hw-facts §1.6), the dispatch after the draw.
  ScoredImage image;
  // Every resolve of ExperimentConfig::resolves that reads this mode, in registry order.
  std::vector<StudyResolve> resolves{};
  // Frames post passes read: the colour as an 8-bit sRGB target holds it (what the passes start
  // from, sim::FramePipeline::ColourSrgb8), so a pass is compared with its own input's quantisation.
  std::optional<ScoredImage> srgb8{};
  fmask::FragmentCounters fragments{};
  UnknownSamples unknown{};      // at the end of the frame
  std::size_t drawDispatch = 0;  // index into Study::dispatches; the box resolve is the next one
};

struct StudyPassRun {
  passes::Strategy strategy;
  std::size_t firstDispatch = 0, endDispatch = 0;  // [first, end) in Study::dispatches
  std::vector<passes::PassLayer> layers;
};

// How far a pass's image is from that of the pass it varies (PassInfo::variantOf), on the same
// frame: both as the 8-bit sRGB codes an sRGB target would hold.
struct VariantDifference {
  std::string baseline;      // "smaa"
  std::uint64_t pixels = 0;  // pixels whose codes differ in any of R, G, B
  // Of those, the pixels some channel of which differs by more than one code: more than the
  // rounding of two targets of different formats (fxaa-miniengine's R11G11B10) can explain.
  std::uint64_t pixelsOverOneCode = 0;
  int maxCodes = 0;          // the largest difference of one channel, in codes
  double psnr = 0.0;         // dB between the images (passes::Psnr); +infinity when identical
};
VariantDifference CompareVariant(std::string baseline, const sim::Texture2D<glm::vec4>& image,
                                 const sim::Texture2D<glm::vec4>& baselineImage);

struct StudyPass {
  std::string name;
  std::string sweepPoint;  // "threshold=0.05" at a point of a sweep axis, else ""
  std::string description;
  std::string studiedDispatch;
  std::string settings;    // "threshold=0.1"
  std::string inputFrame;  // label of the frame it post-processed
  ScoredImage image;       // the first strategy's output; the others are bit-identical or flagged
  std::uint64_t workItems = 0;
  passes::WorkSetShape workSet{};
  std::vector<StudyPassRun> runs{};
  // The first difference of a later strategy's output from the first's (passes/compare.h).
  passes::StrategyDifference difference{};
  std::optional<VariantDifference> variant{};  // when the pass it varies ran on the same frame

  // The name, with the sweep point when there is one: "smaa threshold=0.05".
  std::string Label() const { return sweepPoint.empty() ? name : name + " " + sweepPoint; }
};

struct StudyGroundTruth {
  scenes::GroundTruthImage image;
  sim::Texture2D<glm::vec4> colour{"ground truth", 1, 1};  // image.colour as RGBA, for the metrics
  std::vector<float> edgeMask;  // the metrics' mask: 1 on edge pixels
  // The metrics' half that depends on the ground truth alone, prepared once for every image
  // scored against it.
  std::optional<passes::ScoringReference> scoring;
  bool cacheHit = false;
  std::filesystem::path cacheFile;  // empty with --no-cache
  double seconds = 0.0;
};

// Counters of one pass run (all its dispatches) or one frame's draw on one frame of a sequence.
struct SequenceFrameCounters {
  sim::LaneCounters lanes;  // merged over the dispatches
  std::uint64_t dispatches = 0;
  std::uint64_t dramBytes = 0;
  // Bytes read and written on the pass's history resources (textures named "history...").
  std::uint64_t historyBytes = 0;
  double estimatedMicroseconds = 0.0;  // sum of the dispatches' estimates (docs/timing-model.md)
};

struct SequenceStrategyRun {
  passes::Strategy strategy;
  std::vector<SequenceFrameCounters> frames;  // one per frame
};

// One technique followed over a sequence: the drawn frames themselves (the aliased input every
// pass of the group reads) or a post pass (its first strategy's images).
struct SequenceTrack {
  std::string technique;  // "frames", "smaa", "taa-ue4"
  std::string pass;       // "" for the drawn frames
  std::string folder;     // "sequence/halton8/taa-ue4"
  std::vector<passes::QualityScores> quality;  // per frame, against that frame's ground truth
  // Per frame: mean motion-compensated change from the previous frame in 8-bit codes (study/
  // stability.h); NaN at frame 0.
  std::vector<double> flicker;
  // Per frame: error in codes on pixels disoccluded less than kGhostFrames frames ago; nullopt
  // when there are none.
  std::vector<std::optional<double>> ghosting;
  std::vector<double> distanceToFinal;  // per frame: mean |image - last frame's image| in codes
  std::optional<int> convergenceFrame;  // ConvergenceFrame(distanceToFinal, kConvergenceCodes)
  // Mean over frames 1.. of flicker minus the ground truth's flicker on the same frames (aa-facts
  // §9.3 (a), with motion compensated as in (c)); NaN for a one-frame sequence.
  double excessFlicker = 0.0;
  std::vector<SequenceStrategyRun> runs;  // the drawn frames: one run (the draw and its resolve)
  // The first frame on which a later strategy's output differs from the first's, and how.
  std::optional<int> differenceFrame;
  passes::StrategyDifference difference{};
};

// The frames drawn with one jitter schedule and the techniques that read them.
struct SequenceGroup {
  std::string schedule;  // "none", "halton8"
  fmask::EqaaConfig mode;
  std::vector<double> groundTruthFlicker;         // per frame, the ground truth's (NaN at frame 0)
  std::vector<std::uint64_t> disoccludedPixels;   // per frame (0 at frame 0)
  std::vector<SequenceTrack> tracks;              // "frames" first, then passes in config order
};

// Pixels disoccluded this many frames ago or less count as young for the ghosting figure, and a
// track has converged once every later frame is within this many codes of its last frame.
inline constexpr int kGhostFrames = 4;
inline constexpr double kConvergenceCodes = 0.5;

struct StudySequence {
  int frames = 0;
  std::string cameraPath;  // "still", "orbit", ...
  double framesPerSecond = 60.0;
  bool groundTruthStill = false;  // one ground truth serves every frame (nothing moves)
  double groundTruthSeconds = 0.0;
  std::uint64_t groundTruthCacheHits = 0;
  std::vector<SequenceGroup> groups;
};

struct Study {
  std::string sceneName;
  std::size_t triangles = 0;
  StudyGroundTruth groundTruth;
  std::vector<StudyFrame> frames;
  std::vector<StudyPass> passes;
  std::optional<StudySequence> sequence;  // runs with ExperimentConfig::sequence.frames > 1
  sim::GpuConfig gpu;
  std::vector<DispatchRecord> dispatches;
  int threads = 0;
  double hostSeconds = 0.0;
};

// Everything read from files or tables, loaded before any output exists.
struct StudyInputs {
  scenes::Scene scene;
  FrameScene frame;
  std::vector<raster::SamplePattern> patterns;  // per mode of ExperimentConfig::modes
  sim::GpuConfig gpu;
};

// Throws a one-line error naming the input (scene, pattern, GPU configuration, a sweep axis).
StudyInputs LoadStudyInputs(const ExperimentConfig& config);

// Every pass run the configuration asks for: each pass once, or once per value of its sweep axis
// with that value set. Throws std::invalid_argument for an axis naming no pass of the run, two
// axes on one pass, no values or a repeated value, and passes::SettingsError for an unknown
// setting or a value outside its range.
struct PlannedPass {
  passes::PassConfig config;
  std::string sweepPoint;  // "" without an axis
};
std::vector<PlannedPass> PlanPasses(const ExperimentConfig& config);
// "threshold=0.05" -> "threshold-0.05", for folder names.
std::string SweepSlug(const std::string& sweepPoint);

// What the caller sees while the study runs. Every member may be empty.
struct StudyObserver {
  // After each step ("frame 8S/4Z/2F", "pass demo [queue]"), with its host time.
  std::function<void(const std::string& step, double seconds)> stepDone;
  scenes::ProgressCallback groundTruthProgress;
  // Once per mode, while its frame pipeline still holds the full surfaces.
  std::function<void(const StudyFrame&, const sim::FramePipeline&)> frameDone;
  // Every image of a sequence as it is made: ground truth (group and track null), then each
  // group's tracks, frame by frame.
  std::function<void(const SequenceGroup* group, const SequenceTrack* track, int frame,
                     const sim::Texture2D<glm::vec4>& image)>
      sequenceImage;
  // After each pass, with every strategy's layers. When set, the study then drops the layers
  // (StudyPassRun::layers ends empty), so a run holds one pass's layers at a time.
  std::function<void(const StudyPass&)> passDone;
};

// "8S/4Z/2F" -> "8s-4z-2f", for folder names.
std::string ModeSlug(const fmask::EqaaConfig& mode);

// The index of the mode whose frame a pass post-processes: the first mode (the aliased frame a
// renderer without MSAA produces) for passes reading no EQAA surface, else the first mode with
// the surface's sample count the pass needs; nullopt when the configuration has none.
std::optional<std::size_t> PassFrame(const ExperimentConfig& config, const passes::PassInfo& pass);

// The caller pins the host thread count (tbb::global_control); images and counters do not
// depend on it.
Study RunStudy(const StudyInputs& inputs, const ExperimentConfig& config, const StudyObserver& observer = {});

}  // namespace study
