// `aasim raster`'s memory estimate (EstimateRasterBytes, the 4 GiB pre-flight check) against the
// peak resident set the real binary reaches: the estimate must not be below what is allocated.
// Wide, short images are the hard case: there the EXR writers' row buffers (samples.exr's strip,
// OpenEXR's ZIP chunk) outweigh every per-pixel buffer, and the estimate once left them out.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/raster_options.h"
#include "cli_test_util.h"
#include "sanitized.h"

namespace {

namespace fs = std::filesystem;

class CliRasterMemory : public cli::testing::ScratchDirTest {};

struct Size {
  int width, height, samples, depthSamples, fragments;
};

std::vector<std::string> MemoryRunArgs(const Size& size, const fs::path& out) {
  std::vector<std::string> args{"raster", "--width", std::to_string(size.width), "--height", std::to_string(size.height),
                                "--samples", std::to_string(size.samples), "--depth-samples",
                                std::to_string(size.depthSamples), "--out", out.string()};
  if (size.fragments > 0) args.insert(args.end(), {"--fragments", std::to_string(size.fragments)});
  return args;
}

// Peak resident set of one successful run, in bytes (wait4's ru_maxrss is in KiB on Linux).
std::uint64_t PeakResidentBytes(const std::vector<std::string>& args, const fs::path& scratch) {
  const std::string log = (scratch / "log.txt").string();
  const pid_t pid = cli::testing::SpawnAasim(args, log, log);
  if (pid <= 0) {
    ADD_FAILURE() << "cannot start " << AASIM_BINARY;
    return 0;
  }
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cli::testing::ReadText(scratch / "log.txt");
  return std::uint64_t(usage.ru_maxrss) * 1024u;
}

TEST_F(CliRasterMemory, TheEstimateCoversThePeakResidentSetAboveAOnePixelRun) {
#if AASIM_TEST_SANITIZED
  GTEST_SKIP() << "sanitizer shadow memory and quarantine inflate the resident set";
#endif
  // The code, libraries and thread stacks every run has, whatever its size.
  const std::uint64_t baseline = PeakResidentBytes(MemoryRunArgs({1, 1, 1, 1, 0}, scratch_ / "base"), scratch_);
  const Size sizes[] = {
      {16384, 16, 16, 8, 0},  // the estimate was 28.5 MiB; the run peaks ~110 MiB above the baseline
      {16384, 64, 16, 8, 4},
      {1024, 1024, 8, 4, 2},
  };
  for (const Size& size : sizes) {
    const std::vector<std::string> args = MemoryRunArgs(size, scratch_ / "out");
    std::string text;
    for (const std::string& arg : args) text += arg + " ";
    SCOPED_TRACE(text);
    const std::uint64_t peak = PeakResidentBytes(args, scratch_);
    const std::uint64_t estimate =
        cli::EstimateRasterBytes(size.width, size.height, size.samples, size.depthSamples, size.fragments);
    EXPECT_GE(estimate + baseline, peak) << "estimate " << estimate << ", baseline " << baseline;
  }
}

}  // namespace
