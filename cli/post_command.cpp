// `aasim post` (see post_command.h): reads the user's image, runs the pass under each strategy and
// writes the output set.

#include "cli/post_command.h"

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <oneapi/tbb/global_control.h>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "cli/common_options.h"
#include "cli/dispatch_output.h"
#include "cli/frame_output.h"
#include "cli/image_input.h"
#include "cli/image_io.h"
#include "cli/output_dir.h"
#include "cli/pass_runs.h"
#include "cli/text_io.h"
#include "passes/pass.h"
#include "raster/jitter_schedule.h"
#include "sim/gpu_config.h"

namespace cli {
namespace {

inline constexpr const char* kPostSchema = "aasim.post";
inline constexpr int kPostVersion = 1;
constexpr const char* kReport = "report.json";

// One frame's files.
struct PostInputs {
  std::string input, depthFile, velocityFile;
  InputImage image;
  std::optional<DepthImage> depth;
  std::optional<VelocityImage> velocity;
  std::optional<sim::Texture2D<glm::vec4>> colourSrgb8;  // the image as the 8-bit passes read it

  passes::FrameInputs Frame() const {
    return {.colour = &image.colour,
            .colourSrgb8 = &*colourSrgb8,
            .depth = depth ? &depth->depth : nullptr,
            .velocity = velocity ? &velocity->velocity : nullptr};
  }
};

// The memory guard of `aasim frame`, for a size only the image's header tells; a sequence's
// frames are all read before any output exists, so all count.
ImageSizeCheck MemoryCheck(const PostCommandOptions& options, const std::string& input) {
  return [&options, input](int width, int height) {
    const std::uint64_t bytes =
        EstimatePostBytes(width, height, options.config->Info(), options.Strategies().size(), !options.depths.empty(),
                          !options.velocities.empty()) *
        options.inputs.size();
    if (bytes <= kMaxRunBytes) return;
    throw InputImageError(input + ": " + std::to_string(options.inputs.size()) + " image(s) of " + std::to_string(width) +
                          "x" + std::to_string(height) + " need about " + FormatGiB(bytes) + " GiB for pass " +
                          options.pass + " under " + std::to_string(options.Strategies().size()) +
                          " strategies (images, pass and outputs), over the " + FormatGiB(kMaxRunBytes) + " GiB limit");
  };
}

std::string FileAt(const std::vector<std::string>& files, std::size_t frame) {
  return files.empty() ? std::string() : files[frame];
}

PostInputs ReadFrameInputs(const PostCommandOptions& options, std::size_t frame) {
  PostInputs inputs{options.inputs[frame], FileAt(options.depths, frame), FileAt(options.velocities, frame),
                    ReadInputImage(options.inputs[frame], MemoryCheck(options, options.inputs[frame])), std::nullopt,
                    std::nullopt, std::nullopt};
  const int width = inputs.image.colour.Width(), height = inputs.image.colour.Height();
  inputs.colourSrgb8 = passes::Srgb8ColourTarget("colour-srgb8", inputs.image.colour);
  if (!inputs.depthFile.empty()) inputs.depth = ReadDepthExr(inputs.depthFile, width, height, inputs.input);
  if (!inputs.velocityFile.empty()) inputs.velocity = ReadVelocityExr(inputs.velocityFile, width, height, inputs.input);
  return inputs;
}

// Every frame, all of the first frame's size.
std::vector<PostInputs> ReadInputs(const PostCommandOptions& options) {
  std::vector<PostInputs> frames;
  for (std::size_t k = 0; k < options.inputs.size(); ++k) {
    PostInputs frame = ReadFrameInputs(options, k);
    if (!frames.empty()) {
      const sim::Texture2D<glm::vec4>& first = frames.front().image.colour;
      const sim::Texture2D<glm::vec4>& colour = frame.image.colour;
      if (colour.Width() != first.Width() || colour.Height() != first.Height()) {
        throw InputImageError(frame.input + ": " + std::to_string(colour.Width()) + "x" + std::to_string(colour.Height()) +
                              ", the first image " + frames.front().input + " is " + std::to_string(first.Width()) +
                              "x" + std::to_string(first.Height()) + "; a sequence's images have one size");
      }
    }
    frames.push_back(std::move(frame));
  }
  return frames;
}

nlohmann::ordered_json OrNull(const std::string& text) {
  return text.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(text);
}

nlohmann::ordered_json ConfigurationJson(const PostCommandOptions& options, const PostInputs& inputs, int threads) {
  return {{"input", inputs.input},
          {"depth", OrNull(inputs.depthFile)},
          {"width", inputs.image.colour.Width()},
          {"height", inputs.image.colour.Height()},
          {"gpu", options.gpu},
          {"post", options.pass},
          {"pass_settings", passes::DescribeSettings(options.config->settings)},
          {"strategy", options.strategy},
          {"threads", threads}};
}

// Every file the output colour and the layers of `run` become, in write order, under `folder`
// ("" or "frame-NNN/").
std::vector<std::string> WriteImages(OutputDir& dir, const passes::PassOutput& output, bool alpha,
                                     const std::string& folder = "") {
  const sim::Texture2D<glm::vec4>& colour = output.colour;
  const int width = colour.Width(), height = colour.Height();
  if (alpha) {
    WritePng(dir.Stage(folder + "output.png"), width, height, 4, SrgbAlphaImage(colour.Texels()));
  } else {
    WritePng(dir.Stage(folder + "output.png"), width, height, 3, SrgbImage(colour.Texels()));
  }
  std::vector<float> planes[4];
  for (const glm::vec4& texel : colour.Texels()) {
    for (int c = 0; c < 4; ++c) planes[c].push_back(texel[c]);
  }
  const ExrChannel channels[] = {{"R", planes[0]}, {"G", planes[1]}, {"B", planes[2]}, {"A", planes[3]}};
  WriteExr(dir.Stage(folder + "output.exr"), width, height, channels);
  std::vector<std::string> files{folder + "output.png", folder + "output.exr"};
  for (const passes::PassLayer& layer : output.layers) {
    WriteLayerPng(dir.Stage(folder + layer.name + ".png"), layer);
    WriteLayerExr(dir.Stage(folder + layer.name + ".exr"), layer);
    files.insert(files.end(), {folder + layer.name + ".png", folder + layer.name + ".exr"});
  }
  return files;
}

nlohmann::ordered_json SettingsJson(const passes::PassSettings& settings) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < settings.Schema().size(); ++i) {
    json[std::string(settings.Schema()[i].name)] = settings.Values()[i];
  }
  return json;
}

