#pragma once
// The outputs of a multi-frame run (docs/report.md "Sequence"): every frame of every technique
// as images/<track folder>/frame-NNN.png (ground truth: images/sequence/ground-truth/), the
// report's sequence sections (frame strips, quality and stability over frames, per-frame
// counters, seed 001's timing table) and report.json's "sequence".

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/output_dir.h"
#include "cli/report_html.h"
#include "cli/report_images.h"
#include "study/study.h"

namespace cli {

// Stages each image as it is made and keeps a crop of it for the frame strips.
class SequenceImages {
 public:
  explicit SequenceImages(OutputDir& dir) : dir_(dir) {}
  // The window the strips show (the single-frame report's hardest region of the aliased frame),
  // shown x zoom. Until it is set, strips keep nothing.
  void SetRegion(const PixelRect& region, int zoom);
  bool HasRegion() const { return region_.width > 0; }
  void Add(const study::SequenceGroup* group, const study::SequenceTrack* track, int frame,
           const sim::Texture2D<glm::vec4>& image);

  const PixelRect& Region() const { return region_; }
  int Zoom() const { return zoom_; }
  // Crops per track folder ("sequence/ground-truth" for the ground truth), frame by frame.
  const std::map<std::string, std::vector<RgbImage>>& Strips() const { return strips_; }

 private:
  OutputDir& dir_;
  PixelRect region_{};
  int zoom_ = 1;
  std::map<std::string, std::vector<RgbImage>> strips_;
};

inline constexpr const char* kGroundTruthSequenceFolder = "sequence/ground-truth";

nlohmann::ordered_json SequenceJson(const study::StudySequence& sequence);
// Seed 001's temporal timing rows with aasim's estimates (report.json sequence.seed_001_timings).
nlohmann::ordered_json SeedTimingJson(const study::Study& study);
std::vector<ReportSection> SequenceSections(const study::Study& study, const SequenceImages& images);

}  // namespace cli
