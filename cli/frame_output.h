#pragma once
// Images of a rendered frame shared by `aasim frame` and `aasim run`: sRGB previews of linear
// colour, 0/1 masks, and frame.exr with the frame pipeline's pixel targets as named layers.

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "passes/pass.h"
#include "sim/frame.h"

namespace cli {

// 8-bit sRGB RGB of linear RGBA texels (alpha dropped).
std::vector<std::uint8_t> SrgbImage(std::span<const glm::vec4> texels);
// What an 8-bit sRGB render target (RGBA8Srgb) holds: RGB sRGB-encoded, alpha linear UNORM.
std::vector<std::uint8_t> SrgbAlphaImage(std::span<const glm::vec4> texels);
// 8-bit grey of a 0/1 mask: black and white come out exactly.
std::vector<std::uint8_t> MaskImage(std::span<const float> mask);

// A pass layer as a PNG: values in [0, 1] scaled linearly to 8 bits, round(v * 255), the texel
// codes an 8-bit UNORM target holds (layers are data such as edges and weights, not colour);
// 1 channel as grey, 2 as red/green (blue 0), 3 as RGB, 4 as RGBA.
void WriteLayerPng(const std::filesystem::path& path, const passes::PassLayer& layer);
// The PNG of WriteLayerPng: its channel count (one or two channels become grey or RGB with blue
// 0) and its bytes.
struct LayerPng {
  int channels = 0;
  std::vector<std::uint8_t> pixels;
};
LayerPng LayerPngImage(const passes::PassLayer& layer);
// The layer's float values, one EXR channel per layer channel under its name.
void WriteLayerExr(const std::filesystem::path& path, const passes::PassLayer& layer);

// Channels R, G, B (resolved colour), depth, normal.X/Y/Z, objectId (-1 for the background),
// velocity.X/Y. Throws OutputError naming the path.
void WriteFrameExr(const std::filesystem::path& path, const sim::FramePipeline& pipeline);

}  // namespace cli
