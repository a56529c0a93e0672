// Multi-frame outputs (see sequence_report.h).

#include "cli/sequence_report.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdio>

#include "cli/frame_output.h"
#include "cli/image_io.h"
#include "cli/number_format.h"
#include "cli/report_json.h"
#include "passes/pass.h"

namespace cli {
namespace {

using study::SequenceFrameCounters;
using study::SequenceGroup;
using study::SequenceTrack;
using study::StudySequence;

std::string FrameFile(const std::string& folder, int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "/frame-%03d.png", frame);
  return "images/" + folder + name;
}

std::string GroupLabel(const SequenceGroup& group) {
  return group.schedule + ", " + fmask::EqaaName(group.mode);
}

std::string TrackLabel(const SequenceGroup& group, const SequenceTrack& track) {
  return track.technique + " (" + GroupLabel(group) + ")";
}

double Mean(const std::vector<double>& values, std::size_t from = 0) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = from; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) continue;
    sum += values[i];
    ++count;
  }
  return count == 0 ? std::nan("") : sum / static_cast<double>(count);
}

double MeanGhosting(const SequenceTrack& track) {
  std::vector<double> values;
  for (const std::optional<double>& ghost : track.ghosting) {
    if (ghost) values.push_back(*ghost);
  }
  return Mean(values);
}

std::vector<double> QualityOverFrames(const SequenceTrack& track, double passes::QualityScores::*score) {
  std::vector<double> values;
  for (const passes::QualityScores& q : track.quality) values.push_back(q.*score);
  return values;
}

nlohmann::ordered_json Numbers(const std::vector<double>& values) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const double value : values) list.push_back(Number(value));
  return list;
}

nlohmann::ordered_json CountersJson(const SequenceFrameCounters& c) {
  return {{"dispatches", c.dispatches},
          {"waves", c.lanes.waves},
          {"lanes_launched", c.lanes.lanesLaunched},
          {"lanes_active", c.lanes.lanesActive},
          {"dram_bytes", c.dramBytes},
          {"history_bytes", c.historyBytes},
          {"estimated_us", c.estimatedMicroseconds}};
}

nlohmann::ordered_json TrackJson(const SequenceTrack& track) {
  nlohmann::ordered_json quality = nlohmann::ordered_json::array(), ghosting = nlohmann::ordered_json::array(),
                         runs = nlohmann::ordered_json::array();
  for (const passes::QualityScores& q : track.quality) quality.push_back(QualityJson(q));
  for (const std::optional<double>& ghost : track.ghosting) ghosting.push_back(ghost ? Number(*ghost) : nullptr);
  for (const study::SequenceStrategyRun& run : track.runs) {
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    for (const SequenceFrameCounters& counters : run.frames) frames.push_back(CountersJson(counters));
    runs.push_back({{"strategy", track.pass.empty() ? "draw" : std::string(passes::StrategyName(run.strategy))},
                    {"frames", std::move(frames)}});
  }
  return {{"technique", track.technique},
          {"pass", track.pass.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(track.pass)},
          {"folder", "images/" + track.folder},
          {"quality", std::move(quality)},
          {"flicker_codes", Numbers(track.flicker)},
          {"ghosting_codes", std::move(ghosting)},
          {"distance_to_final_codes", Numbers(track.distanceToFinal)},
          {"convergence_frame", track.convergenceFrame ? nlohmann::ordered_json(*track.convergenceFrame) : nullptr},
          {"excess_flicker_codes", Number(track.excessFlicker)},
          {"strategies_identical", !track.differenceFrame},
          {"difference", track.differenceFrame ? nlohmann::ordered_json({{"frame", *track.differenceFrame},
                                                                         {"what", track.difference.Describe()}})
                                               : nlohmann::ordered_json(nullptr)},
          {"runs", std::move(runs)}};
}

}  // namespace

void SequenceImages::SetRegion(const PixelRect& region, int zoom) {
  region_ = region;
  zoom_ = zoom;
}

void SequenceImages::Add(const SequenceGroup*, const SequenceTrack* track, int frame,
                         const sim::Texture2D<glm::vec4>& image) {
  const std::string folder = track ? track->folder : kGroundTruthSequenceFolder;
  StagePngLater(dir_, FrameFile(folder, frame), image.Width(), image.Height(), 3, SrgbImage(image.Texels()));
  if (HasRegion()) strips_[folder].push_back(Crop(image.Texels(), image.Width(), region_));
}

