#pragma once
// The options of `aasim post`: which registered pass, its settings (--preset, --set, validated by
// the registry's schema), the user's image and depth files, the strategies, the machine and the
// output directory. Rules between options run before any file is read; violations are
// CLI::ValidationError (exit 2).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cli/cli11_fwd.h"
#include "passes/registry.h"

namespace cli {

struct PostCommandOptions {
  std::string pass;                      // --pass NAME
  std::string preset;                    // --preset NAME; empty: the schema's defaults
  std::vector<std::string> settings;     // --set KEY=VALUE, in order
  // --input IMAGE, repeatable: one image is one frame; several are a sequence run in order
  // through one pass instance per strategy (temporal passes keep their history).
  std::vector<std::string> inputs;
  std::vector<std::string> depths;       // --depth EXR: none, or one per input
  std::vector<std::string> velocities;   // --velocity EXR: none, or one per input
  std::string jitter;                    // --jitter NAME; empty: the pass's own schedule
  double framesPerSecond = 60.0;         // --fps
  std::string strategy = "both";
  std::string gpu;                       // default set by AddPostCommand: sim::kDefaultGpuName
  int threads = 0;                       // default set by AddPostCommand: every core
  std::string out;

  // Filled by ResolvePostOptions: the pass with its validated settings.
  std::optional<passes::PassConfig> config;

  // The strategies the pass runs under, in run order; the first one's outputs are written.
  std::vector<passes::Strategy> Strategies() const;
  bool Sequence() const { return inputs.size() > 1; }
};

// Registers the `post` subcommand on `app`, bound to `options`; its --help ends with the
// registered passes as `aasim passes` prints them.
CLI::App* AddPostCommand(CLI::App& app, PostCommandOptions& options);

// Resolves the pass and its settings and checks the rules between options.
void ResolvePostOptions(PostCommandOptions& options);

// CLI::ValidationError naming the first input `info` reads that the options do not supply
// (`haveDepth`: --depth was given, `haveVelocity`: --velocity) and the option that supplies it,
// or saying that `aasim post` cannot.
void CheckPostInputs(const passes::PassInfo& info, bool haveDepth, bool haveVelocity = false);

// Bytes held at once for a width x height image: the decoded image and the colour texture, the
// depth file's plane and texture, what each strategy's run of the pass holds
// (PassInfo::bytesPerPixel: every run's output is kept for the comparison), and the writers'
// buffers for output.exr and output.png.
// A sequence holds one frame's inputs at a time (the velocity file's plane and texture counted with
// the depth's).
std::uint64_t EstimatePostBytes(int width, int height, const passes::PassInfo& info, std::size_t strategies,
                                bool depth, bool velocity = false);

}  // namespace cli