nlohmann::ordered_json InputJson(const PostInputs& inputs) {
  return {{"image", inputs.input},
          {"format", inputs.image.format},
          {"width", inputs.image.colour.Width()},
          {"height", inputs.image.colour.Height()},
          {"alpha", inputs.image.alpha},
          {"depth", OrNull(inputs.depthFile)},
          {"depth_channel", inputs.depth ? nlohmann::ordered_json(inputs.depth->channel) : nlohmann::ordered_json(nullptr)},
          {"velocity", OrNull(inputs.velocityFile)}};
}

nlohmann::ordered_json RunsJson(std::span<const study::DispatchRecord> records, const PassRuns& runs) {
  nlohmann::ordered_json json = nlohmann::ordered_json::array();
  for (const PassRun& run : runs.runs) {
    nlohmann::ordered_json dispatches = nlohmann::ordered_json::array();
    for (std::size_t i = run.firstDispatch; i < run.endDispatch; ++i) dispatches.push_back(i);
    json.push_back({{"strategy", passes::StrategyName(run.strategy)},
                    {"dispatches", dispatches},
                    {"work_items", run.output.workItems},
                    {"estimated_us_total", EstimatedMicroseconds(records, run)}});
  }
  return json;
}

nlohmann::ordered_json ComparisonJson(const PassRuns& runs) {
  if (runs.runs.size() < 2) return nullptr;
  const passes::StrategyDifference& difference = runs.difference;
  return {{"identical", difference.Identical()},
          {"differs_in", OrNull(difference.what)},
          {"differing_pixels", difference.pixels.pixels},
          {"description", difference.Describe()}};
}