nlohmann::ordered_json SequenceJson(const StudySequence& sequence) {
  nlohmann::ordered_json groups = nlohmann::ordered_json::array();
  for (const SequenceGroup& group : sequence.groups) {
    nlohmann::ordered_json tracks = nlohmann::ordered_json::array();
    for (const SequenceTrack& track : group.tracks) tracks.push_back(TrackJson(track));
    groups.push_back({{"schedule", group.schedule},
                      {"mode", fmask::EqaaName(group.mode)},
                      {"ground_truth_flicker_codes", Numbers(group.groundTruthFlicker)},
                      {"disoccluded_pixels", group.disoccludedPixels},
                      {"tracks", std::move(tracks)}});
  }
  return {{"frames", sequence.frames},
          {"camera_path", sequence.cameraPath},
          {"frames_per_second", sequence.framesPerSecond},
          {"ghost_frames", study::kGhostFrames},
          {"convergence_codes", study::kConvergenceCodes},
          {"ground_truth",
           {{"still", sequence.groundTruthStill},
            {"folder", std::string("images/") + kGroundTruthSequenceFolder},
            {"seconds", sequence.groundTruthSeconds},
            {"cache_hits", sequence.groundTruthCacheHits}}},
          {"groups", std::move(groups)}};
}

}  // namespace cli

