// The main job's outputs (see study_report.h).

#include "cli/study_report.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli/counters_json.h"
#include "cli/dispatch_output.h"
#include "cli/eqaa_output.h"
#include "cli/eqaa_study_report.h"
#include "cli/frame_output.h"
#include "cli/image_io.h"
#include "cli/number_format.h"
#include "cli/pattern_report.h"
#include "cli/report_json.h"
#include "cli/report_images.h"
#include "cli/text_io.h"
#include "passes/registry.h"

namespace cli {
namespace {

using study::ModeSlug;
using study::ScoredImage;
using study::StudyGroundTruth;
using study::StudyPass;
using study::StudyPassRun;
using study::StudyResolve;

// Previews at most this wide keep report.html a few MB at 1080p; full images are in images/.
constexpr int kPreviewMaxWidth = 960;
// Crops of the hardest regions: three windows of about 1/16 of the image height, shown at
// roughly 256 pixels.
constexpr int kCropCount = 3;
constexpr int kCropDisplayPixels = 256;
constexpr const char* kEstimateNote =
    "Times are estimates of the timing model (docs/timing-model.md) on the configured GPU, not "
    "measurements.";

const std::string kImages = "images/";

// ---- Files ----------------------------------------------------------------------------------

void StageColour(OutputDir& dir, const std::string& path, const sim::Texture2D<glm::vec4>& colour) {
  StagePngLater(dir, path, colour.Width(), colour.Height(), 3, SrgbImage(colour.Texels()));
}

void StageErrorFiles(OutputDir& dir, const ScoredImage& image) {
  const int width = image.colour.Width(), height = image.colour.Height();
  const passes::QualityMaps& maps = image.quality.maps;
  const ExrChannel channels[] = {
      {"squared_error", maps.squaredError}, {"ssim_error", maps.ssimError}, {"flip", maps.flip}};
  WriteExr(dir.Stage(kImages + image.folder + "/error.exr"), width, height, channels);
  RgbImage flip = ErrorPreview(maps.flip, width, height, 1.0f, 1);
  StagePngLater(dir, kImages + image.folder + "/flip.png", flip.width, flip.height, 3, std::move(flip.rgb));
}

void StageGroundTruth(OutputDir& dir, const StudyGroundTruth& truth) {
  const scenes::GroundTruthImage& image = truth.image;
  std::vector<float> r, g, b;
  for (const glm::vec3& colour : image.colour) {
    r.push_back(colour.r);
    g.push_back(colour.g);
    b.push_back(colour.b);
  }
  const ExrChannel channels[] = {
      {"R", r}, {"G", g}, {"B", b}, {"coverage", image.coverage}, {"edge", truth.edgeMask}};
  WriteExr(dir.Stage(kImages + "ground-truth/ground-truth.exr"), image.width, image.height, channels);
  StagePngLater(dir, kImages + "ground-truth/colour.png", image.width, image.height, 3, SrgbImage(truth.colour.Texels()));
  StagePngLater(dir, kImages + "ground-truth/edges.png", image.width, image.height, 1, MaskImage(truth.edgeMask));
}

// The 8-bit codes as PNG (what the pass's render target held) and the values as EXR.
void StageLayer(OutputDir& dir, const std::string& folder, const passes::PassLayer& layer) {
  LayerPng png = LayerPngImage(layer);
  StagePngLater(dir, folder + layer.name + ".png", layer.width, layer.height, png.channels, std::move(png.pixels));
  WriteLayerExr(dir.Stage(folder + layer.name + ".exr"), layer);
}

nlohmann::ordered_json PassNamesJson(std::span<const passes::PassConfig> passes) {
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (const passes::PassConfig& pass : passes) names.push_back(pass.Info().name);
  return names;
}

void StagePassFiles(OutputDir& dir, const StudyPass& pass) {
  StageColour(dir, kImages + pass.image.folder + "/output.png", pass.image.colour);
  StageErrorFiles(dir, pass.image);
}

}  // namespace

void StagePassLayers(OutputDir& dir, const StudyPass& pass) {
  for (const StudyPassRun& run : pass.runs) {
    const std::string folder = kImages + pass.image.folder + "/" + std::string(passes::StrategyName(run.strategy)) + "/";
    for (const passes::PassLayer& layer : run.layers) StageLayer(dir, folder, layer);
  }
}

namespace {

std::string HeatFolder(const Study& study, std::size_t dispatch) {
  for (const StudyFrame& frame : study.frames) {
    if (frame.image.label == study.dispatches[dispatch].frame) return kImages + "heat/" + ModeSlug(frame.mode) + "/";
  }
  return kImages + "heat/";
}

void StageHeatMaps(OutputDir& dir, const Study& study) {
  for (std::size_t i = 0; i < study.dispatches.size(); ++i) {
    const sim::DispatchReport& report = study.dispatches[i].report;
    if (report.heat.Empty()) continue;
    const std::string stem = HeatFolder(study, i) + HeatMapStem(i, report.name, study.dispatches[i].strategy);
    WriteHeatMap(report.heat, dir.Stage(stem + ".exr"), dir.Stage(stem + ".png"));
  }
}

// ---- report.json and the CSV files -------------------------------------------------------------

nlohmann::ordered_json IndexRange(std::size_t first, std::size_t end) {
  nlohmann::ordered_json indices = nlohmann::ordered_json::array();
  for (std::size_t i = first; i < end; ++i) indices.push_back(i);
  return indices;
}

double PassMicroseconds(const Study& study, const StudyPassRun& run) {
  double total = 0.0;
  for (std::size_t i = run.firstDispatch; i < run.endDispatch; ++i) total += study.dispatches[i].report.time.totalMicroseconds;
  return total;
}

nlohmann::ordered_json ResolvesJson(const StudyFrame& frame) {
  nlohmann::ordered_json resolves = nlohmann::ordered_json::array();
  for (const StudyResolve& resolve : frame.resolves) {
    resolves.push_back({{"name", resolve.name},
                        {"folder", kImages + resolve.image.folder},
                        {"dispatches", IndexRange(resolve.firstDispatch, resolve.endDispatch)},
                        {"quality", QualityJson(resolve.image.quality.scores)}});
  }
  return resolves;
}

nlohmann::ordered_json FrameJson(const StudyFrame& frame, const RunCommandOptions& options) {
  return {{"mode", frame.image.label},
          {"samples", frame.mode.coverageSamples},
          {"depth_samples", frame.mode.depthSamples},
          {"fragments", frame.mode.fragments},
          {"pattern", options.pattern},
          {"policy", frame.policy},
          {"folder", kImages + frame.image.folder},
          {"draw_dispatch", frame.drawDispatch},
          {"quality", QualityJson(frame.image.quality.scores)},
          {"resolve_dispatch", frame.drawDispatch + 1},
          {"resolves", ResolvesJson(frame)},
          {"srgb8", frame.srgb8 ? nlohmann::ordered_json{{"folder", kImages + frame.srgb8->folder},
                                                         {"quality", QualityJson(frame.srgb8->quality.scores)}}
                                : nlohmann::ordered_json(nullptr)},
          {"fragment_counters", FragmentCountersJson(frame.fragments)}};
}

nlohmann::ordered_json VariantJson(const std::optional<study::VariantDifference>& variant) {
  if (!variant) return nullptr;
  return {{"pass", variant->baseline},
          {"differing_pixels", variant->pixels},
          {"differing_pixels_over_one_code", variant->pixelsOverOneCode},
          {"max_code_difference", variant->maxCodes},
          {"psnr_db", Number(variant->psnr)}};
}

nlohmann::ordered_json PassJson(const Study& study, const StudyPass& pass) {
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const StudyPassRun& run : pass.runs) {
    runs.push_back({{"strategy", passes::StrategyName(run.strategy)},
                    {"dispatches", IndexRange(run.firstDispatch, run.endDispatch)},
                    {"estimated_us_total", PassMicroseconds(study, run)}});
  }
  return {{"name", pass.name},
          {"sweep_point", pass.sweepPoint.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(pass.sweepPoint)},
          {"input_frame", pass.inputFrame},
          {"studied_dispatch", pass.studiedDispatch},
          {"folder", kImages + pass.image.folder},
          {"settings", pass.settings},
          {"edge_pixels", pass.workItems},
          {"work_set", {{"pixels", pass.workSet.pixels}, {"quads", pass.workSet.quads}, {"tiles_8x8", pass.workSet.tiles}}},
          {"strategies_identical", pass.difference.Identical()},
          {"differing_pixels", pass.difference.pixels.pixels},
          {"difference", pass.difference.Identical() ? nlohmann::ordered_json(nullptr)
                                                     : nlohmann::ordered_json(pass.difference.Describe())},
          {"quality", QualityJson(pass.image.quality.scores)},
          {"variant_of", VariantJson(pass.variant)},
          {"strategies", runs}};
}

std::string QualityCsv(const Study& study) {
  std::string csv = "image,kind,psnr_db,ssim,flip,edge_psnr_db,edge_ssim,edge_flip,edge_pixels\n";
  auto row = [&](const ScoredImage& image, const char* kind) {
    const passes::QualityScores& s = image.quality.scores;
    for (const std::string& field :
         {CsvField(image.label), std::string(kind), FormatFixed(s.psnr, 4), FormatFixed(s.ssim, 6), FormatFixed(s.flip, 6),
          FormatFixed(s.edgePsnr, 4), FormatFixed(s.edgeSsim, 6), FormatFixed(s.edgeFlip, 6), std::to_string(s.edgePixels)}) {
      csv += field;
      csv += ',';
    }
    csv.back() = '\n';
  };
  for (const StudyFrame& frame : study.frames) {
    row(frame.image, "frame");
    for (const StudyResolve& resolve : frame.resolves) row(resolve.image, "resolve");
    if (frame.srgb8) row(*frame.srgb8, "frame sRGB8");
  }
  for (const StudyPass& pass : study.passes) row(pass.image, "pass");
  return csv;
}

// ---- report.html -------------------------------------------------------------------------------

ReportImage Embed(const std::string& title, const RgbImage& image, int displayScale = 1, std::string group = {}) {
  return {title, EncodePng(image.width, image.height, 3, image.rgb), image.width, image.height, displayScale,
          std::move(group)};
}

constexpr const char* kWholeFrameGroup = "whole frame";

// Every image the report compares, ground truth first, in one list.
struct Shown {
  std::string label;
  const sim::Texture2D<glm::vec4>* colour;
  const ScoredImage* scored;  // null for the ground truth
};

std::vector<Shown> ShownImages(const Study& study, const sim::Texture2D<glm::vec4>& truth) {
  std::vector<Shown> shown{{"ground truth (" + std::to_string(study.groundTruth.image.samplesPerPixel) + " rays/px)",
                            &truth, nullptr}};
  for (const StudyFrame& frame : study.frames) {
    shown.push_back({frame.image.label, &frame.image.colour, &frame.image});
    for (const StudyResolve& resolve : frame.resolves) {
      shown.push_back({resolve.image.label, &resolve.image.colour, &resolve.image});
    }
    if (frame.srgb8) shown.push_back({frame.srgb8->label, &frame.srgb8->colour, &*frame.srgb8});
  }
  for (const StudyPass& pass : study.passes) {
    shown.push_back({pass.Label() + " on " + pass.inputFrame, &pass.image.colour, &pass.image});
  }
  return shown;
}

ReportSection RunSection(const Study& study, const RunCommandOptions& options) {
  const StudyGroundTruth& truth = study.groundTruth;
  std::string modes;
  for (const StudyFrame& frame : study.frames) modes += (modes.empty() ? "" : ", ") + frame.image.label;
  ReportSection section{"Run", {}, {}, {}, {}};
  section.paragraphs = {
      "Scene " + study.sceneName + " (" + std::to_string(study.triangles) + " triangles) at " +
          std::to_string(options.width) + "x" + std::to_string(options.height) + ", rendered on the modelled GPU '" +
          study.gpu.name + "' under " + modes + " (pattern " + options.pattern + ", arbitration policy " +
          options.policy + "; draw order " + options.setup.drawOrder +
          (options.setup.depthPrepass ? ", a depth pre-pass then an EQUAL draw" : ", no depth pre-pass") +
          ", at most " + std::to_string(options.setup.maxZPlanes) + " Z planes per tile: docs/eqaa.md \"CRAA setup\").",
      "Ground truth: Embree, " + std::to_string(truth.image.samplesPerPixel) +
          " stratified rays per pixel, box filter, the same material model; " +
          std::to_string(passes::CountSelected(truth.edgeMask)) + " edge pixels (pixels whose rays saw more than one "
          "primitive). " + (truth.cacheHit ? "Read from the cache." : "Rendered for this run.") +
          " Post passes work on the " + (study.frames.empty() ? std::string("-") : study.frames.front().image.label) +
          " frame (a pass reading a multisampled surface, on the first mode with its sample count) as an 8-bit sRGB "
          "target holds it, shown as 'sRGB8': compare a pass with that image, not with the float frame, whose FLIP "
          "does not include the 8-bit quantisation every pass output has.",
      kEstimateNote,
      "Host time " + FormatFixed(study.hostSeconds, 1) + " s on " + std::to_string(study.threads) +
          " threads (the simulator's own wall time, not a GPU time). Full-resolution images, EXR layers and every "
          "counter are in images/, report.json, counters.csv and quality.csv next to this file."};
  return section;
}

ReportSection ImagesSection(const std::vector<Shown>& shown, int width, int height) {
  const int factor = PreviewFactor(width, kPreviewMaxWidth);
  ReportSection section{"Images", {}, {}, {}, {}};
  section.paragraphs.push_back(
      "A mode's image is its box resolve (UNKNOWN samples dropped); the images named after a resolve are that "
      "resolve of the same surface (\"fetch\": the shader fetch path, UNKNOWN samples reading fragment 0; "
      "\"craa-simple\", \"craa-lut\": seed 001's coverage reconstruction of 1F surfaces). All are dispatches on "
      "the machine; the EQAA study below compares them.");
  section.paragraphs.push_back(factor == 1 ? "Full resolution."
                                           : "Previews averaged over " + std::to_string(factor) + "x" +
                                                 std::to_string(factor) + " pixels; the hardest regions below are "
                                                 "at full resolution.");
  for (const Shown& image : shown) {
    section.images.push_back(
        Embed(image.label, Preview(image.colour->Texels(), width, height, factor), 1, kWholeFrameGroup));
  }
  return section;
}

// Where the first frame (the aliased one) is furthest from the ground truth by FLIP: one section
// per region, every image cropped to it.
// Crops are an eighth of the height rounded to whole 8x8 tiles, zoomed to about kCropDisplayPixels.
int CropSize(int width, int height) { return std::min({std::max(8, height / 16 / 8 * 8), width, height}); }
int CropZoom(int size) { return std::max(1, kCropDisplayPixels / size); }

std::vector<ReportSection> CropSections(const Study& study, const std::vector<Shown>& shown, int width, int height) {
  if (study.frames.empty()) return {};
  const int size = CropSize(width, height);
  const int zoom = CropZoom(size);
  const std::string& aliased = study.frames.front().image.label;
  std::vector<ReportSection> sections;
  for (const PixelRect& rect :
       HardestRegions(study.frames.front().image.quality.maps.flip, width, height, size, kCropCount)) {
    const std::string where = "(" + std::to_string(rect.x) + ", " + std::to_string(rect.y) + ")";
    ReportSection section{"Hard region " + std::to_string(sections.size() + 1) + ": " + std::to_string(size) + "x" +
                              std::to_string(size) + " pixels at " + where,
                          {}, {}, {}, {}};
    if (sections.empty()) {
      section.paragraphs.push_back("The windows where " + aliased + " has the largest total FLIP error, shown x" +
                                   std::to_string(zoom) + " with nearest-neighbour pixels.");
    }
    const std::string group = "region " + std::to_string(sections.size() + 1) + " at " + where;
    for (const Shown& image : shown) {
      section.images.push_back(Embed(image.label, Crop(image.colour->Texels(), width, rect), zoom, group));
    }
    sections.push_back(std::move(section));
  }
  return sections;
}

ReportSection ComparerSection() {
  ReportSection section{"Compare two images", {}, {}, {}, {}};
  section.paragraphs.push_back(
      "Pick two images and a region (the whole frame as previewed above, or one of the hard regions below at full "
      "resolution), then flip between them (button or key f) or wipe across with the slider; pixels are enlarged "
      "nearest-neighbour. Defaults: the ground truth against the aliased frame on the hardest region.");
  section.imageComparer = true;
  return section;
}

ReportSection QualitySection(const std::vector<Shown>& shown) {
  ReportSection section{"Quality against the ground truth", {}, {}, {}, {}};
  section.paragraphs.push_back(
      "PSNR (dB, higher is better) and SSIM (1 is identical) on sRGB-encoded values, LDR-FLIP (0 is identical) on "
      "linear colour; \"edge\" columns average over the ground truth's edge pixels only (docs/metrics.md).");
  ReportTable table{"Scores", {"image", "PSNR", "SSIM", "FLIP", "edge PSNR", "edge SSIM", "edge FLIP"}, {}};
  BarChart chart{"Mean FLIP error (lower is better)", "FLIP", {}, {"all pixels", "edge pixels"}, {{}, {}}, false};
  for (const Shown& image : shown) {
    if (image.scored == nullptr) continue;
    const passes::QualityScores& s = image.scored->quality.scores;
    table.rows.push_back({image.label, FormatFixed(s.psnr, 2), FormatFixed(s.ssim, 4), FormatFixed(s.flip, 4), FormatFixed(s.edgePsnr, 2),
                          FormatFixed(s.edgeSsim, 4), FormatFixed(s.edgeFlip, 4)});
    chart.categories.push_back(image.label);
    chart.values[0].push_back(s.flip);
    chart.values[1].push_back(std::isfinite(s.edgeFlip) ? s.edgeFlip : 0.0);
  }
  section.tables.push_back(std::move(table));
  section.charts.push_back(std::move(chart));
  return section;
}

ReportSection ErrorMapsSection(const std::vector<Shown>& shown, int width, int height) {
  const int factor = PreviewFactor(width, kPreviewMaxWidth);
  ReportSection section{"Error maps", {}, {}, {}, {}};
  section.paragraphs.push_back("Per-pixel FLIP error against the ground truth, black (0) to pale yellow (1), magma "
                               "colour map" + std::string(factor > 1 ? ", averaged like the previews." : "."));
  for (const Shown& image : shown) {
    if (image.scored == nullptr) continue;
    section.images.push_back(
        Embed("FLIP: " + image.label, ErrorPreview(image.scored->quality.maps.flip, width, height, 1.0f, factor)));
  }
  return section;
}

ReportImage HeatImage(const std::string& title, const sim::TileHeatMap& heat) {
  const HeatMapImage preview = HeatMapPreview(heat);
  return {title, EncodePng(preview.width, preview.height, 3, preview.rgb), preview.width, preview.height, 1};
}

ReportSection FramesSection(const Study& study) {
  ReportSection section{"EQAA frames", {}, {}, {}, {}};
  section.paragraphs.push_back(
      "The material draw of each mode: lanes of its pixel waves (helpers are uncovered pixels of live quads), the "
      "colour block's fragment counters (docs/eqaa.md), and a lane-utilization heat map per 8x8 tile (dark blue 0, "
      "yellow 1, grey: no lanes). " + std::string(kEstimateNote));
  ReportTable lanes{"Material draw", {"mode", "waves", "lanes launched", "active %", "helper %", "dead (empty) %",
                                      "DRAM MB", "est. µs"}, {}};
  ReportTable fragments{"Colour block counters", {"counter"}, {}};
  for (const StudyFrame& frame : study.frames) {
    const sim::DispatchReport& draw = study.dispatches[frame.drawDispatch].report;
    const sim::LaneCounters& l = draw.lanes;
    lanes.rows.push_back({frame.image.label, std::to_string(l.waves), std::to_string(l.lanesLaunched),
                          FormatPercent(l.lanesActive, l.lanesLaunched), FormatPercent(l.lanesHelper, l.lanesLaunched),
                          FormatPercent(l.lanesDeadEmpty, l.lanesLaunched), FormatFixed(double(draw.DramBytes()) / 1e6, 2),
                          FormatFixed(draw.time.totalMicroseconds, 1)});
    fragments.header.push_back(frame.image.label);
    std::size_t row = 0;
    frame.fragments.ForEach([&](const char* name, std::uint64_t value) {
      // The per-count histograms are in report.json; the table keeps the events.
      if (std::string_view(name).starts_with("fragments/before_") || std::string_view(name).starts_with("fragments/after_")) {
        return;
      }
      if (row == fragments.rows.size()) fragments.rows.push_back({name});
      fragments.rows[row++].push_back(std::to_string(value));
    });
    if (!draw.heat.Empty()) section.images.push_back(HeatImage("material draw, " + frame.image.label, draw.heat));
  }
  section.tables = {std::move(lanes), std::move(fragments)};
  return section;
}

std::string DispatchLabel(const Study& study, std::size_t i) {
  return study.dispatches[i].report.name + " [" + study.dispatches[i].strategy + "]";
}

void AddLanes(BarChart& chart, const std::string& label, const sim::LaneCounters& lanes) {
  chart.categories.push_back(label);
  chart.values[0].push_back(double(lanes.lanesActive));
  chart.values[1].push_back(double(lanes.lanesHelper));
  chart.values[2].push_back(double(lanes.lanesDeadStencil));
  chart.values[3].push_back(double(lanes.lanesDeadEmpty));
}

BarChart LanesChart(std::string title) {
  return {std::move(title), "lanes", {}, {"active", "helper", "dead (stencil)", "dead (empty)"}, {{}, {}, {}, {}}, true};
}

void AddStrategyCharts(ReportSection& section, const Study& study, const StudyPass& pass) {
  BarChart studied = LanesChart("Lanes launched by " + pass.studiedDispatch);
  BarChart lanes = LanesChart("Lanes by kind, every dispatch of the pass");
  BarChart waves{"Waves per dispatch", "waves", {}, {"waves"}, {{}}, false};
  BarChart bytes{"DRAM traffic per dispatch (distinct 64-byte lines)", "MB", {}, {"DRAM"}, {{}}, false};
  BarChart time{"Estimated time (an estimate: docs/timing-model.md)", "µs", {}, {"dispatch"}, {{}}, false};
  for (const StudyPassRun& run : pass.runs) {
    for (std::size_t i = run.firstDispatch; i < run.endDispatch; ++i) {
      const sim::DispatchReport& report = study.dispatches[i].report;
      const std::string label = DispatchLabel(study, i);
      for (BarChart* chart : {&waves, &bytes, &time}) chart->categories.push_back(label);
      AddLanes(lanes, label, report.lanes);
      if (report.name == pass.studiedDispatch) AddLanes(studied, label, report.lanes);
      waves.values[0].push_back(double(report.lanes.waves));
      bytes.values[0].push_back(double(report.DramBytes()) / 1e6);
      time.values[0].push_back(report.time.totalMicroseconds);
    }
    time.categories.push_back("whole pass [" + std::string(passes::StrategyName(run.strategy)) + "]");
    time.values[0].push_back(PassMicroseconds(study, run));
  }
  section.charts = {std::move(studied), std::move(lanes), std::move(waves), std::move(bytes), std::move(time)};
}

std::span<const study::DispatchRecord> RunDispatches(const Study& study, const StudyPassRun& run) {
  return std::span(study.dispatches).subspan(run.firstDispatch, run.endDispatch - run.firstDispatch);
}

// Seed 000's argument for queues, with this frame's numbers: a stencil-culled shader runs whole
// quads and packs them into waves by 8x8 hi-stencil tile, so the fewer work-set pixels per quad
// and per tile, the more of its lanes idle; a queue packs the pixels densely.
std::string ScatterParagraph(const passes::WorkSetShape& shape) {
  if (shape.pixels == 0) return "The work set is empty.";
  const double perQuad = double(shape.pixels) / double(shape.quads);
  const double perTile = double(shape.pixels) / double(shape.tiles);
  return "The work set is scattered over " + std::to_string(shape.quads) + " quads and " +
         std::to_string(shape.tiles) + " 8x8 tiles: " + FormatFixed(perQuad, 2) + " pixels per touched quad (of 4) and " +
         FormatFixed(perTile, 1) + " per touched tile (of 64). The stencil strategy launches every lane of a touched "
         "quad, so at best " + FormatPercent(shape.pixels, 4 * shape.quads) + "% of its lanes work; the queue packs 64 work-set pixels "
         "per wave.";
}

std::string VariantParagraph(const StudyPass& pass, const study::VariantDifference& variant) {
  const std::uint64_t pixels = std::uint64_t(pass.image.colour.Width()) * std::uint64_t(pass.image.colour.Height());
  if (variant.pixels == 0) return "Against " + variant.baseline + " on the same frame: the same 8-bit image.";
  return "Against " + variant.baseline + " on the same frame: " + std::to_string(variant.pixels) + " pixels (" +
         FormatPercent(variant.pixels, pixels) + "%) differ in their 8-bit sRGB codes, " +
         std::to_string(variant.pixelsOverOneCode) + " of them by more than one code, by up to " +
         std::to_string(variant.maxCodes) + " codes; PSNR between the two images " + FormatFixed(variant.psnr, 2) +
         " dB.";
}

ReportSection PassSection(const Study& study, const StudyPass& pass) {
  ReportSection section{"Dispatch strategies: " + pass.Label(), {}, {}, {}, {}};
  section.paragraphs.push_back(
      pass.description + " (" + pass.settings + "), on the " + pass.inputFrame + " frame; " +
      std::to_string(pass.workItems) + " pixels in its work set. Stencil: a full-screen pixel shader culled by "
      "stencil (quads run when any pixel passes, 16 quads per wave). Queue: the work-set pixels appended to a "
      "buffer, then an indirect compute dispatch over exactly that many items.");
  section.paragraphs.push_back(ScatterParagraph(pass.workSet));
  if (pass.variant) section.paragraphs.push_back(VariantParagraph(pass, *pass.variant));
  section.paragraphs.push_back(pass.difference.Identical()
                                   ? "The strategies' outputs and layers are bit-identical."
                                   : "The strategies' outputs DIFFER: " + pass.difference.Describe() + ". A bug.");
  if (pass.runs.size() == 2) {
    const StudyPassRun &a = pass.runs[0], &b = pass.runs[1];
    std::vector<std::vector<std::string>> rows =
        DispatchComparisonRows(pass.studiedDispatch, passes::StrategyName(a.strategy), RunDispatches(study, a),
                               passes::StrategyName(b.strategy), RunDispatches(study, b));
    ReportTable table{pass.studiedDispatch + " under both strategies", rows.front(), {}};
    table.rows.assign(rows.begin() + 1, rows.end());
    section.tables.push_back(std::move(table));
  }
  AddStrategyCharts(section, study, pass);
  for (const StudyPassRun& run : pass.runs) {
    for (std::size_t i = run.firstDispatch; i < run.endDispatch; ++i) {
      const sim::DispatchReport& report = study.dispatches[i].report;
      if (report.name == pass.studiedDispatch && !report.heat.Empty()) {
        section.images.push_back(HeatImage("lane utilization, " + DispatchLabel(study, i), report.heat));
      }
    }
  }
  return section;
}

sim::LaneCounters RunLanes(const Study& study, const StudyPassRun& run) {
  sim::LaneCounters lanes;
  for (const study::DispatchRecord& record : RunDispatches(study, run)) lanes.Merge(record.report.lanes);
  return lanes;
}

std::uint64_t RunDramBytes(const Study& study, const StudyPassRun& run) {
  std::uint64_t bytes = 0;
  for (const study::DispatchRecord& record : RunDispatches(study, run)) bytes += record.report.DramBytes();
  return bytes;
}

// Every pass of the run under every strategy in one table: the cost side (every dispatch of the
// pass summed) next to the quality side (the strategies' images are identical, so once per pass).
ReportSection PassesComparedSection(const Study& study) {
  ReportSection section{"Passes compared", {kEstimateNote}, {}, {}, {}};
  section.paragraphs.push_back(
      "Per pass and strategy, over every dispatch of the pass: the work set (pixels the pass's detect kept), waves, "
      "launched lanes split into active, helper and dead (stencil-culled or empty) lanes, DRAM traffic and the "
      "estimated time, next to the pass's quality against the ground truth (PSNR and SSIM on sRGB values, FLIP on "
      "linear colour, edge FLIP over the ground truth's edge pixels).");
  ReportTable table{"Cost and quality per pass and strategy",
                    {"pass", "strategy", "work set px", "waves", "lanes", "active %", "helper %", "dead %", "DRAM MB",
                     "estimated µs", "PSNR", "SSIM", "FLIP", "edge FLIP"},
                    {}};
  BarChart time{"Estimated time per pass (docs/timing-model.md)", "µs", {}, {}, {}, false};
  for (const passes::Strategy strategy : passes::kAllStrategies) {
    time.series.emplace_back(passes::StrategyName(strategy));
    time.values.emplace_back();
  }
  for (const StudyPass& pass : study.passes) {
    time.categories.push_back(pass.Label());
    for (std::vector<double>& values : time.values) values.push_back(0.0);
    const passes::QualityScores& q = pass.image.quality.scores;
    for (const StudyPassRun& run : pass.runs) {
      const sim::LaneCounters lanes = RunLanes(study, run);
      const double microseconds = PassMicroseconds(study, run);
      table.rows.push_back({pass.Label(), std::string(passes::StrategyName(run.strategy)), std::to_string(pass.workItems),
                            std::to_string(lanes.waves), std::to_string(lanes.lanesLaunched),
                            FormatPercent(lanes.lanesActive, lanes.lanesLaunched),
                            FormatPercent(lanes.lanesHelper, lanes.lanesLaunched),
                            FormatPercent(lanes.lanesDeadStencil + lanes.lanesDeadEmpty, lanes.lanesLaunched),
                            FormatFixed(double(RunDramBytes(study, run)) / 1e6, 2), FormatFixed(microseconds, 1),
                            FormatFixed(q.psnr, 2), FormatFixed(q.ssim, 4), FormatFixed(q.flip, 4),
                            FormatFixed(q.edgeFlip, 4)});
      time.values[static_cast<std::size_t>(run.strategy)].back() = microseconds;
    }
  }
  section.tables.push_back(std::move(table));
  section.charts.push_back(std::move(time));
  return section;
}

// Passes run at the points of a sweep axis, by pass, in run order.
std::vector<std::vector<const StudyPass*>> SweptPasses(const Study& study) {
  std::vector<std::vector<const StudyPass*>> axes;
  for (const StudyPass& pass : study.passes) {
    if (pass.sweepPoint.empty()) continue;
    if (axes.empty() || axes.back().front()->name != pass.name) axes.emplace_back();
    axes.back().push_back(&pass);
  }
  return axes;
}

ReportSection SweepSection(const Study& study, const std::vector<const StudyPass*>& points) {
  const std::string axis = points.front()->sweepPoint.substr(0, points.front()->sweepPoint.find('='));
  ReportSection section{"Sweep: " + points.front()->name + " " + axis, {kEstimateNote}, {}, {}, {}};
  ReportTable table{"Cost and quality at each point",
                    {"point", "work set px", "estimated µs (per strategy)", "PSNR", "FLIP", "edge FLIP"},
                    {}};
  BarChart quality{"Edge FLIP at each point", "edge FLIP", {}, {"edge FLIP"}, {{}}, false};
  BarChart cost{"Estimated time at each point", "µs", {}, {}, {}, false};
  for (const StudyPassRun& run : points.front()->runs) {
    cost.series.emplace_back(passes::StrategyName(run.strategy));
    cost.values.emplace_back();
  }
  for (const StudyPass* pass : points) {
    const passes::QualityScores& q = pass->image.quality.scores;
    std::string times;
    for (std::size_t r = 0; r < pass->runs.size(); ++r) {
      const double microseconds = PassMicroseconds(study, pass->runs[r]);
      times += (times.empty() ? "" : " / ") + FormatFixed(microseconds, 1);
      if (r < cost.values.size()) cost.values[r].push_back(microseconds);
    }
    table.rows.push_back({pass->sweepPoint, std::to_string(pass->workItems), times, FormatFixed(q.psnr, 2),
                          FormatFixed(q.flip, 4), FormatFixed(q.edgeFlip, 4)});
    quality.categories.push_back(pass->sweepPoint);
    cost.categories.push_back(pass->sweepPoint);
    quality.values.front().push_back(std::isfinite(q.edgeFlip) ? q.edgeFlip : 0.0);
  }
  section.tables.push_back(std::move(table));
  section.charts.push_back(std::move(quality));
  section.charts.push_back(std::move(cost));
  return section;
}

ReportSection DispatchesSection(const Study& study) {
  ReportSection section{"All dispatches", {kEstimateNote}, {}, {}, {}};
  std::vector<std::vector<std::string>> rows = DispatchSummaryRows(study.dispatches);
  ReportTable table{"Per dispatch (every counter: counters.csv, report.json)", {"frame"}, {}};
  table.header.insert(table.header.end(), rows.front().begin(), rows.front().end());
  for (std::size_t i = 1; i < rows.size(); ++i) {
    std::vector<std::string> row{study.dispatches[i - 1].frame};
    row.insert(row.end(), rows[i].begin(), rows[i].end());
    table.rows.push_back(std::move(row));
  }
  section.tables.push_back(std::move(table));
  return section;
}

}  // namespace