nlohmann::ordered_json ReportJson(const PostCommandOptions& options, const PostInputs& inputs,
                                  std::span<const study::DispatchRecord> records, const PassRuns& runs,
                                  const std::vector<std::string>& images, const sim::GpuConfig& gpu, int threads) {
  const passes::PassInfo& info = options.config->Info();
  nlohmann::ordered_json layers = nlohmann::ordered_json::array();
  for (const passes::PassLayer& layer : runs.runs.front().output.layers) {
    layers.push_back({{"name", layer.name}, {"channels", layer.channels}});
  }
  return {{"schema", kPostSchema},
          {"version", kPostVersion},
          {"input", InputJson(inputs)},
          {"pass",
           {{"name", info.name},
            {"description", info.description},
            {"source", info.source},
            {"preset", OrNull(options.preset)},
            {"settings", SettingsJson(options.config->settings)},
            {"studied_dispatch", info.studiedDispatches.front()}}},
          {"gpu", gpu.name},
          {"threads", threads},
          {"strategies", RunsJson(records, runs)},
          {"written_strategy", passes::StrategyName(runs.runs.front().strategy)},
          {"work_items", runs.runs.front().output.workItems},
          {"comparison", ComparisonJson(runs)},
          {"layers", layers},
          {"images", images},
          {"dispatch_reports", {"dispatches.json", "dispatches.csv"}}};
}

void PrintSummary(std::ostream& out, const PostCommandOptions& options, const PostInputs& inputs,
                  std::span<const study::DispatchRecord> records, const PassRuns& runs, const sim::GpuConfig& gpu,
                  int threads, const OutputDir& dir) {
  const passes::PassInfo& info = options.config->Info();
  const std::string settings = passes::DescribeSettings(options.config->settings);
  out << "post       " << info.name << (settings.empty() ? "" : " (" + settings + ")") << " on " << inputs.input
      << ", " << inputs.image.colour.Width() << "x" << inputs.image.colour.Height() << " "
      << (inputs.image.format == "png" ? "PNG (sRGB)" : "OpenEXR (linear)")
      << (inputs.image.alpha ? " with alpha" : "") << ", GPU " << gpu.name << '\n';
  if (inputs.depth) out << "depth      " << inputs.depthFile << ", channel " << inputs.depth->channel << '\n';
  if (inputs.velocity) out << "velocity   " << inputs.velocityFile << ", channels " << inputs.velocity->channels << '\n';
  out << '\n';
  PrintDispatchSummary(out, records, gpu);
  if (runs.runs.size() == 2) PrintStrategyComparison(out, records, info, runs);
  out << "\nimages     output.png, output.exr and the pass's layers of the "
      << passes::StrategyName(runs.runs.front().strategy) << " run\n";
  PrintHostTime(out, records, threads);
  out << "report: " << (dir.Path() / kReport).string() << '\n';
}

// A sequence's frame k: the pass reads the pattern and jitter of the schedule the frames were
// rendered with, and the sequence's frame time.
passes::FrameInputs SequenceFrame(const PostInputs& inputs, const raster::JitterSchedule& schedule, int frame,
                                  double framesPerSecond) {
  passes::FrameInputs frameInputs = inputs.Frame();
  frameInputs.pattern = &schedule.At(frame);
  frameInputs.frameIndex = frame;
  frameInputs.jitter = passes::PatternJitter(schedule.At(frame));
  frameInputs.frameSeconds = 1.0 / framesPerSecond;
  return frameInputs;
}

std::string FrameFolder(std::size_t frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame-%03zu/", frame);
  return name;
}

