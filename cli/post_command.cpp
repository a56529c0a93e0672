// `aasim post` (see post_command.h): reads the user's image, runs the pass under each strategy and
// writes the output set.

#include "cli/post_command.h"

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
#include "sim/gpu_config.h"

namespace cli {
namespace {

inline constexpr const char* kPostSchema = "aasim.post";
inline constexpr int kPostVersion = 1;
constexpr const char* kReport = "report.json";

struct PostInputs {
  InputImage image;
  std::optional<DepthImage> depth;

  passes::FrameInputs Frame() const {
    return {.colour = &image.colour, .depth = depth ? &depth->depth : nullptr};
  }
};

// The memory guard of `aasim frame`, for a size only the image's header tells.
ImageSizeCheck MemoryCheck(const PostCommandOptions& options) {
  return [&options](int width, int height) {
    const std::uint64_t bytes = EstimatePostBytes(width, height, options.config->Info(), options.Strategies().size(),
                                                  !options.depth.empty());
    if (bytes <= kMaxRunBytes) return;
    throw InputImageError(options.input + ": a " + std::to_string(width) + "x" + std::to_string(height) +
                          " image needs about " + FormatGiB(bytes) + " GiB for pass " + options.pass + " under " +
                          std::to_string(options.Strategies().size()) +
                          " strategies (image, pass and outputs), over the " + FormatGiB(kMaxRunBytes) + " GiB limit");
  };
}

PostInputs ReadInputs(const PostCommandOptions& options) {
  PostInputs inputs{ReadInputImage(options.input, MemoryCheck(options)), std::nullopt};
  if (!options.depth.empty()) {
    inputs.depth = ReadDepthExr(options.depth, inputs.image.colour.Width(), inputs.image.colour.Height(), options.input);
  }
  return inputs;
}

nlohmann::ordered_json OrNull(const std::string& text) {
  return text.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(text);
}

nlohmann::ordered_json ConfigurationJson(const PostCommandOptions& options, const PostInputs& inputs, int threads) {
  return {{"input", options.input},
          {"depth", OrNull(options.depth)},
          {"width", inputs.image.colour.Width()},
          {"height", inputs.image.colour.Height()},
          {"gpu", options.gpu},
          {"post", options.pass},
          {"pass_settings", passes::DescribeSettings(options.config->settings)},
          {"strategy", options.strategy},
          {"threads", threads}};
}

// Every file the output colour and the layers of `run` become, in write order.
std::vector<std::string> WriteImages(OutputDir& dir, const passes::PassOutput& output, bool alpha) {
  const sim::Texture2D<glm::vec4>& colour = output.colour;
  const int width = colour.Width(), height = colour.Height();
  if (alpha) {
    WritePng(dir.Stage("output.png"), width, height, 4, SrgbAlphaImage(colour.Texels()));
  } else {
    WritePng(dir.Stage("output.png"), width, height, 3, SrgbImage(colour.Texels()));
  }
  std::vector<float> planes[4];
  for (const glm::vec4& texel : colour.Texels()) {
    for (int c = 0; c < 4; ++c) planes[c].push_back(texel[c]);
  }
  const ExrChannel channels[] = {{"R", planes[0]}, {"G", planes[1]}, {"B", planes[2]}, {"A", planes[3]}};
  WriteExr(dir.Stage("output.exr"), width, height, channels);
  std::vector<std::string> files{"output.png", "output.exr"};
  for (const passes::PassLayer& layer : output.layers) {
    WriteLayerPng(dir.Stage(layer.name + ".png"), layer);
    WriteLayerExr(dir.Stage(layer.name + ".exr"), layer);
    files.insert(files.end(), {layer.name + ".png", layer.name + ".exr"});
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

nlohmann::ordered_json InputJson(const PostCommandOptions& options, const PostInputs& inputs) {
  return {{"image", options.input},
          {"format", inputs.image.format},
          {"width", inputs.image.colour.Width()},
          {"height", inputs.image.colour.Height()},
          {"alpha", inputs.image.alpha},
          {"depth", OrNull(options.depth)},
          {"depth_channel", inputs.depth ? nlohmann::ordered_json(inputs.depth->channel) : nlohmann::ordered_json(nullptr)}};
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
          {"input", InputJson(options, inputs)},
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
  out << "post       " << info.name << (settings.empty() ? "" : " (" + settings + ")") << " on " << options.input
      << ", " << inputs.image.colour.Width() << "x" << inputs.image.colour.Height() << " "
      << (inputs.image.format == "png" ? "PNG (sRGB)" : "OpenEXR (linear)")
      << (inputs.image.alpha ? " with alpha" : "") << ", GPU " << gpu.name << '\n';
  if (inputs.depth) out << "depth      " << options.depth << ", channel " << inputs.depth->channel << '\n';
  out << '\n';
  PrintDispatchSummary(out, records, gpu);
  if (runs.runs.size() == 2) PrintStrategyComparison(out, records, info, runs);
  out << "\nimages     output.png, output.exr and the pass's layers of the "
      << passes::StrategyName(runs.runs.front().strategy) << " run\n";
  PrintHostTime(out, records, threads);
  out << "report: " << (dir.Path() / kReport).string() << '\n';
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
  const PostInputs inputs = ReadInputs(options);
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