void StageFrameFiles(OutputDir& dir, const StudyFrame& frame, const sim::FramePipeline& pipeline) {
  const std::string folder = kImages + frame.image.folder + "/";
  StageColour(dir, folder + "colour.png", frame.image.colour);
  WriteFrameExr(dir.Stage(folder + "frame.exr"), pipeline);
  const EqaaPlanes planes = ReadEqaaPlanes(pipeline.Eqaa());
  WriteEqaaExr(dir.Stage(folder + "eqaa.exr"), planes);
  WritePng(dir.Stage(folder + "fmask.png"), planes.width, planes.height, 3, FmaskImage(planes));
  StageErrorFiles(dir, frame.image);
  for (const StudyResolve& resolve : frame.resolves) {
    StageColour(dir, kImages + resolve.image.folder + "/colour.png", resolve.image.colour);
    StageErrorFiles(dir, resolve.image);
  }
  if (frame.srgb8) {
    StageColour(dir, kImages + frame.srgb8->folder + "/colour.png", frame.srgb8->colour);
    StageErrorFiles(dir, *frame.srgb8);
  }
}

nlohmann::ordered_json RunConfigurationJson(const RunCommandOptions& options, int threads) {
  nlohmann::ordered_json modes = nlohmann::ordered_json::array();
  for (const fmask::EqaaConfig& mode : options.eqaaModes) modes.push_back(fmask::EqaaName(mode));
  return {{"scene", options.scene},
          {"width", options.width},
          {"height", options.height},
          {"quick", options.quick},
          {"modes", modes},
          {"pattern", options.pattern},
          {"policy", options.policy},
          {"compared_policies", options.comparedPolicies},
          {"resolves", options.resolveNames},
          {"lut_configurations", options.lutConfigurations == 0 ? nlohmann::ordered_json(nullptr)
                                                                : nlohmann::ordered_json(options.lutConfigurations)},
          {"gpu", options.gpu},
          {"flush", options.flush},
          {"draw_order", options.setup.drawOrder},
          {"depth_prepass", options.setup.depthPrepass},
          {"max_zplanes", options.setup.maxZPlanes},
          {"post", PassNamesJson(options.postPasses)},
          {"strategy", options.strategy},
          {"sweeps", options.sweeps},
          {"frames", options.frames},
          {"camera_path", options.cameraPath},
          {"camera_speed", options.cameraSpeed == 0.0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(options.cameraSpeed)},
          {"jitter", options.jitter.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(options.jitter)},
          {"fps", options.framesPerSecond},
          {"velocity_buffer", options.velocityBuffer},
          {"sequence_post", options.sequencePost},
          {"gt_samples", options.groundTruthSamples},
          {"cache", options.noCache ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(options.cache)},
          {"threads", threads}};
}

