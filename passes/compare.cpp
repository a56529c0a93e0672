// The strategy-identity rule (see compare.h).

#include "passes/compare.h"

namespace passes {
namespace {

ImageDifference LayerDifference(const PassLayer& a, const PassLayer& b) {
  ImageDifference difference;
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
    return {.pixels = static_cast<std::uint64_t>(a.width) * static_cast<std::uint64_t>(a.height)};
  }
  const std::size_t channels = a.channels.size();
  for (std::size_t pixel = 0; pixel * channels < a.values.size(); ++pixel) {
    if (std::memcmp(&a.values[pixel * channels], &b.values[pixel * channels], channels * sizeof(float)) == 0) continue;
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
