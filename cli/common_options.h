#pragma once
// Options that more than one subcommand takes (scene and viewport, sample counts, sample
// pattern, threads) and the memory of the surfaces they render into, registered in one place so
// names, ranges and help read the same in `aasim raster` and `aasim frame`.

#include <cstdint>
#include <string>
#include <vector>

#include "cli/cli11_fwd.h"
#include "fmask/eqaa_surface.h"

namespace cli {

// Refuse runs whose buffers would exceed this (EstimateRasterBytes, EstimateFrameBytes).
inline constexpr std::uint64_t kMaxRunBytes = std::uint64_t{4} << 30;
// `aasim run` keeps every image its report shows (every mode, resolve and pass, and with --frames
// every frame's ground truth and each followed technique's frames), so its own limit is higher:
// the default single-frame study at 1080p estimates 3.7 GiB, with --frames 8 6.2 GiB.
inline constexpr std::uint64_t kMaxStudyBytes = std::uint64_t{8} << 30;

// The names of a table of {name, value} entries, in table order, for CLI::IsMember.
template <typename Table>
std::vector<std::string> Names(const Table& table) {
  std::vector<std::string> names;
  for (const auto& entry : table) names.emplace_back(entry.name);
  return names;
}

// "a, b, c", for help texts and error messages that list the legal names.
std::string JoinNames(const std::vector<std::string>& names);
// "4.0": bytes in GiB with one decimal, for the memory-limit messages.
std::string FormatGiB(std::uint64_t bytes);

// --scene FILE|builtin:NAME (default builtin:default), --width and --height (1..kMaxDimension).
void AddViewportOptions(CLI::App& command, std::string& scene, int& width, int& height);
// --pattern NAME|FILE; the default is whatever `pattern` holds.
void AddPatternOption(CLI::App& command, std::string& pattern);
// --threads N (1..1024); sets `threads` to every core first, which is the default.
void AddThreadsOption(CLI::App& command, int& threads);
// --fps: the frame rate of a sequence, 1..1000; passes read dt = 1 / fps.
void AddFramesPerSecondOption(CLI::App& command, double& framesPerSecond);

// Makes every integer option of `app` and its subcommands read decimal only: CLI11 converts with
// base 0, so `--width 0064` would be octal 52 and `0x40` hexadecimal. Leading zeros are dropped
// ("0064" is 64); anything but optional sign and digits is a usage error naming the option.
void RequireDecimalIntegers(CLI::App& app);

// The single-value checks of S, Z and F; whether the three form a legal mode is
// fmask::ValidateEqaaConfig's call (CheckEqaaMode).
CLI::Validator SampleCountCheck();
CLI::Validator DepthSampleCountCheck();
CLI::Validator FragmentCountCheck();
// fmask::ValidateEqaaConfig as a CLI::ValidationError (exit 2) carrying its message, which
// lists every legal S/Z/F.
void CheckEqaaMode(const fmask::EqaaConfig& eqaa);

// Bytes per pixel of an EQAA depth surface (S plane indices, Z float anchors, a stencil byte)
// and one layer of quads; with fragments > 0 also the colour surface (FMASK element, F slots,
// an UNKNOWN cause per sample).
std::uint64_t SurfaceBytesPerPixel(int samples, int depthSamples, int fragments);

}  // namespace cli