nlohmann::ordered_json StudyJson(const Study& study, const RunCommandOptions& options) {
  const StudyGroundTruth& truth = study.groundTruth;
  nlohmann::ordered_json json = {
      {"schema", kReportSchema},
      {"version", kReportVersion},
      {"configuration", RunConfigurationJson(options, study.threads)},
      {"scene", {{"name", study.sceneName}, {"triangles", study.triangles}}},
      {"ground_truth",
       {{"samples_per_pixel", truth.image.samplesPerPixel},
        {"edge_pixels", passes::CountSelected(truth.edgeMask)},
        {"cache_hit", truth.cacheHit},
        {"cache_file", truth.cacheFile.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(truth.cacheFile.string())},
        {"folder", kImages + "ground-truth"},
        {"host_seconds", truth.seconds}}},
      {"metrics", "psnr_db and ssim on sRGB-encoded values, flip (LDR) on linear colour; edge_* over the ground "
                  "truth's edge pixels; null = infinite (identical) PSNR or no edge pixels; docs/metrics.md"},
      {"frames", nlohmann::ordered_json::array()},
      {"passes", nlohmann::ordered_json::array()},
      {"eqaa_study", EqaaStudyJson(study)},
      {"dispatches", DispatchReportsJson(study.dispatches, study.gpu, nlohmann::ordered_json::object())},
      {"host_seconds", study.hostSeconds},
  };
  // The configuration is echoed once, at the top.
  json["dispatches"].erase("configuration");
  for (const StudyFrame& frame : study.frames) json["frames"].push_back(FrameJson(frame, options));
  for (const StudyPass& pass : study.passes) json["passes"].push_back(PassJson(study, pass));
  json["sample_patterns"] = PatternErrorJson();
  if (study.sequence) {
    json["sequence"] = SequenceJson(*study.sequence);
    json["sequence"]["seed_001_timings"] = SeedTimingJson(study);
  }
  return json;
}

