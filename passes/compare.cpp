// The strategy-identity rule (see compare.h).

#include "passes/compare.h"

namespace passes {
namespace {

ImageDifference LayerDifference(const PassLayer& a, const PassLayer& b) {
  ImageDifference difference;
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
    return {.pixels = static_cast<std::uint64_t>(a.width) * static_cast<std::uint64_t>(a.height)};
  }
  // Bit for bit: two 8-bit layers by their codes, anything else by its float values.
  const bool codes = a.codeChannels != 0 && a.codeChannels == b.codeChannels;
  const std::size_t channels = a.channels.size();
  const auto same = [&](std::size_t pixel) {
    if (codes) {
      const auto stride = static_cast<std::size_t>(a.codeChannels);
      return std::memcmp(&a.codes[pixel * stride], &b.codes[pixel * stride], stride) == 0;
    }
    for (std::size_t c = 0; c < channels; ++c) {
      const float left = a.Value(pixel * channels + c), right = b.Value(pixel * channels + c);
      if (std::memcmp(&left, &right, sizeof(float)) != 0) return false;
    }
    return true;
  };
  for (std::size_t pixel = 0; pixel * channels < a.Size(); ++pixel) {
    if (same(pixel)) continue;
    if (difference.pixels++ == 0) {
      difference.x = static_cast<int>(pixel % static_cast<std::size_t>(a.width));
      difference.y = static_cast<int>(pixel / static_cast<std::size_t>(a.width));
    }
  }
  return difference;
}

}  // namespace

std::string StrategyDifference::Describe() const {
  if (Identical()) return "identical";
  if (what == "work items") return "work-set sizes differ";
  return what + " differs in " + std::to_string(pixels.pixels) + " pixels, first at (" + std::to_string(pixels.x) +
         ", " + std::to_string(pixels.y) + ")";
}

StrategyDifference CompareOutputs(const PassOutput& first, const PassOutput& other) {
  const ImageDifference colour = BitwiseDifference(first.colour, other.colour);
  if (colour.pixels > 0) return {"output", colour};
  if (first.layers.size() != other.layers.size()) return {"layers", {}};
  for (std::size_t i = 0; i < first.layers.size(); ++i) {
    const ImageDifference layer = LayerDifference(first.layers[i], other.layers[i]);
    if (layer.pixels > 0 || first.layers[i].name != other.layers[i].name) return {first.layers[i].name, layer};
  }
  if (first.workItems != other.workItems) return {"work items", {}};
  return {};
}

}  // namespace passes