// Every frame through one instance per strategy, in order; each frame's outputs under
// frame-NNN/, one report.json and one dispatch log for the sequence.
void RunPostSequence(const PostCommandOptions& options, const std::vector<PostInputs>& frames, sim::Machine& machine,
                     int threads, std::ostream& summary) {
  const passes::PassInfo& info = options.config->Info();
  const std::string scheduleName = options.jitter.empty() ? std::string(info.jitter) : options.jitter;
  const raster::JitterSchedule schedule =
      raster::JitterSchedule::Make(scheduleName, raster::MakeBuiltinPattern("centre", 1));
  OutputDir dir = OpenOutOption(options.out);
  const std::vector<passes::Strategy> strategies = options.Strategies();
  std::vector<std::unique_ptr<passes::Pass>> instances;
  for (std::size_t s = 0; s < strategies.size(); ++s) instances.push_back(options.config->Make());
  std::vector<study::DispatchRecord> records;
  nlohmann::ordered_json framesJson = nlohmann::ordered_json::array();
  std::optional<PassRuns> differing;
  summary << "post       " << info.name << " over " << frames.size() << " frames of " << frames.front().image.colour.Width()
          << "x" << frames.front().image.colour.Height() << ", jitter schedule " << scheduleName << ", GPU "
          << machine.Gpu().name << '\n';
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const int frame = static_cast<int>(k);
    const passes::FrameInputs input = SequenceFrame(frames[k], schedule, frame, options.framesPerSecond);
    const std::string label = "frame " + std::to_string(k);
    PassRuns runs;
    for (std::size_t s = 0; s < strategies.size(); ++s) {
      PassRun run{strategies[s], instances[s]->Run(machine, input, strategies[s]), records.size(), 0};
      TakeDispatches(machine, records, label, std::string(info.name), std::string(passes::StrategyName(strategies[s])));
      run.endDispatch = records.size();
      if (s > 0 && runs.difference.Identical()) runs.difference = passes::CompareOutputs(runs.runs.front().output, run.output);
      runs.runs.push_back(std::move(run));
    }
    const std::vector<std::string> images = WriteImages(dir, runs.runs.front().output, frames[k].image.alpha, FrameFolder(k));
    framesJson.push_back({{"frame", k},
                          {"input", InputJson(frames[k])},
                          {"strategies", RunsJson(records, runs)},
                          {"work_items", runs.runs.front().output.workItems},
                          {"comparison", ComparisonJson(runs)},
                          {"images", images}});
    summary << "  " << label << ": " << frames[k].input << ", work items " << runs.runs.front().output.workItems
            << ", strategies " << (runs.runs.size() < 2 ? "one run" : runs.difference.Identical() ? "identical" : "DIFFER")
            << '\n';
    if (!differing && !runs.difference.Identical()) differing = std::move(runs);
  }
  nlohmann::ordered_json configuration = ConfigurationJson(options, frames.front(), threads);
  configuration["input"] = options.inputs;
  configuration["jitter"] = scheduleName;
  configuration["fps"] = options.framesPerSecond;
  WriteDispatchReports(dir, records, machine.Gpu(), configuration);
  WriteJson(dir.Stage(kReport),
            {{"schema", kPostSchema},
             {"version", kPostVersion},
             {"pass",
              {{"name", info.name},
               {"description", info.description},
               {"source", info.source},
               {"preset", OrNull(options.preset)},
               {"settings", SettingsJson(options.config->settings)},
               {"studied_dispatch", info.studiedDispatches.front()}}},
             {"gpu", machine.Gpu().name},
             {"threads", threads},
             {"jitter", scheduleName},
             {"fps", options.framesPerSecond},
             {"written_strategy", passes::StrategyName(strategies.front())},
             {"frames", std::move(framesJson)},
             {"dispatch_reports", {"dispatches.json", "dispatches.csv"}}});
  dir.Commit(kReport);
  PrintHostTime(summary, records, threads);
  summary << "report: " << (dir.Path() / kReport).string() << '\n';
  if (differing) ThrowIfStrategiesDiffer(*differing, info, dir.Path());
}

}  // namespace

void RunPostCommand(const PostCommandOptions& options, std::ostream& summary) {
  const tbb::global_control threadLimit(tbb::global_control::max_allowed_parallelism,
                                        static_cast<std::size_t>(options.threads));
  const int threads =
      static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  // Every input is read and checked before the output directory is touched, so a bad input
  // leaves a previous set as it was.
  sim::Machine machine(sim::GpuConfigByName(options.gpu));
  const std::vector<PostInputs> frames = ReadInputs(options);
  if (options.Sequence()) return RunPostSequence(options, frames, machine, threads, summary);
  const PostInputs& inputs = frames.front();
  OutputDir dir = OpenOutOption(options.out);

  std::vector<study::DispatchRecord> records;
  const PassRuns runs = RunUnderStrategies(machine, *options.config, inputs.Frame(), options.Strategies(), records);
  const std::vector<std::string> images = WriteImages(dir, runs.runs.front().output, inputs.image.alpha);
  WriteDispatchReports(dir, records, machine.Gpu(), ConfigurationJson(options, inputs, threads));
  WriteJson(dir.Stage(kReport), ReportJson(options, inputs, records, runs, images, machine.Gpu(), threads));
  dir.Commit(kReport);

  PrintSummary(summary, options, inputs, records, runs, machine.Gpu(), threads, dir);
  ThrowIfStrategiesDiffer(runs, options.config->Info(), dir.Path());
}

}  // namespace cli