Report StudyHtml(const Study& study, const RunCommandOptions& options, const SequenceImages* sequenceImages) {
  const std::vector<Shown> shown = ShownImages(study, study.groundTruth.colour);
  const int width = options.width, height = options.height;
  Report report{"aasim report: " + study.sceneName, {}, RunConfigurationJson(options, study.threads).dump(2)};
  report.sections = {RunSection(study, options), ImagesSection(shown, width, height), ComparerSection()};
  for (ReportSection& crop : CropSections(study, shown, width, height)) report.sections.push_back(std::move(crop));
  report.sections.push_back(QualitySection(shown));
  report.sections.push_back(ErrorMapsSection(shown, width, height));
  report.sections.push_back(FramesSection(study));
  report.sections.push_back(EqaaStudySection(study));
  if (!study.passes.empty()) report.sections.push_back(PassesComparedSection(study));
  for (const StudyPass& pass : study.passes) report.sections.push_back(PassSection(study, pass));
  for (const std::vector<const StudyPass*>& axis : SweptPasses(study)) report.sections.push_back(SweepSection(study, axis));
  if (sequenceImages) {
    for (ReportSection& section : SequenceSections(study, *sequenceImages)) report.sections.push_back(std::move(section));
  }
  report.sections.push_back(DispatchesSection(study));
  report.sections.push_back(PatternErrorSection());
  return report;
}

void SetSequenceRegion(SequenceImages& images, const StudyFrame& frame) {
  const int width = frame.image.colour.Width(), height = frame.image.colour.Height();
  const int size = CropSize(width, height);
  const std::vector<PixelRect> hardest = HardestRegions(frame.image.quality.maps.flip, width, height, size, 1);
  images.SetRegion(hardest.empty() ? PixelRect{0, 0, size, size} : hardest.front(), CropZoom(size));
}

void StageStudyFiles(OutputDir& dir, const Study& study, const RunCommandOptions& options,
                     const SequenceImages* sequenceImages) {
  StageGroundTruth(dir, study.groundTruth);
  for (const StudyPass& pass : study.passes) StagePassFiles(dir, pass);
  StageHeatMaps(dir, study);
  WriteJson(dir.Stage("report.json"), StudyJson(study, options));
  WriteText(dir.Stage("counters.csv"),
            DispatchReportsCsv(study.dispatches));
  WriteText(dir.Stage("quality.csv"), QualityCsv(study));
  WriteText(dir.Stage("report.html"), RenderHtml(StudyHtml(study, options, sequenceImages)));
}

}  // namespace cli
