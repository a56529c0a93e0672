#pragma once
// Images of a rendered frame shared by `aasim frame` and `aasim run`: sRGB previews of linear
// colour, 0/1 masks, and frame.exr with the frame pipeline's pixel targets as named layers.

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "sim/frame.h"

namespace cli {

// 8-bit sRGB RGB of linear RGBA texels (alpha dropped).
std::vector<std::uint8_t> SrgbImage(std::span<const glm::vec4> texels);
// 8-bit grey of a 0/1 mask: black and white come out exactly.
std::vector<std::uint8_t> MaskImage(std::span<const float> mask);

// Channels R, G, B (resolved colour), depth, normal.X/Y/Z, objectId (-1 for the background),
// velocity.X/Y. Throws OutputError naming the path.
void WriteFrameExr(const std::filesystem::path& path, const sim::FramePipeline& pipeline);

}  // namespace cli