namespace cli {
namespace {

std::string Fixed(double value, int decimals) { return std::isfinite(value) ? FormatFixed(value, decimals) : "n/a"; }

std::vector<std::string> SummaryRow(const SequenceGroup& group, const SequenceTrack& track) {
  const std::vector<double> flip = QualityOverFrames(track, &passes::QualityScores::flip);
  return {track.technique,
          GroupLabel(group),
          Fixed(Mean(QualityOverFrames(track, &passes::QualityScores::psnr)), 2),
          Fixed(Mean(flip), 4),
          Fixed(flip.empty() ? std::nan("") : flip.back(), 4),
          Fixed(Mean(QualityOverFrames(track, &passes::QualityScores::edgeFlip)), 4),
          Fixed(Mean(track.flicker, 1), 3),
          Fixed(track.excessFlicker, 3),
          Fixed(MeanGhosting(track), 2),
          track.convergenceFrame ? std::to_string(*track.convergenceFrame) : "n/a",
          track.pass.empty() ? "-" : (track.differenceFrame ? "NO (frame " + std::to_string(*track.differenceFrame) + ")" : "yes")};
}

ReportSection SummarySection(const StudySequence& sequence) {
  ReportSection section{"Sequence: " + std::to_string(sequence.frames) + " frames, camera " + sequence.cameraPath, {}, {}, {}, {}};
  section.paragraphs = {
      "Every post pass followed frame by frame (docs/temporal.md): spatial passes on the run's first mode, unjittered; "
      "temporal passes on the jitter schedule each is built for, drawn S/S/S. Each frame is scored against a "
      "jitter-free ground truth of the same frame" +
          std::string(sequence.groundTruthStill ? " (nothing moves, so one ground truth serves every frame)." : ".") +
          " Ground truth: " + FormatFixed(sequence.groundTruthSeconds, 1) + " s, " +
          std::to_string(sequence.groundTruthCacheHits) + " frames from the cache.",
      "Flicker: mean change from the previous frame in 8-bit display codes, with the known motion compensated "
      "(the previous image sampled at each pixel minus its velocity), over pixels that show the same object in "
      "both frames; excess flicker subtracts the ground truth's on the same pixels (aa-facts §9.3). Ghosting: "
      "error in codes against the ground truth on pixels disoccluded less than " +
          std::to_string(study::kGhostFrames) + " frames ago. Convergence: the first frame from which every "
          "later frame is within " + FormatFixed(study::kConvergenceCodes, 1) + " codes (mean) of the last frame."};
  ReportTable table{"Techniques over the sequence",
                    {"technique", "frames", "mean PSNR dB", "mean FLIP", "last FLIP", "mean edge FLIP",
                     "flicker (codes)", "excess flicker", "ghosting (codes)", "converged at frame",
                     "strategies identical"},
                    {}};
  for (const SequenceGroup& group : sequence.groups) {
    for (const SequenceTrack& track : group.tracks) table.rows.push_back(SummaryRow(group, track));
  }
  section.tables.push_back(std::move(table));
  return section;
}

std::vector<std::string> FrameCategories(int frames, int from) {
  std::vector<std::string> categories;
  for (int k = from; k < frames; ++k) categories.push_back("frame " + std::to_string(k));
  return categories;
}

ReportSection ChartsSection(const StudySequence& sequence) {
  ReportSection section{"Sequence: quality and stability over frames", {}, {}, {}, {}};
  section.paragraphs.push_back("One chart pair per group of techniques reading the same frames.");
  for (const SequenceGroup& group : sequence.groups) {
    BarChart flip{"FLIP per frame, " + GroupLabel(group), "FLIP", FrameCategories(sequence.frames, 0), {}, {}};
    BarChart flicker{"Flicker per frame, " + GroupLabel(group), "codes", FrameCategories(sequence.frames, 1),
                     {"ground truth"}, {{group.groundTruthFlicker.begin() + 1, group.groundTruthFlicker.end()}}};
    for (const SequenceTrack& track : group.tracks) {
      flip.series.push_back(track.technique);
      flip.values.push_back(QualityOverFrames(track, &passes::QualityScores::flip));
      flicker.series.push_back(track.technique);
      flicker.values.push_back({track.flicker.begin() + 1, track.flicker.end()});
    }
    section.charts.push_back(std::move(flip));
    if (sequence.frames > 1) section.charts.push_back(std::move(flicker));
  }
  return section;
}

ReportImage StripImage(const std::string& title, const RgbImage& crop, int zoom, const std::string& group) {
  return {title, EncodePng(crop.width, crop.height, 3, crop.rgb), crop.width, crop.height, zoom, group};
}

ReportSection StripSection(const StudySequence& sequence, const SequenceImages& images) {
  const PixelRect& r = images.Region();
  ReportSection section{"Sequence: frame strips", {}, {}, {}, {}};
  section.paragraphs.push_back("Frames 0.." + std::to_string(sequence.frames - 1) + " of each technique in the " +
                               std::to_string(r.width) + "x" + std::to_string(r.height) + " window at (" +
                               std::to_string(r.x) + ", " + std::to_string(r.y) +
                               ") (the aliased frame's hardest region), x" + std::to_string(images.Zoom()) +
                               ". In the image comparer each technique is a group: flip between its frames to "
                               "see flicker and ghosts move. Full frames: images/sequence/.");
  section.imageComparer = true;
  auto addStrip = [&](const std::string& folder, const std::string& label) {
    const auto found = images.Strips().find(folder);
    if (found == images.Strips().end()) return;
    for (std::size_t k = 0; k < found->second.size(); ++k) {
      section.images.push_back(StripImage(label + ", frame " + std::to_string(k), found->second[k], images.Zoom(),
                                          "sequence: " + label));
    }
  };
  addStrip(kGroundTruthSequenceFolder, "ground truth");
  for (const SequenceGroup& group : sequence.groups) {
    for (const SequenceTrack& track : group.tracks) addStrip(track.folder, TrackLabel(group, track));
  }
  return section;
}

std::vector<std::string> CountersRow(const std::string& technique, const std::string& strategy, int frame,
                                     const SequenceFrameCounters& c, std::uint64_t pixels) {
  auto perPixel = [&](std::uint64_t bytes) { return FormatFixed(static_cast<double>(bytes) / static_cast<double>(pixels), 2); };
  return {technique, strategy, std::to_string(frame), std::to_string(c.dispatches), std::to_string(c.lanes.waves),
          FormatPercent(c.lanes.lanesActive, c.lanes.lanesLaunched), perPixel(c.historyBytes), perPixel(c.dramBytes),
          FormatFixed(c.estimatedMicroseconds, 1)};
}

ReportSection CountersSection(const study::Study& study) {
  const StudySequence& sequence = *study.sequence;
  const std::uint64_t pixels = std::uint64_t(study.groundTruth.colour.Width()) * std::uint64_t(study.groundTruth.colour.Height());
  ReportSection section{"Sequence: counters per frame", {}, {}, {}, {}};
  section.paragraphs.push_back(
      "Every dispatch of a pass (or of a frame's draw and resolve) on each frame, summed: history bytes are those "
      "read and written on the pass's history textures. Times are estimates of the timing model "
      "(docs/timing-model.md), not measurements.");
  ReportTable table{"Per-frame counters",
                    {"technique", "strategy", "frame", "dispatches", "waves", "active lanes %", "history B/px",
                     "DRAM B/px", "estimated µs"},
                    {}};
  for (const SequenceGroup& group : sequence.groups) {
    for (const SequenceTrack& track : group.tracks) {
      for (const study::SequenceStrategyRun& run : track.runs) {
        const std::string strategy = track.pass.empty() ? "draw" : std::string(passes::StrategyName(run.strategy));
        for (std::size_t k = 0; k < run.frames.size(); ++k) {
          table.rows.push_back(CountersRow(TrackLabel(group, track), strategy, static_cast<int>(k), run.frames[k], pixels));
        }
      }
    }
  }
  section.tables.push_back(std::move(table));
  return section;
}

// Seed 001's timing table ("Single Pass / Timing (ms)", PS4, 1080p): the temporal rows, each with
// the dispatches of aasim's passes that do its work (docs/temporal.md "Cost").
struct SeedTiming {
  const char* item;
  double milliseconds;
  const char* pass;                          // the registered pass whose last frame is measured
  std::vector<std::string_view> dispatches;  // empty: every dispatch of the pass
};
const std::vector<SeedTiming>& SeedTimings() {
  static const std::vector<SeedTiming> kTimings = {
      {"BFECC single value", 0.3, "hraa", {"hraa/forward"}},
      {"Temporal FLIPQUAD (TFQ)", 0.2, "tfq", {"tfq/resolve"}},
      {"TAA", 0.6, "hraa", {"hraa/forward", "hraa/taa"}},
      {"TFQ + TAA", 0.62, "hraa", {}},
  };
  return kTimings;
}

// The timing's estimate on the pass's cheapest strategy at the run's size, scaled to 1080p by
// pixel count; nullopt when the pass did not run.
std::optional<double> Estimated1080pMs(const study::Study& study, const SeedTiming& timing) {
  const double pixels = double(study.groundTruth.colour.Width()) * double(study.groundTruth.colour.Height());
  std::optional<double> best;
  for (const study::StudyPass& pass : study.passes) {
    if (pass.name != timing.pass || !pass.sweepPoint.empty()) continue;
    for (const study::StudyPassRun& run : pass.runs) {
      double microseconds = 0.0;
      for (std::size_t i = run.firstDispatch; i < run.endDispatch; ++i) {
        const sim::DispatchReport& report = study.dispatches[i].report;
        const bool counted = timing.dispatches.empty() ||
                             std::find(timing.dispatches.begin(), timing.dispatches.end(), report.name) != timing.dispatches.end();
        if (counted) microseconds += report.time.totalMicroseconds;
      }
      const double ms = microseconds / 1000.0 * kSeedTimingPixels / pixels;
      best = best ? std::min(*best, ms) : ms;
    }
  }
  return best;
}

ReportSection SeedTimingSection(const study::Study& study) {
  ReportSection section{"Sequence: seed 001's temporal timings beside aasim's estimates", {}, {}, {}, {}};
  section.paragraphs.push_back(
      "Seed 001's PS4 table at 1080p next to the timing model's estimate (docs/timing-model.md, not a measurement) "
      "of the dispatches of aasim's passes that do the same work, on the sequence's last frame, scaled to 1080p by "
      "pixel count. TFQ + TAA is the hraa pass with its temporal FLIPQUAD on (its default). The mapping and why "
      "TFQ is estimated above the seed: docs/temporal.md \"Cost\".");
  ReportTable table{"Seed 001 (PS4) vs aasim estimate, ms at 1080p", {"item", "seed ms", "aasim pass", "dispatches", "estimate ms"}, {}};
  for (const SeedTiming& timing : SeedTimings()) {
    std::string dispatches;
    for (const std::string_view name : timing.dispatches) dispatches += (dispatches.empty() ? "" : ", ") + std::string(name);
    const std::optional<double> estimate = Estimated1080pMs(study, timing);
    table.rows.push_back({timing.item, FormatFixed(timing.milliseconds, 2), timing.pass,
                          dispatches.empty() ? "all" : dispatches, estimate ? FormatFixed(*estimate, 2) : "not run"});
  }
  section.tables.push_back(std::move(table));
  return section;
}

}  // namespace

nlohmann::ordered_json SeedTimingJson(const study::Study& study) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const SeedTiming& timing : SeedTimings()) {
    const std::optional<double> estimate = Estimated1080pMs(study, timing);
    rows.push_back({{"item", timing.item},
                    {"seed_ps4_1080p_ms", timing.milliseconds},
                    {"pass", timing.pass},
                    {"dispatches", timing.dispatches.empty() ? nlohmann::ordered_json("all")
                                                             : nlohmann::ordered_json(std::vector<std::string>(
                                                                   timing.dispatches.begin(), timing.dispatches.end()))},
                    {"estimated_1080p_ms", estimate ? nlohmann::ordered_json(*estimate) : nlohmann::ordered_json(nullptr)}});
  }
  return rows;
}

std::vector<ReportSection> SequenceSections(const study::Study& study, const SequenceImages& images) {
  if (!study.sequence) return {};
  return {SummarySection(*study.sequence), ChartsSection(*study.sequence), StripSection(*study.sequence, images),
          CountersSection(study), SeedTimingSection(study)};
}

}  // namespace cli
