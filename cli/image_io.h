#pragma once
// Image files of the command line: 8-bit PNG previews (sRGB-encoded, DESIGN.md "Conventions")
// and float EXR with named channels (linear). Pixels are row-major, top row first.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cli/output_dir.h"
#include "sim/colour.h"

namespace cli {

// Linear [0, 1] -> 8-bit sRGB; out-of-range values clamp.
using sim::EncodeSrgb8;

// `pixels` holds width * height * channels bytes (1 = grey, 3 = RGB, 4 = RGBA).
// Throws OutputError naming the path.
void WritePng(const std::filesystem::path& path, int width, int height, int channels,
              std::span<const std::uint8_t> pixels);

// The same, staged in `dir` as `fileName` and encoded on a worker thread while the caller goes
// on (OutputDir::WriteLater): the pixels are moved in.
void StagePngLater(OutputDir& dir, std::string_view fileName, int width, int height, int channels,
                   std::vector<std::uint8_t> pixels);

// The same PNG in memory (for self-contained HTML reports).
std::vector<std::uint8_t> EncodePng(int width, int height, int channels, std::span<const std::uint8_t> pixels);

struct ExrChannel {
  std::string name;
  std::span<const float> values;  // width * height
};

// One 32-bit float channel per entry, ZIP compression. Throws OutputError naming the path.
void WriteExr(const std::filesystem::path& path, int width, int height,
              std::span<const ExrChannel> channels);

// Fills one strip of a UINT image: strip[c][(y - firstRow) * width + x] for channel c and every
// row y in [firstRow, firstRow + rows).
using UintExrStripFill =
    std::function<void(int firstRow, int rows, std::vector<std::vector<std::uint32_t>>& strip)>;

// 32-bit unsigned integer channels (OpenEXR UINT), ZIP compression: for ids and masks, which a
// float channel could not hold exactly. Written `stripRows` scanlines at a time from `fill`, so
// only one strip is ever in memory however many channels there are. Throws OutputError naming
// the path.
void WriteUintExr(const std::filesystem::path& path, int width, int height,
                  std::span<const std::string> channelNames, int stripRows,
                  const UintExrStripFill& fill);

}  // namespace cli
