// PNG (stb_image_write) and EXR (OpenEXR) writers; see image_io.h.

#include "cli/image_io.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <optional>
#include <stdexcept>

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <stb_image_write.h>

#include "cli/output_error.h"

namespace cli {
namespace {

std::size_t PixelCount(int width, int height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("image size must be positive");
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

}  // namespace

void WritePng(const std::filesystem::path& path, int width, int height, int channels,
              std::span<const std::uint8_t> pixels) {
  if (channels < 1 || channels > 4 || pixels.size() != PixelCount(width, height) * channels) {
    throw std::invalid_argument("WritePng: pixel buffer does not match the image size");
  }
  if (stbi_write_png(path.c_str(), width, height, channels, pixels.data(), width * channels) == 0) {
    throw OutputError(path.string() + ": cannot write PNG");
  }
}

void StagePngLater(OutputDir& dir, std::string_view fileName, int width, int height, int channels,
                   std::vector<std::uint8_t> pixels) {
  if (channels < 1 || channels > 4 || pixels.size() != PixelCount(width, height) * channels) {
    throw std::invalid_argument("StagePngLater: pixel buffer does not match the image size");
  }
  dir.WriteLater(fileName, [width, height, channels, pixels = std::move(pixels)](const std::filesystem::path& path) {
    WritePng(path, width, height, channels, pixels);
  });
}

std::vector<std::uint8_t> EncodePng(int width, int height, int channels, std::span<const std::uint8_t> pixels) {
  if (channels < 1 || channels > 4 || pixels.size() != PixelCount(width, height) * channels) {
    throw std::invalid_argument("EncodePng: pixel buffer does not match the image size");
  }
  std::vector<std::uint8_t> png;
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (stbi_write_png_to_func(append, &png, width, height, channels, pixels.data(), width * channels) == 0) {
    throw std::runtime_error("EncodePng: stb_image_write failed");
  }
  return png;
}

void WriteExr(const std::filesystem::path& path, int width, int height,
              std::span<const ExrChannel> channels) {
  const std::size_t pixelCount = PixelCount(width, height);
  Imf::Header header(width, height);
  header.compression() = Imf::ZIP_COMPRESSION;
  Imf::FrameBuffer frameBuffer;
  for (const ExrChannel& channel : channels) {
    if (channel.values.size() != pixelCount) {
      throw std::invalid_argument("WriteExr: channel " + channel.name + " does not match the size");
    }
    header.channels().insert(channel.name, Imf::Channel(Imf::FLOAT));
    // OpenEXR's Slice takes a mutable pointer for both directions; writing only reads it.
    char* base = reinterpret_cast<char*>(const_cast<float*>(channel.values.data()));
    frameBuffer.insert(channel.name, Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                                sizeof(float) * static_cast<std::size_t>(width)));
  }
  try {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frameBuffer);
    file.writePixels(height);
  } catch (const std::exception& error) {
    throw OutputError(path.string() + ": cannot write EXR: " + error.what());
  }
}

void WriteUintExr(const std::filesystem::path& path, int width, int height,
                  std::span<const std::string> channelNames, int stripRows,
                  const UintExrStripFill& fill) {
  const std::size_t rowValues = PixelCount(width, height) / static_cast<std::size_t>(height);
  if (stripRows < 1) throw std::invalid_argument("WriteUintExr: strips need at least one row");
  Imf::Header header(width, height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const std::string& name : channelNames) header.channels().insert(name, Imf::Channel(Imf::UINT));
  auto fail = [&](const std::exception& error) {
    return OutputError(path.string() + ": cannot write EXR: " + error.what());
  };
  std::optional<Imf::OutputFile> file;
  try {
    file.emplace(path.c_str(), header);
  } catch (const std::exception& error) {
    throw fail(error);
  }
  std::vector<std::vector<std::uint32_t>> strip(channelNames.size());
  const std::size_t yStride = sizeof(std::uint32_t) * rowValues;
  for (int firstRow = 0; firstRow < height; firstRow += stripRows) {
    const int rows = std::min(stripRows, height - firstRow);
    for (std::vector<std::uint32_t>& channel : strip) channel.assign(rowValues * rows, 0u);
    fill(firstRow, rows, strip);
    Imf::FrameBuffer frameBuffer;
    for (std::size_t c = 0; c < strip.size(); ++c) {
      if (strip[c].size() != rowValues * rows) {
        throw std::invalid_argument("WriteUintExr: channel " + channelNames[c] + " does not match the strip");
      }
      // OpenEXR addresses pixel (x, y) as base + x * xStride + y * yStride with y counted from
      // the top of the image, so the strip's base lies firstRow rows before its data; integer
      // arithmetic keeps that out-of-array address from being formed as a pointer offset.
      const std::uintptr_t data = reinterpret_cast<std::uintptr_t>(strip[c].data());
      char* base = reinterpret_cast<char*>(data - static_cast<std::uintptr_t>(firstRow) * yStride);
      frameBuffer.insert(channelNames[c], Imf::Slice(Imf::UINT, base, sizeof(std::uint32_t), yStride));
    }
    try {
      file->setFrameBuffer(frameBuffer);
      file->writePixels(rows);
    } catch (const std::exception& error) {
      throw fail(error);
    }
  }
}

}  // namespace cli
